"""Spin-speed schedules of a transient run: speed W(t), acceleration W'(t), angle phi(t).

The shaft angle ``phi(t) = phi0 + int_t0^t W`` places the rolling elements of the bearings
(``psi_j = psi_0 + 2 pi j / Z + kappa phi``) and the unbalance forces, so it must be
accurate: closed forms for :class:`ConstantSpeed` and :class:`LinearSpeed`; for a user
:class:`SpeedFunction` a table of the integral at ``resolution`` nodes over the span
(4-point Gauss-Legendre per interval, error ``O(h^8 W^(8))``) plus one 4-point rule from the
nearest node below.

Examples
--------
>>> ramp = LinearSpeed(0.0, 100.0, t_start=0.0, t_stop=2.0).bind(0.0, 3.0)
>>> float(ramp.speed(1.0)), float(ramp.angle(2.0)), float(ramp.angle(3.0))
(50.0, 100.0, 200.0)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.analyses.linear.argument_checks import NEGATIVE_SPEED_HINT
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError

_GL_X, _GL_W = np.polynomial.legendre.leggauss(4)


class BoundSpeed(Protocol):
    """A speed schedule on a time span: ``speed``, ``acceleration`` and ``angle`` of ``t``."""

    def speed(self, t: float) -> float: ...

    def acceleration(self, t: float) -> float: ...

    def angle(self, t: float) -> float: ...

    def describe(self) -> dict[str, object]: ...


@dataclass(frozen=True)
class ConstantSpeed:
    """Constant spin speed ``W`` [rad/s]; ``phi0`` is the shaft angle at the start [rad]."""

    value: float
    phi0: float = 0.0

    def __post_init__(self) -> None:
        _finite(self.value, "ConstantSpeed.value")
        _finite(self.phi0, "ConstantSpeed.phi0")
        _not_negative(self.value, "ConstantSpeed.value")

    def bind(self, t0: float, t_end: float, resolution: int = 0) -> _Ramp:
        return _Ramp(self.value, self.value, t0, t_end, t0, self.phi0, "constant")


@dataclass(frozen=True)
class LinearSpeed:
    """Linear run-up or coast-down from ``start`` to ``stop`` [rad/s] between ``t_start``
    and ``t_stop`` [s], constant before and after."""

    start: float
    stop: float
    t_start: float
    t_stop: float
    phi0: float = 0.0

    def __post_init__(self) -> None:
        for name in ("start", "stop", "t_start", "t_stop", "phi0"):
            _finite(getattr(self, name), f"LinearSpeed.{name}")
        for name in ("start", "stop"):
            _not_negative(getattr(self, name), f"LinearSpeed.{name}")
        if not self.t_stop > self.t_start:
            raise ModelError(f"t_stop ({self.t_stop}) must exceed t_start ({self.t_start})",
                             "LinearSpeed")

    def bind(self, t0: float, t_end: float, resolution: int = 0) -> _Ramp:
        return _Ramp(self.start, self.stop, self.t_start, self.t_stop, t0, self.phi0, "linear")


@dataclass(frozen=True)
class SpeedFunction:
    """Any speed schedule ``function(t) -> W`` [rad/s].

    Parameters
    ----------
    function : callable
        ``W(t)``, evaluated at scalar times.
    derivative : callable, optional
        ``W'(t)`` [rad/s^2]; default a central difference with step ``1e-6 (1 + |t|)`` s
        (relative error ~1e-10 for a smooth schedule).
    phi0 : float
        Shaft angle at the start [rad].
    """

    function: Callable[[float], float]
    derivative: Callable[[float], float] | None = None
    phi0: float = 0.0

    def __post_init__(self) -> None:
        for name in ("function", "derivative"):
            value = getattr(self, name)
            if value is not None and not callable(value):
                raise ModelError(f"must be callable, got {type(value).__name__}",
                                 f"SpeedFunction.{name}")
        _finite(self.phi0, "SpeedFunction.phi0")

    def bind(self, t0: float, t_end: float, resolution: int = 4096) -> _Tabulated:
        return _Tabulated.build(self, t0, t_end, max(int(resolution), 16))


SpeedProfile = ConstantSpeed | LinearSpeed | SpeedFunction


def as_speed_profile(speed: float | SpeedProfile | Callable[[float], float]) -> SpeedProfile:
    """A number is a constant speed, a callable a :class:`SpeedFunction`."""
    if isinstance(speed, ConstantSpeed | LinearSpeed | SpeedFunction):
        return speed
    if callable(speed):
        return SpeedFunction(speed)
    try:
        value = float(speed)
    except (TypeError, ValueError):
        value = math.nan
    if not math.isfinite(value):
        raise ModelError(f"give a number [rad/s], a callable W(t) or a speed profile, got "
                         f"{speed!r}", "speed")
    _not_negative(value, "speed")
    return ConstantSpeed(value)


@dataclass(frozen=True)
class _Ramp:
    """Piecewise-linear speed: ``w0`` until ``ta``, linear to ``w1`` at ``tb``, then ``w1``."""

    w0: float
    w1: float
    ta: float
    tb: float
    t0: float
    phi0: float
    kind: str

    @property
    def slope(self) -> float:
        return (self.w1 - self.w0) / (self.tb - self.ta) if self.tb > self.ta else 0.0

    def speed(self, t: float) -> float:
        if t <= self.ta:
            return self.w0
        if t >= self.tb:
            return self.w1
        return self.w0 + self.slope * (t - self.ta)

    def acceleration(self, t: float) -> float:
        return self.slope if self.ta < t < self.tb else 0.0

    def angle(self, t: float) -> float:
        return self.phi0 + self._integral(t) - self._integral(self.t0)

    def _integral(self, t: float) -> float:
        """``int_ta^t W`` (negative before ``ta``)."""
        if t <= self.ta:
            return self.w0 * (t - self.ta)
        s = min(t, self.tb) - self.ta
        out = self.w0 * s + 0.5 * self.slope * s * s
        return out + self.w1 * max(t - self.tb, 0.0)

    def describe(self) -> dict[str, object]:
        return {"kind": self.kind, "start": self.w0, "stop": self.w1, "t_start": self.ta,
                "t_stop": self.tb, "phi0": self.phi0}


@dataclass(frozen=True, eq=False)
class _Tabulated:
    profile: SpeedFunction
    nodes: FloatArray
    cumulative: FloatArray

    @classmethod
    def build(cls, profile: SpeedFunction, t0: float, t_end: float, m: int) -> _Tabulated:
        nodes = np.linspace(t0, t_end, m + 1)
        h = nodes[1] - nodes[0]
        pts = (nodes[:-1, None] + 0.5 * h * (1.0 + _GL_X)[None, :]).ravel()
        values = np.array([_checked(profile.function, t) for t in pts]).reshape(m, 4)
        for t in (t0, t_end):
            _checked(profile.function, t)
        pieces = 0.5 * h * values @ _GL_W
        return cls(profile, nodes, np.concatenate([[0.0], np.cumsum(pieces)]))

    def speed(self, t: float) -> float:
        return _checked(self.profile.function, t)

    def acceleration(self, t: float) -> float:
        if self.profile.derivative is not None:
            return _checked(self.profile.derivative, t, "derivative")
        h = 1e-6 * (1.0 + abs(t))
        return (self.speed(t + h) - self.speed(t - h)) / (2.0 * h)

    def angle(self, t: float) -> float:
        i = int(np.clip(np.searchsorted(self.nodes, t, side="right") - 1, 0,
                        self.nodes.size - 2))
        a, h = self.nodes[i], t - self.nodes[i]
        if h == 0.0:
            return self.profile.phi0 + float(self.cumulative[i])
        pts = a + 0.5 * h * (1.0 + _GL_X)
        part = 0.5 * h * sum(w * self.speed(float(x)) for x, w in zip(pts, _GL_W, strict=True))
        return self.profile.phi0 + float(self.cumulative[i]) + part

    def describe(self) -> dict[str, object]:
        return {"kind": "function", "function": repr(self.profile.function),
                "resolution": int(self.nodes.size - 1), "phi0": self.profile.phi0}


def _checked(fn: Callable[[float], float], t: float, name: str = "function") -> float:
    value = float(fn(float(t)))
    if not math.isfinite(value):
        raise ModelError(f"returned {value!r} at t = {float(t):.6g} s", f"SpeedFunction.{name}")
    return value


def _not_negative(speed: float, where: str) -> None:
    """The one rule on the sense of spin, as in the linear analyses."""
    if speed < 0:
        raise ModelError(f"must be >= 0 rad/s, got {speed!r}: {NEGATIVE_SPEED_HINT}", where)


def _finite(value: ArrayLike, where: str) -> None:
    if not (isinstance(value, int | float) and math.isfinite(value)):
        raise ModelError(f"must be a finite number, got {value!r}", where)
