"""Incremental store of sweep points: one HDF5 file written point by point.

Layout (``format = "rotorsim.sweep"``, ``version = 1``)::

    /                   attrs: format, version, fingerprint, definition (JSON), kind,
                               shape (JSON, grids), last_run (JSON: options and stats)
    /parameters/names   (n_params,) str
    /parameters/values  (n_points, n_params) float64
    /points/done        (n_points,) bool      True once the point is stored (OK or failed)
    /points/status      (n_points,) int8      rotorsim.errors.Status (3 = SKIPPED: not run)
    /points/message     (n_points,) str       failure message, empty when OK
    /points/wall_time   (n_points,) float64   seconds spent on the point
    /outputs/<name>     (n_points, ...)       float64 or complex128, NaN until written

The file is created complete (temporary file, then rename). Each point writes its
outputs, status, message and time, then sets ``done`` last and flushes the file, so a
process killed between points leaves every finished point readable; a point whose
``done`` flag is not set is simply evaluated again on resume. Output datasets are
created when the first point succeeds, from the names and shapes it returns.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError, Status
from rotorsim.io.atomic_file import write_atomically
from rotorsim.results.sweep import FloatArray, ParameterSpace, PointRecord, SweepResult

FORMAT = "rotorsim.sweep"
VERSION = 1


# ---------------------------------------------------------------------------- identity
def content_hash(obj: Any) -> str:
    """Hash of the content of a model object (dataclasses, arrays, numbers, strings).

    Numbers hash by value (``1`` and ``1.0`` alike); dataclasses by their ``init`` fields,
    so cached or derived attributes do not matter.

    Examples
    --------
    >>> content_hash({"k": 1}) == content_hash({"k": 1.0}) != content_hash({"k": 2.0})
    True
    """
    digest = hashlib.sha256()
    _feed(digest, obj)
    return digest.hexdigest()[:32]


def _feed(digest: Any, obj: Any) -> None:
    put = digest.update
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        put(f"<{type(obj).__qualname__}>".encode())
        for f in dataclasses.fields(obj):
            if f.init:
                put(f.name.encode())
                _feed(digest, getattr(obj, f.name))
    elif isinstance(obj, np.ndarray):
        arr = np.ascontiguousarray(obj.astype(float) if obj.dtype.kind in "biuf" else obj)
        put(f"array{arr.dtype}{arr.shape}".encode())
        put(arr.tobytes() if arr.dtype.kind != "O" else repr(arr.tolist()).encode())
    elif isinstance(obj, bool | np.bool_ | str | None):
        put(repr(obj).encode())
    elif isinstance(obj, int | float | np.integer | np.floating):
        put(float(obj).hex().encode())
    elif isinstance(obj, Mapping):
        put(b"{")
        for key in sorted(obj, key=str):
            put(str(key).encode())
            _feed(digest, obj[key])
        put(b"}")
    elif isinstance(obj, list | tuple):
        put(f"[{len(obj)}".encode())
        for item in obj:
            _feed(digest, item)
    else:
        put(repr(obj).encode())


def describe_callable(fn: Callable[..., Any] | None) -> str:
    """Stable text naming a function: ``module.qualname``, with the arguments bound by
    :func:`functools.partial` (numbers and strings by value, objects by content hash).

    Examples
    --------
    >>> describe_callable(functools.partial(round, ndigits=2))
    'builtins.round(ndigits=2)'
    """
    if fn is None:
        return "none"
    if isinstance(fn, functools.partial):
        args = [_describe_argument(a) for a in fn.args]
        args += [f"{k}={_describe_argument(v)}" for k, v in sorted(fn.keywords.items())]
        return f"{describe_callable(fn.func)}({', '.join(args)})"
    module = getattr(fn, "__module__", None) or type(fn).__module__
    name = getattr(fn, "__qualname__", None) or type(fn).__qualname__
    return f"{module}.{name}"


def _describe_argument(value: Any) -> str:
    if isinstance(value, bool | int | float | str | None):
        return repr(value)
    if isinstance(value, list | tuple):
        return "(" + ", ".join(_describe_argument(v) for v in value) + ")"
    if callable(value) and not dataclasses.is_dataclass(value):
        return describe_callable(value)
    return f"<{type(value).__qualname__} {content_hash(value)}>"


@dataclass(frozen=True, eq=False)
class StoreHeader:
    """What a store holds: the parameter space and the JSON definition of the sweep."""

    space: ParameterSpace
    definition: dict[str, Any]

    @cached_property
    def definition_json(self) -> str:
        return json.dumps({"space": self.space.describe(), **self.definition}, sort_keys=True)

    @cached_property
    def fingerprint(self) -> str:
        digest = hashlib.sha256(self.definition_json.encode())
        digest.update(np.ascontiguousarray(self.space.values).tobytes())
        return digest.hexdigest()[:32]


# ---------------------------------------------------------------------------- outputs
def _normalise(outputs: Mapping[str, Any], index: int) -> dict[str, NDArray[Any]]:
    if not isinstance(outputs, Mapping) or not outputs:
        raise ModelError(f"evaluate must return a non-empty dict name -> value, got"
                         f" {outputs!r} at point {index}", "sweep")
    arrays = {}
    for name, value in outputs.items():
        if not isinstance(name, str) or not name or "/" in name:
            raise ModelError(f"output names must be non-empty strings without '/', got"
                             f" {name!r}", "sweep")
        arr = np.asarray(value)
        if arr.dtype.kind in "biuf":
            arr = arr.astype(np.float64)
        elif arr.dtype.kind == "c":
            arr = arr.astype(np.complex128)
        else:
            raise ModelError(f"output {name!r} at point {index} is not numeric"
                             f" (dtype {arr.dtype})", "sweep")
        arrays[name] = arr
    return arrays


def _check_spec(arrays: Mapping[str, NDArray[Any]], spec: Mapping[str, tuple[Any, ...]],
                index: int) -> None:
    """Raise unless the outputs have the names, shapes and kinds of the earlier points."""
    got = {k: (v.shape, v.dtype.kind) for k, v in arrays.items()}
    if got != dict(spec):
        raise ModelError(
            f"point {index} returned outputs {got}, earlier points {dict(spec)}: evaluate"
            " must return the same names with fixed shapes (pad with NaN)", "sweep")


class MemoryStore:
    """Store kept in memory (``sweep(..., store=None)``)."""

    def __init__(self, header: StoreHeader) -> None:
        n = header.space.n_points
        self.header = header
        self.done = np.zeros(n, dtype=bool)
        self.status = np.full(n, int(Status.SKIPPED), dtype=np.int64)
        self.messages = [""] * n
        self.wall_time = np.zeros(n)
        self.outputs: dict[str, NDArray[Any]] = {}

    def write(self, record: PointRecord) -> None:
        """Store one point."""
        i = record.index
        if record.outputs is not None:
            arrays = _normalise(record.outputs, i)
            if not self.outputs:
                self.outputs = {k: np.full((self.done.size, *v.shape), np.nan, dtype=v.dtype)
                                for k, v in arrays.items()}
            _check_spec(arrays, {k: (v.shape[1:], v.dtype.kind)
                                 for k, v in self.outputs.items()}, i)
            for name, value in arrays.items():
                self.outputs[name][i] = value
        self.status[i] = int(record.status)
        self.messages[i] = record.message
        self.wall_time[i] = record.wall_time
        self.done[i] = True

    def finish(self, options: dict[str, Any], stats: dict[str, float]) -> SweepResult:
        """The result of everything stored so far."""
        space = self.header.space
        return _result(space.kind, space.names, np.asarray(space.values), space.shape,
                       dict(self.outputs), self.status.copy(), tuple(self.messages),
                       self.wall_time.copy(), self.header.fingerprint,
                       json.loads(self.header.definition_json), options, stats)

    def close(self) -> None:
        """Nothing to release."""


class HDF5Store:
    """Store written to an HDF5 file point by point (see the module docstring)."""

    def __init__(self, path: Path, header: StoreHeader) -> None:
        import h5py

        self.path = path
        self.header = header
        self.file = h5py.File(path, "r+")
        self.done = np.asarray(self.file["points/done"][...], dtype=bool)

    @classmethod
    def create(cls, path: str | os.PathLike[str], header: StoreHeader) -> HDF5Store:
        """Create a new store (replacing any file at ``path``) for ``header``."""
        import h5py

        space, n = header.space, header.space.n_points

        def write(f: h5py.File) -> None:
            f.attrs.update({"format": FORMAT, "version": VERSION, "kind": space.kind,
                            "fingerprint": header.fingerprint,
                            "definition": header.definition_json,
                            "shape": json.dumps(space.shape)})
            params = f.create_group("parameters")
            params.create_dataset("names", data=list(space.names), dtype=h5py.string_dtype())
            params.create_dataset("values", data=np.asarray(space.values))
            points = f.create_group("points")
            points.create_dataset("done", data=np.zeros(n, dtype=bool))
            points.create_dataset("status", data=np.full(n, int(Status.SKIPPED), np.int8))
            points.create_dataset("message", data=[""] * n, dtype=h5py.string_dtype())
            points.create_dataset("wall_time", data=np.zeros(n))
            f.create_group("outputs")

        path = write_atomically(Path(path), write, "sweep store")
        return cls(path, header)

    @classmethod
    def resume(cls, path: str | os.PathLike[str], header: StoreHeader) -> HDF5Store:
        """Open an existing store after checking it was written by the same sweep."""
        path = Path(path)
        stored = _read_attrs(path)
        if stored["fingerprint"] != header.fingerprint:
            new = json.loads(header.definition_json)
            old = json.loads(stored["definition"])
            differ = sorted(k for k in set(new) | set(old) if new.get(k) != old.get(k))
            raise ModelError(
                f"the store holds a different sweep ({', '.join(differ) or 'parameter values'}"
                " differ); use another store path, or resume=False to start over", str(path))
        return cls(path, header)

    def write(self, record: PointRecord) -> None:
        """Store one point, set its ``done`` flag last and flush the file."""
        i = record.index
        if record.outputs is not None:
            arrays = _normalise(record.outputs, i)
            group = self.file["outputs"]
            if len(group) == 0:
                for name, value in arrays.items():
                    group.create_dataset(name, shape=(self.done.size, *value.shape),
                                         dtype=value.dtype, chunks=True,
                                         fillvalue=np.full((), np.nan, value.dtype))
            _check_spec(arrays, {k: (d.shape[1:], d.dtype.kind) for k, d in group.items()}, i)
            for name, value in arrays.items():
                group[name][i] = value
        points = self.file["points"]
        points["status"][i] = int(record.status)
        points["message"][i] = record.message
        points["wall_time"][i] = record.wall_time
        points["done"][i] = True
        self.file.flush()
        self.done[i] = True

    def finish(self, options: dict[str, Any], stats: dict[str, float]) -> SweepResult:
        """Record the run's options and stats, and read the whole store back."""
        self.file.attrs["last_run"] = json.dumps({"options": options, "stats": stats},
                                                 default=str)
        self.file.flush()
        return _read(self.file)

    def close(self) -> None:
        """Close the file (idempotent)."""
        if self.file.id.valid:
            self.file.close()


def open_store(path: str | os.PathLike[str] | None, header: StoreHeader,
               resume: bool) -> MemoryStore | HDF5Store:
    """In-memory store (``path=None``), a resumed store, or a new store at ``path``."""
    if path is None:
        return MemoryStore(header)
    if resume and Path(path).exists():
        return HDF5Store.resume(path, header)
    return HDF5Store.create(path, header)


def load_sweep(path: str | os.PathLike[str]) -> SweepResult:
    """Read a sweep store, finished or not (points not run have status ``SKIPPED``).

    Parameters
    ----------
    path : str or path
        The ``.h5`` file written by :func:`rotorsim.analyses.sweep.sweep.sweep`.
    """
    import h5py

    _read_attrs(Path(path))
    with h5py.File(path, "r") as f:
        return _read(f)


def _read_attrs(path: Path) -> dict[str, Any]:
    import h5py

    try:
        with h5py.File(path, "r") as f:
            attrs = dict(f.attrs)
    except OSError as exc:
        raise ModelError(f"cannot read as HDF5: {exc}", str(path)) from exc
    if attrs.get("format") != FORMAT:
        raise ModelError(f"not a rotorsim sweep store (format {attrs.get('format')!r})",
                         str(path))
    if int(attrs.get("version", -1)) != VERSION:
        raise ModelError(f"sweep store version {attrs.get('version')} is not supported"
                         f" (this rotorsim reads version {VERSION})", str(path))
    return attrs


def _read(f: Any) -> SweepResult:
    shape = json.loads(f.attrs["shape"])
    last = json.loads(f.attrs.get("last_run", '{"options": {}, "stats": {}}'))
    points = f["points"]
    return _result(
        str(f.attrs["kind"]), tuple(f["parameters/names"].asstr()[...].tolist()),
        f["parameters/values"][...], None if shape is None else tuple(shape),
        {k: d[...] for k, d in f["outputs"].items()},
        points["status"][...].astype(np.int64),
        tuple(points["message"].asstr()[...].tolist()), points["wall_time"][...],
        str(f.attrs["fingerprint"]), json.loads(f.attrs["definition"]),
        last["options"], last["stats"])


def _result(kind: str, names: tuple[str, ...], values: FloatArray,
            shape: tuple[int, ...] | None, outputs: dict[str, NDArray[Any]],
            status: NDArray[np.int64], messages: tuple[str, ...], wall_time: FloatArray,
            fingerprint: str, definition: dict[str, Any], options: dict[str, Any],
            stats: dict[str, float]) -> SweepResult:
    overall = Status(int(status.max())) if status.size else Status.OK
    return SweepResult(
        kind=kind, names=names, values=values, shape=shape, outputs=outputs,
        point_status=status, messages=messages, point_time=wall_time,
        fingerprint=fingerprint, options=options, stats=stats, status=overall,
        summary=dict(definition.get("rotor_summary", {})),
    )
