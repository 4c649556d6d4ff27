"""Any number of a model file as a parameter: key paths, values in SI and varied models.

A *key path* names one value of a model file: table names and keys joined by dots, with an
entry of an array of tables (``[[bearings]]``, ``[[rolling_bearings]]``, ``[[disks]]``,
``[[materials]]``) chosen by its ``tag`` (``name`` for materials) or its 0-based index:

* ``"rolling_bearings.DE.radial_clearance"``: the clearance of the rolling bearing ``DE``;
* ``"bearings.B1.cxx"``: the damping of the linear bearing ``B1``;
* ``"disks.0.o_d"``, ``"materials.steel.E"``, ``"shaft.0.od"``.

:class:`ModelParameter` rebuilds the model with the value of the path set to a number (in
SI units) and returns its rotor, for :func:`rotorsim.periodic_parameter` and
:class:`~rotorsim.analyses.periodic.folds.ParameterMap`; a path into
``rolling_bearings`` returns only the rolling bearings (the linear part then stays
assembled once).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Mapping
from typing import Any

from rotorsim.errors import ModelError
from rotorsim.units import _NUMBER, _registry, _scale

WHERE = "parameter"


def split_path(path: str) -> list[str]:
    """The segments of a key path (ModelError for an empty segment)."""
    parts = str(path).split(".")
    if len(parts) < 2 or any(not p.strip() for p in parts):
        raise ModelError(f"{path!r} is not a key path such as "
                         "'rolling_bearings.DE.radial_clearance'", WHERE)
    return [p.strip() for p in parts]


def _entry(items: list[Any], key: str, walked: str) -> Any:
    for item in items:
        if isinstance(item, Mapping) and key in (item.get("tag"), item.get("name")):
            return item
    if key.isdigit() and int(key) < len(items):
        return items[int(key)]
    names = [str(i.get("tag") or i.get("name")) for i in items if isinstance(i, Mapping)
             and (i.get("tag") or i.get("name"))]
    raise ModelError(f"no entry {key!r} in [[{walked}]]: use a tag or name {names} or an "
                     f"index 0..{len(items) - 1}", WHERE)


def _parent(data: Any, path: str) -> tuple[dict[str, Any], str]:
    """The table holding the last key of ``path`` in ``data`` and that key."""
    parts = split_path(path)
    node, walked = data, ""
    for part in parts[:-1]:
        if isinstance(node, Mapping):
            if part not in node:
                raise ModelError(f"the model file has no {walked + part!r}", WHERE)
            node = node[part]
        elif isinstance(node, list):
            node = _entry(node, part, walked.rstrip("."))
        else:
            raise ModelError(f"{walked.rstrip('.')!r} is a value, not a table", WHERE)
        walked += part + "."
    if isinstance(node, list):
        raise ModelError(f"{path!r} ends at the array [[{walked.rstrip('.')}]]: name an "
                         "entry and one of its keys", WHERE)
    if not isinstance(node, dict):
        raise ModelError(f"{walked.rstrip('.')!r} is a value, not a table", WHERE)
    return node, parts[-1]


def current_value(data: Mapping[str, Any], path: str) -> Any:
    """The value at ``path`` as written in the file (None when the key is not given)."""
    table, key = _parent(data, path)
    return table.get(key)


def with_value(data: Mapping[str, Any], path: str, value: Any) -> dict[str, Any]:
    """A deep copy of ``data`` with ``value`` at ``path`` (the key is added if absent)."""
    out = copy.deepcopy(dict(data))
    table, key = _parent(out, path)
    if isinstance(table.get(key), Mapping | list):
        raise ModelError(f"{path!r} is a table, not a value", WHERE)
    table[key] = value
    return out


def si_value(value: Any, where: str) -> float:
    """SI number of ``value``: a number (already SI) or ``"<number> <unit>"`` of any
    dimension (``"5 um"`` -> 5e-06, ``"3000 rpm"`` -> 314.16 rad/s, ``"2 kN s/m"`` ->
    2000)."""
    if isinstance(value, bool):
        raise ModelError(f"expected a number or a string with units, got {value!r}", where)
    if isinstance(value, int | float):
        out = float(value)
    elif isinstance(value, str):
        match = _NUMBER.match(value)
        if match is None:
            raise ModelError(f"cannot read {value!r}: expected '<number> <unit>'", where)
        try:
            unit = _registry().parse_units(match.group(2) or "dimensionless")
            factor = float(_registry().Quantity(1.0, unit).to_base_units().magnitude)
        except Exception as err:  # pint raises many kinds on malformed text
            raise ModelError(f"cannot read the unit of {value!r}: {err}", where) from None
        out = _scale(float(match.group(1)), factor)  # "10 um" is exactly 1e-05
    else:
        raise ModelError(f"expected a number or a string with units, got {value!r}", where)
    if not math.isfinite(out):
        raise ModelError(f"must be finite, got {value!r}", where)
    return out


class ModelParameter:
    """``vary(value) -> Rotor`` (or the rolling bearings) of a model file's data with
    ``value`` [SI] at ``path``.

    Parameters
    ----------
    data : mapping
        The parsed model file (``Model.data``).
    path : str
        Key path of the parameter (module docstring).
    build : callable
        ``build(data) -> Model`` that turns changed data into a model:
        :func:`rotorsim.io.model.model_from_dict` (what :meth:`Model.parameter` passes).

    Raises
    ------
    ModelError
        When ``path`` does not name a value of ``data``.
    """

    def __init__(self, data: Mapping[str, Any], path: str,
                 build: Callable[[Mapping[str, Any]], Any]) -> None:
        self.path = str(path)
        self.build = build
        self.data = {k: v for k, v in data.items() if k != "analyses"}
        with_value(self.data, self.path, 0.0)  # resolves the path now
        self.elements_only = split_path(self.path)[0] == "rolling_bearings"

    def model(self, value: Any) -> Any:
        """The model with ``value`` (a number in SI, or a string with units) at the path."""
        try:
            return self.build(with_value(self.data, self.path, value))
        except ModelError as err:
            raise ModelError(f"with {self.path} = {value!r}: {err}", WHERE) from None

    def __call__(self, value: float) -> Any:
        m = self.model(float(value))
        if self.elements_only:
            return m.rolling_bearings
        return m.rotor.with_nonlinear(m.rolling_bearings)

    def check(self, start: Any, stop: Any) -> tuple[float, float]:
        """SI values of ``start`` and ``stop``, each first tried in the model: the schema
        checks a string's dimension against the key, and both ends must give a valid model
        (a clearance whose interference is absurd is refused here, not mid-branch)."""
        out = []
        for name, value in (("start", start), ("stop", stop)):
            self.model(value)
            out.append(si_value(value, f"{WHERE}.{name}"))
        return out[0], out[1]


def parameter_range(model: Any, vary: str, start: Any, stop: Any) -> tuple[float, float]:
    """SI ``(start, stop)`` of a parameter branch of ``model`` over ``vary`` (a key path,
    ``"loads"`` or ``"forcing"``; numbers in SI or strings with units).

    Raises
    ------
    ModelError
        Unknown path, a unit of the wrong dimension for the key, or ``start == stop``.
    """
    if vary in ("loads", "forcing"):
        span = si_value(start, f"{WHERE}.start"), si_value(stop, f"{WHERE}.stop")
    else:
        span = model.parameter(vary).check(start, stop)
    if span[0] == span[1]:
        raise ModelError(f"start and stop are equal ({span[0]})", WHERE)
    return span


__all__ = ["ModelParameter", "current_value", "parameter_range", "si_value", "split_path",
           "with_value"]
