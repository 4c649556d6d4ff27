"""Atomic HDF5 writes: a file is written under a temporary name beside its target and renamed
onto it when complete, so an interruption never leaves a half-written file and any previous
file stays untouched. Results files, sweep stores and checkpoints are all written this way.

h5py is imported when a file is written, not with this module.
"""

from __future__ import annotations

import os
import uuid
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from rotorsim.io.output_folder import prepare_folder

if TYPE_CHECKING:
    import h5py


def write_atomically(target: Path, write: Callable[[h5py.File], None], where: str) -> Path:
    """Run ``write`` on a new HDF5 file beside ``target`` and rename it onto ``target``.

    Parameters
    ----------
    target : Path
        File to create or replace; missing folders are created.
    write : callable
        ``write(f)`` fills the open, empty ``h5py.File``.
    where : str
        Who writes (``"save"``, ``"checkpoint"``, ...), named in a folder error.

    Returns
    -------
    Path
        ``target``.

    Raises
    ------
    ModelError
        When the folder of ``target`` cannot be created.

    Examples
    --------
    >>> import tempfile, h5py
    >>> with tempfile.TemporaryDirectory() as root:
    ...     path = write_atomically(Path(root) / "a" / "x.h5",
    ...                             lambda f: f.attrs.__setitem__("n", 3), "example")
    ...     with h5py.File(path) as f:
    ...         print(int(f.attrs["n"]), sorted(p.name for p in path.parent.iterdir()))
    3 ['x.h5']
    """
    import h5py

    prepare_folder(target, where)
    temp = target.with_name(f".{target.name}.{uuid.uuid4().hex}.tmp")
    try:
        with h5py.File(temp, "x") as f:
            write(f)
        with open(temp, "rb+") as raw:  # the data are on disk before the rename
            os.fsync(raw.fileno())
        os.replace(temp, target)
    except BaseException:
        temp.unlink(missing_ok=True)
        raise
    return target
