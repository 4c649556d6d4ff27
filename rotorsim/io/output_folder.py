"""Output files go where the user points, creating missing folders (as the CLI does for its
results folder); a file standing where a folder is needed is a one-line error."""

from __future__ import annotations

from pathlib import Path

from rotorsim.errors import ModelError


def prepare_folder(target: Path, where: str) -> None:
    """Create the folder of the file ``target`` and its parents when missing.

    Raises
    ------
    ModelError
        When the folder cannot be created (a file of that name exists, no permission).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as root:
    ...     prepare_folder(Path(root) / "a" / "b" / "out.h5", "save")
    ...     (Path(root) / "a" / "b").is_dir()
    True
    """
    folder = target.parent
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise ModelError(f"cannot create the folder {folder}: a file of that name is in the "
                         "way", where) from None
    except OSError as err:
        raise ModelError(f"cannot create the folder {folder}: {err.strerror or err}",
                         where) from None
