"""Mapping between result dataclasses and HDF5 groups (layout version 1).

A result is written into one HDF5 group whose attr ``type`` names the dataclass
(:data:`RESULT_TYPES` maps it back). Every dataclass field, ``init=False`` ones included,
becomes one entry whose *kind* is listed in the group attr ``fields``, a JSON object
``{field: kind}``: ``array`` (dataset with attrs ``numpy_dtype`` and ``units``; complex as
h5py's native ``(r, i)`` compound, str as UTF-8 variable-length strings), ``str_tuple``
(string dataset), ``group`` (nested dataclass, same layout), ``dofmap`` (subgroup with
attr ``n_nodes``, dataset ``fixed`` and the string dataset ``dof_labels``, ``"node 8 uy"``
for every global DOF), ``status`` (int attr), ``bool``/``int``/``float``/
``complex``/``str`` (Python scalar attr), ``numpy`` (numpy scalar attr, dtype kept),
``array_dict`` (a non-empty dict of str to arrays, e.g. ``TransientResult.reduced``:
subgroup ``<field>`` with one dataset per entry and attr ``keys``, their JSON-listed order),
``json`` (attr with the tagged JSON of :func:`to_jsonable`: ``options``, ``stats``,
``summary``, lists, other tuples) and ``none`` (nothing stored). Units of scalar attrs are
in the group attr ``attr_units`` (JSON ``{field: units}``). A result with an integer field
``dofs`` (kept global DOFs) also gets a string dataset ``dof_labels`` aligned with it.
``docs/results_format.md`` describes the layout in full.

``write_result``/``read_result`` work on any open h5py group, so a sweep can stream many
results into one file; :mod:`rotorsim.io.hdf5` adds the file header and atomic writes.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorsim.assembly.dof_map import DofMap, dof_label
from rotorsim.errors import ModelError, ResultsFileError, Status
from rotorsim.io.tagged_json import from_jsonable, plain_dtype, to_jsonable

if TYPE_CHECKING:
    import h5py

DOF_LABELS = "dof_labels"
"""Name of the string datasets that label DOFs ``"node 8 uy"`` (not a result field)."""
RESERVED_ATTRS = ("type", "fields", "attr_units")
"""Group attributes used by the layout itself; no result field may carry these names."""

_INT64 = np.iinfo(np.int64)
_SCALAR_KINDS = {bool: "bool", int: "int", float: "float", complex: "complex", str: "str"}
_PY_TYPES = {kind: t for t, kind in _SCALAR_KINDS.items()}


@dataclasses.dataclass(frozen=True)
class ResultType:
    """A registered result class and the units of its physical fields."""

    cls: type
    units: Mapping[str, str]


RESULT_TYPES: dict[str, ResultType] = {}
"""Registry ``class name -> ResultType`` used to rebuild results on load."""


def register_result_type(cls: type, units: Mapping[str, str] | None = None) -> type:
    """Make the dataclass ``cls`` storable; ``units`` maps field names to unit strings.

    Unit strings are SI as used in the docstrings (``"rad/s"``, ``"m"``, ``"N m"``);
    ``"1"`` is dimensionless and ``"m, rad"`` a per-DOF quantity with translations in m
    and rotations in rad. Returns ``cls`` so it can serve as a decorator.

    Examples
    --------
    >>> @dataclasses.dataclass(frozen=True)
    ... class Point:
    ...     z: float
    >>> register_result_type(Point, {"z": "m"}) is Point
    True
    >>> del RESULT_TYPES["Point"]
    """
    if not (isinstance(cls, type) and dataclasses.is_dataclass(cls)):
        raise ModelError(f"{cls!r} is not a dataclass", "register_result_type")
    names = {f.name for f in dataclasses.fields(cls)}
    clash = names.intersection(RESERVED_ATTRS)
    if clash:
        raise ModelError(f"field names {sorted(clash)} are reserved by the HDF5 layout",
                         cls.__name__)
    units = dict(units or {})
    unknown = set(units) - names
    if unknown:
        raise ModelError(f"units given for unknown fields {sorted(unknown)}", cls.__name__)
    RESULT_TYPES[cls.__name__] = ResultType(cls, units)
    return cls


def result_type(value: object) -> ResultType:
    """The registry entry of ``value``'s class; :class:`ResultsFileError` if not registered."""
    entry = RESULT_TYPES.get(type(value).__name__)
    if entry is None or entry.cls is not type(value):
        known = ", ".join(sorted(RESULT_TYPES))
        raise ResultsFileError(f"cannot store a {type(value).__name__}; storable types: {known}",
                               "save")
    return entry


# ---------------------------------------------------------------------------- writing
def write_result(group: h5py.Group, result: object) -> None:
    """Write the registered dataclass ``result`` into the empty h5py ``group``."""
    entry = result_type(result)
    group.attrs["type"] = type(result).__name__
    kinds: dict[str, str] = {}
    attr_units: dict[str, str] = {}
    for f in dataclasses.fields(result):  # type: ignore[arg-type]
        units = entry.units.get(f.name)
        where = f"{type(result).__name__}.{f.name}"
        kind = _write_field(group, f.name, getattr(result, f.name), units, where)
        kinds[f.name] = kind
        if units and kind in (*_PY_TYPES, "numpy"):
            attr_units[f.name] = units
    group.attrs["fields"] = json.dumps(kinds)
    group.attrs["attr_units"] = json.dumps(attr_units)
    _write_kept_labels(group, result, kinds)


def dof_labels(indices: Any, node_names: tuple[str, ...] = ()) -> np.ndarray:
    """``"node <n> <dof>"`` of each global DOF index (``6 * node + k``), for readers of the
    files that do not use rotorsim.

    Examples
    --------
    >>> dof_labels([0, 49]).tolist()
    ['node 0 ux', 'node 8 uy']
    """
    idx = np.asarray(indices, dtype=np.int64).reshape(-1)
    return np.array([dof_label(i, node_names=node_names) for i in idx], dtype=object)


def _write_kept_labels(group: h5py.Group, result: object, kinds: dict[str, str]) -> None:
    """Dataset ``dof_labels`` beside an integer field ``dofs`` of kept global DOF indices
    (the columns of ``q``, ``v`` of a transient, the rows of a periodic branch)."""
    if kinds.get("dofs") != "array" or "dofmap" not in kinds.values() or \
            DOF_LABELS in kinds:
        return
    dofs = np.asarray(result.dofs)  # type: ignore[attr-defined]
    if dofs.ndim == 1 and dofs.dtype.kind in "iu":
        names = next((v.node_names for v in vars(result).values() if isinstance(v, DofMap)),
                     ())
        _write_strings(group, DOF_LABELS, dof_labels(dofs, names))


def _write_field(group: h5py.Group, name: str, value: Any, units: str | None,
                 where: str) -> str:
    if value is None:
        return "none"
    if isinstance(value, DofMap):
        sub = group.create_group(name)
        sub.attrs["type"] = "DofMap"
        sub.attrs["n_nodes"] = int(value.n_nodes)
        sub.create_dataset("fixed", data=np.asarray(value.fixed, dtype=np.int64))
        _write_strings(sub, DOF_LABELS, dof_labels(np.arange(value.ndof), value.node_names))
        if value.node_names:
            _write_strings(sub, "node_names", np.array(value.node_names, dtype=object))
        return "dofmap"
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        write_result(group.create_group(name), value)
        return "group"
    if isinstance(value, np.ndarray):
        _write_array(group, name, value, units, where)
        return "array"
    if isinstance(value, Status):
        group.attrs[name] = int(value)
        return "status"
    if isinstance(value, np.generic) and value.dtype.kind in "biufc" and plain_dtype(value.dtype):
        group.attrs[name] = value
        return "numpy"
    kind = _SCALAR_KINDS.get(type(value))
    if kind is not None and _fits_attr(value):
        group.attrs[name] = value
        return kind
    if _is_array_dict(value):
        sub = group.create_group(name)
        sub.attrs["keys"] = json.dumps(list(value))
        for key, item in value.items():
            _write_array(sub, key, item, units, f"{where}[{key!r}]")
        return "array_dict"
    if type(value) is tuple and value and all(
            dataclasses.is_dataclass(v) and not isinstance(v, type) for v in value):
        sub = group.create_group(name)  # tuple of results: items "0", "1", ... in order
        sub.attrs["length"] = len(value)
        for i, item in enumerate(value):
            write_result(sub.create_group(str(i)), item)
        return "group_tuple"
    if type(value) is tuple and all(type(v) is str and "\0" not in v for v in value):
        _write_strings(group, name, np.array(value, dtype=object).reshape(len(value)))
        return "str_tuple"
    group.attrs[name] = json.dumps(to_jsonable(value, where), allow_nan=False)
    return "json"


def _is_array_dict(value: Any) -> bool:
    """A non-empty dict of arrays under plain names: stored as datasets, not as JSON (an
    HDF5 attribute holds at most 64 kB; a long run's reductions need more)."""
    return (type(value) is dict and bool(value) and all(
        type(k) is str and k and "/" not in k and k not in (".", "..")
        and isinstance(v, np.ndarray) for k, v in value.items()))


def _fits_attr(value: bool | int | float | complex | str) -> bool:
    """Python scalar that an HDF5 attribute holds exactly (int64, strings without NUL)."""
    if isinstance(value, str):
        return "\0" not in value
    return not isinstance(value, int) or _INT64.min <= value <= _INT64.max


def _write_array(group: h5py.Group, name: str, value: np.ndarray, units: str | None,
                 where: str) -> None:
    if value.dtype.kind == "U":
        if _has_interior_nul(value):
            raise ResultsFileError("cannot store strings containing NUL characters", where)
        ds = _write_strings(group, name, value.astype(object))
    elif value.dtype.kind == "S" or (value.dtype.kind in "biufc" and plain_dtype(value.dtype)):
        ds = group.create_dataset(name, data=value)
    else:
        raise ResultsFileError(f"cannot store an array of dtype {value.dtype}", where)
    ds.attrs["numpy_dtype"] = value.dtype.str
    if units:
        ds.attrs["units"] = units


def _has_interior_nul(value: np.ndarray) -> bool:
    """Whether a str array has a NUL before the end of some element (HDF5 would cut it)."""
    width = value.dtype.itemsize // 4
    if value.size == 0 or width == 0:
        return False
    codes = np.ascontiguousarray(value).view(np.uint32).reshape(-1, width)
    length = np.char.str_len(value).reshape(-1, 1)
    return bool(np.any((codes == 0) & (np.arange(width) < length)))


def _write_strings(group: h5py.Group, name: str, values: np.ndarray) -> h5py.Dataset:
    import h5py

    return group.create_dataset(name, data=values, dtype=h5py.string_dtype("utf-8"))


# ---------------------------------------------------------------------------- reading
def read_result(group: h5py.Group) -> Any:
    """Rebuild the dataclass stored in ``group`` by :func:`write_result`.

    Raises :class:`ResultsFileError` naming the HDF5 path if anything is missing,
    unexpected or inconsistent; a partial result is never returned.
    """
    try:
        return _read_result(group)
    except ResultsFileError:
        raise
    except (KeyError, TypeError, ValueError, AttributeError, OSError) as exc:
        raise ResultsFileError(f"malformed result ({type(exc).__name__}: {exc})",
                               group.name) from exc


def _read_result(group: h5py.Group) -> Any:
    name = _str_attr(group, "type")
    entry = RESULT_TYPES.get(name)
    if entry is None:
        raise ResultsFileError(f"unknown result type {name!r}; known: {sorted(RESULT_TYPES)}",
                               group.name)
    kinds = json.loads(_str_attr(group, "fields"))
    fields = {f.name: f for f in dataclasses.fields(entry.cls)}
    # A field added later with a default (e.g. ``notes``) may be absent from older files.
    missing = [k for k, f in fields.items() if k not in kinds and not _has_default(f)]
    extra = [k for k in kinds if k not in fields]
    if missing or extra:
        raise ResultsFileError(
            f"fields of {name} do not match this rotorsim: missing {missing}, unexpected "
            f"{extra} (file written by another version?)", group.name)
    values = {key: _read_field(group, key, kind) for key, kind in kinds.items()}
    obj = entry.cls(**{k: v for k, v in values.items() if fields[k].init})
    for key, value in values.items():
        if not fields[key].init:  # derived fields: restore exactly what was saved
            object.__setattr__(obj, key, value)
    return obj


def _has_default(field: dataclasses.Field[Any]) -> bool:
    return (field.default is not dataclasses.MISSING
            or field.default_factory is not dataclasses.MISSING)


def _str_attr(group: h5py.Group, key: str) -> str:
    if key not in group.attrs:
        raise ResultsFileError(f"attribute {key!r} missing", group.name)
    value = group.attrs[key]
    if isinstance(value, bytes):
        value = value.decode()
    if not isinstance(value, str):
        raise ResultsFileError(f"attribute {key!r} is not a string", group.name)
    return value


def _read_field(group: h5py.Group, name: str, kind: str) -> Any:
    if kind == "none":
        return None
    if kind == "dofmap":
        sub = group[name]
        names = tuple(str(n) for n in sub["node_names"].asstr()[()]) \
            if "node_names" in sub else ()
        return DofMap(int(sub.attrs["n_nodes"]), np.asarray(sub["fixed"][()], dtype=np.int64),
                      node_names=names)
    if kind == "group":
        return _read_result(group[name])
    if kind == "group_tuple":
        sub = group[name]
        return tuple(_read_result(sub[str(i)]) for i in range(int(sub.attrs["length"])))
    if kind == "array":
        return _read_array(group[name])
    if kind == "array_dict":
        sub = group[name]
        return {key: _read_array(sub[key]) for key in json.loads(sub.attrs["keys"])}
    if kind == "str_tuple":
        return tuple(str(s) for s in group[name].asstr()[()])
    value = group.attrs[name]
    if kind == "status":
        return Status(int(value))
    if kind == "numpy":
        return value
    if kind == "json":
        return from_jsonable(json.loads(value))
    if kind in _PY_TYPES:
        return _PY_TYPES[kind](value.item() if isinstance(value, np.generic) else value)
    raise ResultsFileError(f"unknown field kind {kind!r} of {name!r}", group.name)


def _read_array(ds: h5py.Dataset) -> np.ndarray:
    dtype = np.dtype(ds.attrs["numpy_dtype"])
    data = ds.asstr()[()] if dtype.kind == "U" else ds[()]
    out = np.asarray(data, dtype=dtype)
    if out.shape != ds.shape:
        raise ResultsFileError(f"shape {out.shape} != stored {ds.shape}", ds.name)
    return out


# ---------------------------------------------------------------------------- JSON
