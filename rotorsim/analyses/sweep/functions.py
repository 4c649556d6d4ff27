"""Ready-made, picklable model changes (``apply``) and evaluations (``evaluate``) for
:func:`rotorsim.analyses.sweep.sweep.sweep`."""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.analyses.linear.modal import modal
from rotorsim.elements.linear_bearing import COEFFICIENTS
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor

Params = Mapping[str, float]
Apply = Callable[[Rotor, Params], Rotor]
Evaluate = Callable[[Rotor, Params], Mapping[str, Any]]


# ---------------------------------------------------------------------------- model changes
def _value(params: Params, name: str) -> float:
    if name not in params:
        raise ModelError(f"parameter {name!r} is not in the sweep; parameters are "
                         f"{list(params)}", "sweep")
    return float(params[name])


def _indices(indices: int | Iterable[int], where: str) -> tuple[int, ...]:
    out = (indices,) if isinstance(indices, int) else tuple(indices)
    if not out or any(isinstance(i, bool) or not isinstance(i, int) or i < 0 for i in out):
        raise ModelError(f"indices must be non-negative integers, got {indices!r}", where)
    return out


def _change_bearings(rotor: Rotor, params: Params, *, indices: tuple[int, ...],
                     parameter: str, coefficients: tuple[str, ...], scale: bool) -> Rotor:
    value = _value(params, parameter)
    bearings = list(rotor.bearing_elements)
    for i in indices:
        if i >= len(bearings):
            raise ModelError(f"bearing index {i} outside 0..{len(bearings) - 1}", "sweep")
        b = bearings[i]
        new: dict[str, Any] = {c: np.asarray(getattr(b, c), dtype=float) * value if scale
                               else value for c in coefficients}
        bearings[i] = dataclasses.replace(b, **new)
    return rotor.with_bearings(bearings)


def _bearing_change(indices: int | Iterable[int], parameter: str,
                    coefficients: Sequence[str], scale: bool, where: str) -> Apply:
    unknown = [c for c in coefficients if c not in COEFFICIENTS]
    if unknown or not coefficients:
        raise ModelError(f"unknown coefficients {unknown}; use some of {COEFFICIENTS}", where)
    return functools.partial(_change_bearings, indices=_indices(indices, where),
                             parameter=parameter, coefficients=tuple(coefficients), scale=scale)


def set_bearing_stiffness(indices: int | Iterable[int], parameter: str = "bearing_k",
                          coefficients: Sequence[str] = ("kxx", "kyy")) -> Apply:
    """Model function setting ``coefficients`` of the bearings ``indices`` to the value
    of ``parameter`` [N/m] (other coefficients, e.g. cross-coupling, are kept)."""
    return _bearing_change(indices, parameter, coefficients, False, "set_bearing_stiffness")


def scale_bearing_stiffness(indices: int | Iterable[int], parameter: str = "bearing_k_scale",
                            coefficients: Sequence[str] = ("kxx", "kyy")) -> Apply:
    """Model function multiplying ``coefficients`` of the bearings ``indices`` (constant or
    tabulated over speed) by the value of ``parameter`` [-]."""
    return _bearing_change(indices, parameter, coefficients, True, "scale_bearing_stiffness")


def _scale_disk(rotor: Rotor, params: Params, *, index: int, parameter: str) -> Rotor:
    factor = _value(params, parameter)
    disks = list(rotor.disk_elements)
    if index >= len(disks):
        raise ModelError(f"disk index {index} outside 0..{len(disks) - 1}", "scale_disk_mass")
    d = disks[index]
    disks[index] = dataclasses.replace(d, m=d.m * factor, Id=d.Id * factor, Ip=d.Ip * factor)
    return dataclasses.replace(rotor, disk_elements=tuple(disks))


def scale_disk_mass(index: int, parameter: str = "disk_mass_scale") -> Apply:
    """Model function multiplying mass and inertias of disk ``index`` by ``parameter``."""
    (i,) = _indices(index, "scale_disk_mass")
    return functools.partial(_scale_disk, index=i, parameter=parameter)


def _chained(rotor: Rotor, params: Params, *, applies: tuple[Apply, ...]) -> Rotor:
    for apply in applies:
        rotor = apply(rotor, params)
    return rotor


def chain(*applies: Apply) -> Apply:
    """Model function applying ``applies`` in order."""
    if not applies or not all(callable(a) for a in applies):
        raise TypeError(f"chain needs one or more callables, got {applies!r}")
    return functools.partial(_chained, applies=tuple(applies))


# ---------------------------------------------------------------------------- evaluations
def _check_count(num_modes: int, where: str) -> None:
    if isinstance(num_modes, bool) or not isinstance(num_modes, int) or num_modes < 1:
        raise ModelError(f"num_modes must be an integer >= 1, got {num_modes!r}", where)


def _min_log_dec(rotor: Rotor, params: Params, *, speed: str | float, num_modes: int,
                 kind: str | None, sparse: bool | None) -> dict[str, Any]:
    w = _value(params, speed) if isinstance(speed, str) else float(speed)
    m = modal(rotor, w, num_modes, sparse=sparse)
    log_dec, wd = np.full(num_modes, np.nan), np.full(num_modes, np.nan)
    log_dec[: m.num_modes], wd[: m.num_modes] = m.log_dec, m.wd
    keep = np.ones(m.num_modes, bool) if kind is None else np.array(m.kind) == kind
    least = float(m.log_dec[keep].min()) if np.any(keep) else np.nan
    return {"log_dec_min": least, "log_dec": log_dec, "wd": wd}


def min_log_dec(speed: str | float = "speed", num_modes: int = 6, *,
                kind: str | None = "lateral", sparse: bool | None = None) -> Evaluate:
    """Evaluate function for stability: the least logarithmic decrement.

    Runs :func:`~rotorsim.analyses.linear.modal.modal` at spin ``speed`` (a parameter name or a
    value [rad/s]) for ``num_modes`` modes and returns ``log_dec_min`` (least log dec
    of the modes of ``kind``; negative means unstable), and ``log_dec`` and ``wd``
    [rad/s] of all modes, shape ``(num_modes,)``, NaN-padded. ``sparse`` is passed on
    (``False``: dense LAPACK, bitwise reproducible; ARPACK starts from a random vector).
    """
    _check_count(num_modes, "min_log_dec")
    if kind not in (None, "lateral", "axial", "torsional"):
        raise ModelError(f"kind must be None, 'lateral', 'axial' or 'torsional', got {kind!r}",
                         "min_log_dec")
    return functools.partial(_min_log_dec, speed=speed, num_modes=num_modes, kind=kind,
                             sparse=sparse)


def _critical_speeds(rotor: Rotor, params: Params, *, harmonic: float, num_modes: int,
                     whirl: str | None, sparse: bool | None) -> dict[str, Any]:
    found = critical_speeds(rotor, harmonic, num_modes, whirl=whirl,  # type: ignore[arg-type]
                            sparse=sparse)
    speeds = np.full(num_modes, np.nan)
    speeds[: len(found)] = found.speed[:num_modes]
    return {"critical_speeds": speeds}


def critical_speeds_eval(harmonic: float = 1.0, num_modes: int = 2, *,
                         whirl: str | None = "forward", sparse: bool | None = None) -> Evaluate:
    """Evaluate function returning ``critical_speeds`` [rad/s], shape ``(num_modes,)``
    (NaN-padded): the exact undamped critical speeds of
    :func:`~rotorsim.analyses.linear.critical_speeds.critical_speeds` (``whirl`` and ``sparse``
    passed on)."""
    _check_count(num_modes, "critical_speeds_eval")
    if whirl not in (None, "forward", "backward"):
        raise ModelError(f"whirl must be None, 'forward' or 'backward', got {whirl!r}",
                         "critical_speeds_eval")
    return functools.partial(_critical_speeds, harmonic=float(harmonic), num_modes=num_modes,
                             whirl=whirl, sparse=sparse)
