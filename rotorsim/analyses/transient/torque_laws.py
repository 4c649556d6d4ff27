"""Torque laws of a torque-driven transient: motor characteristics, load and friction torques.

Each law is a small frozen object with ``torque(W, t, phi)`` [N m] at spin speed ``W``
[rad/s], time ``t`` [s] and shaft angle ``phi`` [rad], its speed slope ``slope(W, t, phi)``
= ``dT/dW`` [N m s/rad] (the slip damping of a motor, the speed damping of a load) and
``describe()`` for the result's options. Signs: a motor torque drives ``+z``; a load or
friction torque is counted positive when it opposes a positive spin (the spin equation is
``J W' = T_motor - sum T_load - sum T_friction``).

A load or friction law is *reactive* (``reactive=True``, the default where it matters) when
it only ever opposes motion: at standstill it holds the rotor up to its value at ``W = 0``
(static friction) and cannot turn it backwards. An *active* load (``reactive=False``, e.g.
a hoist) keeps its sign at rest. This is the usual split of load torques in drive
engineering (e.g. Dresig & Holzweissig, *Dynamics of Machinery*, Springer 2010, on the
load characteristics of drives). The quadratic and viscous laws vanish at rest.

The induction-motor law is Kloss's formula for the steady-state torque-slip curve,
``T = 2 T_b / (s / s_b + s_b / s)`` with slip ``s = (W_s - W) / W_s`` (e.g. Fischer,
*Elektrische Maschinen*; Krause et al., *Analysis of Electric Machinery and Drive
Systems*, on the steady-state torque of the induction machine; Dresig & Holzweissig on
motor characteristics in drive dynamics). It neglects the stator resistance and the
electromagnetic transients of the machine: a quasi-static motor model.

Examples
--------
>>> m = InductionMotor(breakdown_torque=100.0, breakdown_slip=0.2, synchronous_speed=150.0)
>>> round(m.torque(120.0, 0.0, 0.0), 6)                   # at the breakdown slip
100.0
>>> round(m.torque(150.0, 0.0, 0.0), 6), round(m.torque(0.0, 0.0, 0.0), 4)
(0.0, 38.4615)
>>> QuadraticTorque(2e-3).torque(100.0, 0.0, 0.0)          # fan law c W |W|
20.0
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError

DERIVATIVE_STEP = 1e-6
"""Relative step of the central difference ``dT/dW`` of a user function (step
``1e-6 (1 + |W|)`` rad/s; relative error ~1e-10 for a smooth law)."""


@runtime_checkable
class TorqueLaw(Protocol):
    """A torque ``T(W, t, phi)`` [N m] with its speed slope ``dT/dW`` [N m s/rad]."""

    @property
    def reactive(self) -> bool: ...

    def torque(self, speed: float, t: float, angle: float) -> float: ...

    def slope(self, speed: float, t: float, angle: float) -> float: ...

    def describe(self) -> dict[str, object]: ...


@dataclass(frozen=True)
class ConstantTorque:
    """A constant torque ``value`` [N m] (a motor at constant torque, a constant load,
    Coulomb bearing friction); ``reactive``: see the module docstring."""

    value: float
    reactive: bool = True

    def __post_init__(self) -> None:
        _finite(self.value, "ConstantTorque.value")

    def torque(self, speed: float, t: float, angle: float) -> float:
        return float(self.value)

    def slope(self, speed: float, t: float, angle: float) -> float:
        return 0.0

    def describe(self) -> dict[str, object]:
        return {"law": "constant", "torque": float(self.value), "reactive": self.reactive}


@dataclass(frozen=True)
class QuadraticTorque:
    """Fan or pump law ``c W |W|`` [N m] with ``coefficient`` ``c`` [N m s^2/rad^2]
    (the affinity laws: torque grows with the square of speed)."""

    coefficient: float

    reactive = True

    def __post_init__(self) -> None:
        _finite(self.coefficient, "QuadraticTorque.coefficient")
        _not_negative(self.coefficient, "QuadraticTorque.coefficient")

    def torque(self, speed: float, t: float, angle: float) -> float:
        return self.coefficient * speed * abs(speed)

    def slope(self, speed: float, t: float, angle: float) -> float:
        return 2.0 * self.coefficient * abs(speed)

    def describe(self) -> dict[str, object]:
        return {"law": "quadratic", "coefficient": float(self.coefficient)}


@dataclass(frozen=True)
class ViscousTorque:
    """Linear viscous drag ``c W`` [N m] with ``coefficient`` ``c`` [N m s/rad]."""

    coefficient: float

    reactive = True

    def __post_init__(self) -> None:
        _finite(self.coefficient, "ViscousTorque.coefficient")
        _not_negative(self.coefficient, "ViscousTorque.coefficient")

    def torque(self, speed: float, t: float, angle: float) -> float:
        return self.coefficient * speed

    def slope(self, speed: float, t: float, angle: float) -> float:
        return float(self.coefficient)

    def describe(self) -> dict[str, object]:
        return {"law": "viscous", "coefficient": float(self.coefficient)}


@dataclass(frozen=True, eq=False)
class TorqueCurve:
    """A measured characteristic: ``torques`` [N m] at increasing ``speeds`` [rad/s],
    linearly interpolated, held at the end values outside the table."""

    speeds: ArrayLike
    torques: ArrayLike
    reactive: bool = True
    _w: FloatArray = field(init=False, repr=False)
    _t: FloatArray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        w = np.asarray(self.speeds, dtype=float).reshape(-1)
        tq = np.asarray(self.torques, dtype=float).reshape(-1)
        if w.size < 2 or w.shape != tq.shape:
            raise ModelError(f"give at least 2 speeds and as many torques, got {w.size} and "
                             f"{tq.size}", "TorqueCurve")
        if not (np.all(np.isfinite(w)) and np.all(np.isfinite(tq))):
            raise ModelError("speeds and torques must be finite", "TorqueCurve")
        if np.any(np.diff(w) <= 0):
            raise ModelError("speeds must be strictly increasing", "TorqueCurve.speeds")
        object.__setattr__(self, "_w", w)
        object.__setattr__(self, "_t", tq)

    def torque(self, speed: float, t: float, angle: float) -> float:
        return float(np.interp(speed, self._w, self._t))

    def slope(self, speed: float, t: float, angle: float) -> float:
        if not self._w[0] < speed < self._w[-1]:
            return 0.0
        i = int(np.searchsorted(self._w, speed, side="right")) - 1
        return float((self._t[i + 1] - self._t[i]) / (self._w[i + 1] - self._w[i]))

    def describe(self) -> dict[str, object]:
        return {"law": "curve", "speeds": self._w.tolist(), "torques": self._t.tolist(),
                "reactive": self.reactive}


@dataclass(frozen=True)
class InductionMotor:
    """Kloss's torque-slip curve of an induction motor (module docstring).

    Parameters
    ----------
    breakdown_torque : float
        Pull-out (maximum) torque ``T_b`` [N m], > 0.
    breakdown_slip : float
        Slip at the breakdown torque ``s_b`` (0 < s_b <= 1).
    synchronous_speed : float
        ``W_s`` [rad/s] (``2 pi f / pole pairs``), > 0. Above it the motor brakes
        (generator).
    """

    breakdown_torque: float
    breakdown_slip: float
    synchronous_speed: float

    reactive = False

    def __post_init__(self) -> None:
        for name in ("breakdown_torque", "breakdown_slip", "synchronous_speed"):
            _finite(getattr(self, name), f"InductionMotor.{name}")
            if not getattr(self, name) > 0:
                raise ModelError(f"must be > 0, got {getattr(self, name)!r}",
                                 f"InductionMotor.{name}")
        if self.breakdown_slip > 1.0:
            raise ModelError(f"must be <= 1, got {self.breakdown_slip!r}",
                             "InductionMotor.breakdown_slip")

    def torque(self, speed: float, t: float, angle: float) -> float:
        s, sb = 1.0 - speed / self.synchronous_speed, self.breakdown_slip
        return 2.0 * self.breakdown_torque * s * sb / (s * s + sb * sb)

    def slope(self, speed: float, t: float, angle: float) -> float:
        s, sb = 1.0 - speed / self.synchronous_speed, self.breakdown_slip
        dT_ds = 2.0 * self.breakdown_torque * sb * (sb * sb - s * s) / (s * s + sb * sb) ** 2
        return -dT_ds / self.synchronous_speed

    def describe(self) -> dict[str, object]:
        return {"law": "induction", "breakdown_torque": float(self.breakdown_torque),
                "breakdown_slip": float(self.breakdown_slip),
                "synchronous_speed": float(self.synchronous_speed)}


@dataclass(frozen=True)
class TorqueFunction:
    """Any torque ``function(W, t)`` [N m] of speed [rad/s] and time [s].

    ``derivative(W, t)`` = ``dT/dW`` [N m s/rad]; default a central difference
    (:data:`DERIVATIVE_STEP`).
    """

    function: Callable[[float, float], float]
    derivative: Callable[[float, float], float] | None = None
    reactive: bool = True

    def __post_init__(self) -> None:
        for name in ("function", "derivative"):
            value = getattr(self, name)
            if value is not None and not callable(value):
                raise ModelError(f"must be callable, got {type(value).__name__}",
                                 f"TorqueFunction.{name}")

    def torque(self, speed: float, t: float, angle: float) -> float:
        return float(self.function(float(speed), float(t)))

    def slope(self, speed: float, t: float, angle: float) -> float:
        if self.derivative is not None:
            return float(self.derivative(float(speed), float(t)))
        h = DERIVATIVE_STEP * (1.0 + abs(speed))
        return (self.torque(speed + h, t, angle) - self.torque(speed - h, t, angle)) / (2 * h)

    def describe(self) -> dict[str, object]:
        return {"law": "function", "function": repr(self.function),
                "reactive": self.reactive}


@dataclass(frozen=True)
class PulsatingTorque:
    """A torque with a pulsation locked to the shaft angle: ``base(W, t) + amplitude
    sin(order phi + phase)`` [N m] (torque ripple of a motor, the firing order of an
    engine, the blade passing of a fan).

    Parameters
    ----------
    base : torque law or float
        The mean characteristic.
    amplitude : float
        Ripple amplitude [N m].
    order : float
        Pulsations per revolution ``k`` (> 0): the ripple frequency is ``k W``.
    phase : float
        [rad].
    """

    base: TorqueLaw | float
    amplitude: float
    order: float
    phase: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "base", as_torque_law(self.base, "PulsatingTorque.base"))
        for name in ("amplitude", "order", "phase"):
            _finite(getattr(self, name), f"PulsatingTorque.{name}")
        if not self.order > 0:
            raise ModelError(f"must be > 0, got {self.order!r}", "PulsatingTorque.order")

    @property
    def reactive(self) -> bool:
        return bool(_law(self.base).reactive)

    def torque(self, speed: float, t: float, angle: float) -> float:
        ripple = self.amplitude * math.sin(self.order * angle + self.phase)
        return _law(self.base).torque(speed, t, angle) + ripple

    def slope(self, speed: float, t: float, angle: float) -> float:
        return _law(self.base).slope(speed, t, angle)

    def describe(self) -> dict[str, object]:
        return {"law": "pulsating", "base": _law(self.base).describe(),
                "amplitude": float(self.amplitude), "order": float(self.order),
                "phase": float(self.phase)}


def as_torque_law(value: object, where: str) -> TorqueLaw:
    """A number is a :class:`ConstantTorque`, a callable ``T(W, t)`` a
    :class:`TorqueFunction`; a law is returned as it is."""
    if isinstance(value, TorqueLaw):
        return value
    if callable(value):
        return TorqueFunction(value)
    if isinstance(value, int | float) and not isinstance(value, bool):
        return ConstantTorque(float(value))
    raise ModelError(f"give a torque [N m], a callable T(W, t) or a torque law, got "
                     f"{value!r}", where)


def _law(value: TorqueLaw | float) -> TorqueLaw:
    assert isinstance(value, TorqueLaw)  # converted in __post_init__
    return value


def _finite(value: object, where: str) -> None:
    if not (isinstance(value, int | float) and not isinstance(value, bool)
            and math.isfinite(value)):
        raise ModelError(f"must be a finite number, got {value!r}", where)


def _not_negative(value: float, where: str) -> None:
    if value < 0:
        raise ModelError(f"must be >= 0, got {value!r}", where)
