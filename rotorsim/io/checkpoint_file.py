"""Checkpoint files of long runs: a run's state, written atomically to HDF5 and read back.

The numerics (:mod:`rotorsim.time_integration.checkpoint`,
:mod:`rotorsim.solvers.continuation_checkpoint`) never import h5py: they describe their
state as plain *content* and hand it to a :class:`CheckpointFiles`, by default
:data:`HDF5_CHECKPOINTS`, which writes it and reads it back.

Layout of every checkpoint::

    /            attrs: format, format_version, created (ISO 8601, UTC),
                        config (JSON with sorted keys: the identity of the run)
    /<group>     one group per entry of the content, with its attributes, datasets and
                 subgroups

Content is a mapping of group names to :class:`GroupContent` dicts: ``attrs`` (numbers, bools
and strings, stored as HDF5 attributes), ``datasets`` (numpy arrays; a name ``"a/b"``
creates the subgroup ``a``) and ``groups`` (nested GroupContent). Values are stored as given
(the caller picks the dtypes), so a resumed run continues bit for bit.

Read back, a group is a read-only mapping over its attributes, datasets and subgroups
together; a missing entry raises :class:`~rotorsim.errors.CheckpointError` naming it, and
every error names the file. h5py is imported when a file is read or written.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterator, Mapping
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol, TypedDict, TypeVar

from numpy.typing import NDArray

from rotorsim.errors import CheckpointError
from rotorsim.io.atomic_file import write_atomically

if TYPE_CHECKING:
    import h5py

__all__ = ["HDF5_CHECKPOINTS", "CheckpointFiles", "GroupContent", "HDF5Checkpoints",
           "StoredGroup", "compare_config", "file_format"]

T = TypeVar("T")


class GroupContent(TypedDict, total=False):
    """One group of a checkpoint as the numerics hand it over."""

    attrs: Mapping[str, Any]
    datasets: Mapping[str, NDArray[Any]]
    groups: Mapping[str, GroupContent]


Decode = Callable[[Mapping[str, Any], dict[str, Any]], T]
"""``decode(content, stored_config)``: the numerics' state from the content read back."""


class CheckpointFiles(Protocol):
    """Where the numerics write their checkpoints and read them back."""

    def write(self, path: str | os.PathLike[str], fmt: str, version: int,
              config: Mapping[str, Any], content: Mapping[str, GroupContent]) -> Path:
        """Store ``content`` at ``path`` (replacing it) with the header ``fmt``,
        ``version`` and ``config``."""
        ...

    def read(self, path: str | os.PathLike[str], fmt: str, version: int,
             decode: Decode[T], config: Mapping[str, Any] | None = None,
             ) -> tuple[T, dict[str, Any]]:
        """``(decode(content, stored config), stored config)`` after checking the header
        and, when given, that ``config`` equals the stored one."""
        ...


class HDF5Checkpoints:
    """Checkpoints as HDF5 files written atomically (the layout in the module docstring).

    Examples
    --------
    >>> import tempfile, numpy as np
    >>> content = {"state": {"attrs": {"t": 1.5}, "datasets": {"q": np.ones(2)},
    ...                      "groups": {"counters": {"attrs": {"steps": 3}}}}}
    >>> def decode(stored, config):
    ...     state = stored["state"]
    ...     return float(state["t"]), state["q"].tolist(), int(state["counters"]["steps"])
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = HDF5_CHECKPOINTS.write(Path(folder) / "run.h5", "demo", 1, {"n": 2}, content)
    ...     HDF5_CHECKPOINTS.read(path, "demo", 1, decode, config={"n": 2})
    ((1.5, [1.0, 1.0], 3), {'n': 2})
    """

    def write(self, path: str | os.PathLike[str], fmt: str, version: int,
              config: Mapping[str, Any], content: Mapping[str, GroupContent]) -> Path:
        """Write the checkpoint atomically; its folder is created when missing.

        Raises
        ------
        ModelError
            When the folder cannot be created.
        """
        def write(f: h5py.File) -> None:
            f.attrs["format"] = fmt
            f.attrs["format_version"] = version
            f.attrs["created"] = datetime.now(UTC).isoformat(timespec="seconds")
            f.attrs["config"] = json.dumps(config, sort_keys=True)
            for name, group in content.items():
                _write_group(f.create_group(name), group)

        return write_atomically(Path(path), write, "checkpoint")

    def read(self, path: str | os.PathLike[str], fmt: str, version: int,
             decode: Decode[T], config: Mapping[str, Any] | None = None,
             ) -> tuple[T, dict[str, Any]]:
        """Read the checkpoint at ``path`` and decode it.

        Raises
        ------
        FileNotFoundError
            If ``path`` does not exist.
        CheckpointError
            If the file is not readable HDF5, not a ``fmt`` file of ``version``, was written
            by a run with another ``config`` (the differing entries are listed), or is
            incomplete or corrupted (the missing entry is named); also any CheckpointError
            of ``decode``. The message names the file.
        """
        import h5py

        source = Path(path)
        if not source.is_file():
            raise FileNotFoundError(f"no such checkpoint: {source}")
        try:
            handle = h5py.File(source, "r")
        except OSError as exc:
            raise CheckpointError(f"not a readable HDF5 file ({exc})", str(source)) from exc
        try:
            with handle as f:
                stored = _read_header(f, fmt, version)
                if config is not None:
                    compare_config(stored, json.loads(json.dumps(config, sort_keys=True)))
                content = _read_group(f, "")
            return decode(content, stored), stored
        except CheckpointError as exc:
            raise CheckpointError(str(exc), str(source)) from exc
        except (KeyError, OSError, TypeError, ValueError) as exc:
            raise CheckpointError(f"corrupted or incomplete ({type(exc).__name__}: {exc})",
                                  str(source)) from exc


HDF5_CHECKPOINTS = HDF5Checkpoints()
"""The checkpoint files of ``integrate``, ``continue_branch``, ``rs.transient`` and
``rs.periodic``."""


class StoredGroup(Mapping[str, Any]):
    """A group read from a checkpoint: attributes (str for strings), datasets (arrays) and
    subgroups (StoredGroup) by name; a missing name raises CheckpointError naming it."""

    def __init__(self, name: str, items: dict[str, Any]) -> None:
        self.name = name
        self._items = items

    def __getitem__(self, key: str) -> Any:
        try:
            return self._items[key]
        except KeyError:
            raise CheckpointError(f"corrupted or incomplete: '{self.name}/{key}' is "
                                  "missing") from None

    def __contains__(self, key: object) -> bool:
        return key in self._items

    def get(self, key: str, default: Any = None) -> Any:
        """The entry ``key``, or ``default`` when it is missing."""
        return self._items.get(key, default)

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)


def compare_config(stored: Mapping[str, Any], current: Mapping[str, Any]) -> None:
    """Refuse a checkpoint written by another run (the differing keys in the message).

    Raises
    ------
    CheckpointError
        When the two configurations differ.
    """
    differ = sorted(k for k in set(stored) | set(current) if stored.get(k) != current.get(k))
    if differ:
        details = "; ".join(f"{k}: checkpoint {_short(stored.get(k))}, this run "
                            f"{_short(current.get(k))}" for k in differ)
        raise CheckpointError(f"written by a different run ({details})")


def file_format(path: str | os.PathLike[str]) -> str | None:
    """The root attribute ``format`` of an HDF5 file (``"rotorsim-checkpoint"``,
    ``"rotorsim-results"``, ...), None when ``path`` is not a readable HDF5 file or has none.
    """
    import h5py

    source = Path(path)
    if not source.is_file():
        return None
    try:
        with h5py.File(source, "r") as f:
            fmt = f.attrs.get("format")
    except OSError:
        return None
    return _text(fmt) if fmt is not None else None


def _write_group(group: h5py.Group, content: GroupContent) -> None:
    for name, value in content.get("attrs", {}).items():
        group.attrs[name] = value
    for name, array in content.get("datasets", {}).items():
        group.create_dataset(name, data=array)
    for name, sub in content.get("groups", {}).items():
        _write_group(group.create_group(name), sub)


def _read_group(group: h5py.Group, name: str) -> StoredGroup:
    import h5py

    items: dict[str, Any] = {key: _text(value) for key, value in group.attrs.items()}
    for key, obj in group.items():
        items[key] = (_read_group(obj, f"{name}/{key}") if isinstance(obj, h5py.Group)
                      else obj[()])
    return StoredGroup(name, items)


def _read_header(f: h5py.File, fmt_expected: str, version_expected: int) -> dict[str, Any]:
    """The stored run configuration, after checking the format name and version."""
    fmt = f.attrs.get("format")
    fmt = fmt.decode() if isinstance(fmt, bytes) else fmt
    if fmt != fmt_expected:
        raise CheckpointError(f"not a {fmt_expected} file (format {fmt!r})")
    version = f.attrs.get("format_version")
    version = version.item() if hasattr(version, "item") else version  # numpy scalar
    if version is None or int(version) != version_expected:
        raise CheckpointError(f"format_version {version!r} is not supported; this rotorsim "
                              f"reads version {version_expected}")
    stored = json.loads(f.attrs["config"])
    if not isinstance(stored, dict):
        raise CheckpointError("config attribute is not a JSON object")
    return stored


def _text(value: Any) -> Any:
    return value.decode() if isinstance(value, bytes) else value


def _short(value: Any) -> str:
    text = json.dumps(value, sort_keys=True)
    return text if len(text) <= 120 else text[:117] + "..."
