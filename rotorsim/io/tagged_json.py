"""Tagged JSON of the values results carry in attributes (``options``, ``stats``,
``summary``): standard JSON with tagged objects for tuples, complex numbers, non-finite
floats, numpy scalars and arrays, non-string dict keys and :class:`~rotorsim.errors.Status`,
so that :func:`from_jsonable` gives back exactly what :func:`to_jsonable` was given.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorsim.errors import ResultsFileError, Status

_JSON_TAGS = ("__tuple__", "__complex__", "__float__", "__numpy__", "__ndarray__",
              "__dict__", "__status__")


def plain_dtype(dtype: np.dtype) -> bool:
    """Fixed-size numeric dtype that HDF5 and JSON hold exactly (no long double)."""
    limit = {"f": 8, "c": 16}.get(dtype.kind, 8)
    return dtype.fields is None and dtype.itemsize <= limit


def to_jsonable(value: Any, where: str = "value") -> Any:
    """Tagged, exact JSON form of ``value`` (standard JSON: no NaN tokens).

    Plain JSON types pass through. Tags (one-key objects, or two or three keys for numpy):
    ``{"__tuple__": [...]}``, ``{"__complex__": [re, im]}``, ``{"__float__": "nan"}``
    (also ``"inf"``, ``"-inf"``, or ``"0x..."``, the bit pattern of another NaN),
    ``{"__status__": int}``, ``{"__numpy__": dtype, "value":
    v}``, ``{"__ndarray__": dtype, "shape": [...], "data": [flat values]}`` and
    ``{"__dict__": [[key, value], ...]}`` for dicts with non-str keys or keys starting with
    ``"__"``. Anything else raises :class:`ResultsFileError` naming the key path.

    Examples
    --------
    >>> import json
    >>> v = {"loads": [(2, 1e-4, 0.0)], "tol": np.float64(1e-8), "x": float("nan"), 3: None}
    >>> text = json.dumps(to_jsonable(v), allow_nan=False)
    >>> back = from_jsonable(json.loads(text))
    >>> back["loads"], type(back["tol"]).__name__, back[3]
    ([(2, 0.0001, 0.0)], 'float64', None)
    """
    t = type(value)
    if value is None or t in (bool, int, str):
        return value
    if t is float:
        return value if math.isfinite(value) else {"__float__": _nonfinite_text(value)}
    if t is complex:
        return {"__complex__": [to_jsonable(value.real), to_jsonable(value.imag)]}
    if isinstance(value, Status):
        return {"__status__": int(value)}
    if isinstance(value, np.generic | np.ndarray):
        return _numpy_to_jsonable(value, where)
    if t is list:
        return [to_jsonable(v, f"{where}[{i}]") for i, v in enumerate(value)]
    if t is tuple:
        return {"__tuple__": [to_jsonable(v, f"{where}[{i}]") for i, v in enumerate(value)]}
    if t is dict:
        if all(type(k) is str and not k.startswith("__") for k in value):
            return {k: to_jsonable(v, f"{where}[{k!r}]") for k, v in value.items()}
        return {"__dict__": [[to_jsonable(k, where), to_jsonable(v, f"{where}[{k!r}]")]
                             for k, v in value.items()]}
    raise ResultsFileError(f"cannot store a value of type {t.__name__}", where)


def _nonfinite_text(value: float) -> str:
    """``"inf"``, ``"-inf"``, ``"nan"`` (the default quiet NaN) or the hex bit pattern of any
    other NaN, so that the value is restored bit for bit."""
    bits = int(np.array(value).view(np.uint64))
    if math.isinf(value) or bits == int(np.array(math.nan).view(np.uint64)):
        return repr(value)
    return hex(bits)


def _numpy_to_jsonable(value: np.generic | np.ndarray, where: str) -> Any:
    dtype = value.dtype
    if not (dtype.kind in "biufcU" and (dtype.kind == "U" or plain_dtype(dtype))):
        raise ResultsFileError(f"cannot store numpy dtype {dtype}", where)
    if isinstance(value, np.generic):
        return {"__numpy__": dtype.str, "value": to_jsonable(value.item(), where)}
    return {"__ndarray__": dtype.str, "shape": list(value.shape),
            "data": to_jsonable(value.ravel().tolist(), where)}


def from_jsonable(obj: Any) -> Any:
    """Inverse of :func:`to_jsonable` applied to parsed JSON."""
    if isinstance(obj, list):
        return [from_jsonable(v) for v in obj]
    if not isinstance(obj, dict):
        return obj
    tag = next((k for k in obj if k.startswith("__")), None)
    if tag is None:
        return {k: from_jsonable(v) for k, v in obj.items()}
    body = obj[tag]
    if tag == "__tuple__":
        return tuple(from_jsonable(v) for v in body)
    if tag == "__complex__":
        return complex(from_jsonable(body[0]), from_jsonable(body[1]))
    if tag == "__float__":
        if body.startswith("0x"):  # a NaN with a sign or payload: its bit pattern
            return float(np.array(int(body, 16), dtype=np.uint64).view(np.float64))
        return float(body)
    if tag == "__status__":
        return Status(body)
    if tag == "__numpy__":
        value = from_jsonable(obj["value"])
        return np.dtype(body).type(value)
    if tag == "__ndarray__":
        return np.array(from_jsonable(obj["data"]), dtype=body).reshape(obj["shape"])
    if tag == "__dict__":
        return {from_jsonable(k): from_jsonable(v) for k, v in body}
    raise ResultsFileError(f"unknown JSON tag {tag!r}; known: {_JSON_TAGS}", "json")
