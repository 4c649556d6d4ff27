"""Save and load results as HDF5 files (versioned layout, atomic writes).

File layout (``format_version`` 1; full description in ``docs/results_format.md``)::

    /                    attrs: format = "rotorsim-results", format_version = 1,
                                rotorsim_version, created (ISO 8601, UTC),
                                layout = "single" | "collection"
    /result              one result (layout "single"): attr type = class name, ...
    /results/<name>      several results (layout "collection"), in the order given

Each result group is written by :func:`rotorsim.io.serialize.write_result`: arrays as
datasets with a ``units`` attribute, scalars as attributes, dicts as tagged JSON,
nested dataclasses and the :class:`~rotorsim.assembly.dof_map.DofMap` as subgroups.

h5py is imported when a file is read or written, not with this module.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import rotorsim.io.result_types  # noqa: F401  (registers every result type)
from rotorsim.io.atomic_file import write_atomically
from rotorsim.io.serialize import ResultsFileError, read_result, result_type, write_result

if TYPE_CHECKING:
    import h5py

__all__ = ["FORMAT", "FORMAT_VERSION", "ResultsFileError", "load", "save"]

SWEEP_FORMAT = "rotorsim.sweep"
"""Root ``format`` of a sweep store (:mod:`rotorsim.io.sweep_store`), also read by :func:`load`."""
FORMAT = "rotorsim-results"
"""Value of the root attribute ``format`` of every results file."""

FORMAT_VERSION = 1
"""Layout version written by this rotorsim; :func:`load` reads exactly this version."""


def save(result: object | Mapping[str, object], path: str | os.PathLike[str]) -> Path:
    """Write one result, or a ``{name: result}`` mapping, to the HDF5 file ``path``.

    The file is written to a temporary file in the same folder and renamed onto ``path``
    only when complete, so an interrupted save leaves any previous file untouched.

    Parameters
    ----------
    result : result dataclass or mapping of str to result
        Any registered type (:data:`rotorsim.io.serialize.RESULT_TYPES`): ModalResult,
        CampbellResult, CriticalSpeeds, CriticalSpeedMapResult, FrequencyResponseResult,
        StaticResult, ... A mapping is stored as ``/results/<name>`` groups.
    path : path-like
        Target file (usually ``*.h5``); missing folders are created. Overwritten if
        present.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    ResultsFileError
        If a result type or a value inside it cannot be stored (nothing is written).

    Examples
    --------
    >>> import tempfile, numpy as np
    >>> from rotorsim.results.orbits import ellipse
    >>> orbit = ellipse(np.array([1.0, 2.0]), np.array([-1j, 0.5]))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     out = save({"orbit": orbit}, Path(folder) / "orbit.h5")
    ...     back = load(out)["orbit"]
    >>> type(back).__name__, back.major.tolist() == orbit.major.tolist()
    ('Ellipse', True)
    """
    target = Path(path)
    if isinstance(result, Mapping):
        items = _checked_items(result)
        write_atomically(target, lambda f: _write_collection(f, items), "save")
    else:
        result_type(result)
        write_atomically(target, lambda f: _write_single(f, result), "save")
    return target


def load(path: str | os.PathLike[str]) -> Any:
    """Read a file written by :func:`save` (or a sweep store, see :func:`load_sweep`).

    Returns
    -------
    result or dict of str to result
        The result (same class, every field equal) for a single-result file; a dict in
        the saved order for a collection.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    ResultsFileError
        If the file is not HDF5, not a rotorsim results file, of another
        ``format_version``, or malformed; no partial data is returned.
    """
    import h5py

    source = Path(path)
    if not source.is_file():
        raise FileNotFoundError(f"no such results file: {source}")
    try:
        handle = h5py.File(source, "r")
    except OSError as exc:
        raise ResultsFileError("not an HDF5 file", str(source)) from exc
    with handle as f:
        is_sweep = f.attrs.get("format") == SWEEP_FORMAT
    if is_sweep:  # a sweep store: read it as a SweepResult
        from rotorsim.io.sweep_store import load_sweep

        return load_sweep(source)
    with h5py.File(source, "r") as f:
        layout = _check_header(f, source)
        try:
            if layout == "single":
                return read_result(_group(f, "result", source))
            group = _group(f, "results", source)
            return {name: read_result(group[name]) for name in group}
        except ResultsFileError as exc:
            raise ResultsFileError(str(exc), str(source)) from exc


def _checked_items(results: Mapping[str, object]) -> list[tuple[str, object]]:
    if not results:
        raise ResultsFileError("nothing to save: the mapping is empty", "save")
    for name, value in results.items():
        if not isinstance(name, str) or not name or "/" in name or name in (".", ".."):
            raise ResultsFileError(
                f"result names must be non-empty strings without '/', got {name!r}", "save")
        result_type(value)
    return list(results.items())


def _write_header(f: h5py.File, layout: str) -> None:
    import rotorsim

    f.attrs["format"] = FORMAT
    f.attrs["format_version"] = FORMAT_VERSION
    f.attrs["rotorsim_version"] = str(getattr(rotorsim, "__version__", "unknown"))
    f.attrs["created"] = datetime.now(UTC).isoformat(timespec="seconds")
    f.attrs["layout"] = layout


def _write_single(f: h5py.File, result: object) -> None:
    _write_header(f, "single")
    write_result(f.create_group("result"), result)


def _write_collection(f: h5py.File, items: list[tuple[str, object]]) -> None:
    _write_header(f, "collection")
    group = f.create_group("results", track_order=True)
    for name, result in items:
        write_result(group.create_group(name), result)


def _check_header(f: h5py.File, source: Path) -> str:
    """Validate the root attributes; return the layout."""
    where = str(source)
    fmt = f.attrs.get("format")
    if isinstance(fmt, bytes):
        fmt = fmt.decode()
    if fmt != FORMAT:
        raise ResultsFileError(
            f"not a rotorsim results file (root attribute 'format' is {fmt!r}, expected "
            f"{FORMAT!r})", where)
    version = f.attrs.get("format_version")
    try:
        supported = version is not None and int(version) == FORMAT_VERSION
    except (TypeError, ValueError):
        supported = False
    if not supported:
        shown = version.item() if hasattr(version, "item") else version  # numpy scalar
        raise ResultsFileError(
            f"format_version {shown!r} is not supported; this rotorsim reads version "
            f"{FORMAT_VERSION} (written by rotorsim {f.attrs.get('rotorsim_version', '?')!s})",
            where)
    layout = f.attrs.get("layout")
    if isinstance(layout, bytes):
        layout = layout.decode()
    if layout not in ("single", "collection"):
        raise ResultsFileError(f"unknown layout {layout!r}", where)
    return str(layout)


def _group(f: h5py.File, name: str, source: Path) -> h5py.Group:
    if name not in f:
        raise ResultsFileError(f"group '/{name}' missing", str(source))
    return f[name]
