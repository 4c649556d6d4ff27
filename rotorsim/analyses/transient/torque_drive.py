"""Torque-driven speed: the spin of the rotor follows from a motor torque and its loads.

:class:`TorqueDrive` is a speed profile like :class:`~.speed_profile.LinearSpeed`: bound to
the span of a transient it integrates the rigid spin equation
``J_p W' = T_motor(W, t, phi) - sum T_load - sum T_friction`` up front
(:mod:`~.spin_equation`) and serves ``W(t)``, ``W'(t)`` and ``phi(t)`` to the gyroscopic
term, the unbalance forces and the rolling-element positions. The polar inertia ``J_p`` is
taken from the model (:mod:`~.torsion_loads`) unless given.

The coupling is one-way: the spin drives the lateral and torsional motion, which does not
act back on the spin. The torsional DOFs ``rz`` are angles relative to ``phi(t)`` and are
loaded by the torques at their nodes minus the inertial load of the accelerating frame
(:class:`~.torsion_loads.TorsionLoad`). The transient reports the neglected feedback of the
lateral motion on the spin (:mod:`~.spin_feedback`); the Sommerfeld effect (a drive stuck
at a resonance because the lateral motion absorbs its torque) is out of scope.

Examples
--------
>>> from rotorsim.analyses.transient.torque_laws import QuadraticTorque
>>> drive = TorqueDrive(motor=2.0, loads=[(0, QuadraticTorque(1e-4))], inertia=0.01)
>>> bound = drive.bind(0.0, 1.0)
>>> w_inf = (2.0 / 1e-4) ** 0.5          # W = w_inf tanh(c w_inf t / J): fan against 2 N m
>>> round(bound.speed(0.5), 6), round(w_inf * math.tanh(1e-4 * w_inf * 0.5 / 0.01), 6)
(86.105717, 86.105717)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rotorsim.analyses.transient.spin_equation import (
    AppliedTorque,
    SpinHistory,
    at_rest,
    integrate_spin,
    net_torque,
)
from rotorsim.analyses.transient.torque_laws import TorqueLaw, as_torque_law
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError

TorqueLike = TorqueLaw | float | Callable[[float, float], float]
"""A torque law, a constant torque [N m] or a function ``T(W, t)``."""

@dataclass(frozen=True)
class TorqueDrive:
    """Speed from torques: a motor at ``drive_node`` against loads and friction.

    Parameters
    ----------
    motor : torque law, float or callable
        Motor torque [N m]: a law of :mod:`~.torque_laws` (``InductionMotor``,
        ``TorqueCurve``, ``PulsatingTorque``, ...), a constant or ``T(W, t)``.
    drive_node : int
        Shaft node where the motor torque acts.
    loads : sequence of (node, law)
        Load torques [N m], positive against the spin (``QuadraticTorque`` for a fan,
        ``ConstantTorque``, ``ViscousTorque``, ``T(W, t)``).
    friction : sequence of (node, law)
        Bearing friction torques [N m], positive against the spin (constant or a
        function of speed).
    initial_speed : float
        ``W0`` [rad/s], >= 0.
    phi0 : float
        Shaft angle at the start [rad].
    inertia : float, optional
        Polar inertia ``J_p`` [kg m^2] of the spin equation; default the model's
        (:func:`~.torsion_loads.model_polar_inertia`). A value above the model's adds the
        difference at ``drive_node`` (e.g. the motor's rotor, rigidly attached).
    torque_damping : bool
        Put the speed slope of the torques on the torsional DOFs of their nodes as a
        damping ``-dT/dW`` (slip damping of the motor, speed damping of a fan;
        :mod:`~.torque_damping`).
    name : str
        Names the drive in messages.
    """

    motor: TorqueLike
    drive_node: int = 0
    loads: Sequence[tuple[int, TorqueLike]] = ()
    friction: Sequence[tuple[int, TorqueLike]] = ()
    initial_speed: float = 0.0
    phi0: float = 0.0
    inertia: float | None = None
    torque_damping: bool = True
    name: str = "TorqueDrive"
    torques: tuple[AppliedTorque, ...] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        where = self.name
        for key in ("initial_speed", "phi0"):
            _finite(getattr(self, key), f"{where}.{key}")
        if self.initial_speed < 0:
            raise ModelError(f"must be >= 0 rad/s, got {self.initial_speed!r}",
                             f"{where}.initial_speed")
        if self.inertia is not None:
            _finite(self.inertia, f"{where}.inertia")
            if not self.inertia > 0:
                raise ModelError(f"must be > 0 kg m^2, got {self.inertia!r}",
                                 f"{where}.inertia")
        applied = [AppliedTorque(_node(self.drive_node, f"{where}.drive_node"),
                                 as_torque_law(self.motor, f"{where}.motor"), "motor",
                                 f"{where}.motor")]
        for role in ("loads", "friction"):
            items = getattr(self, role)
            if isinstance(items, str) or not isinstance(items, Sequence):
                raise ModelError("give a list of (node, torque law)", f"{where}.{role}")
            for i, item in enumerate(items):
                label = f"{where}.{role}[{i}]"
                try:
                    node, law = item
                except (TypeError, ValueError):
                    raise ModelError(f"give (node, torque law), got {item!r}", label) from None
                applied.append(AppliedTorque(_node(node, f"{label}.node"),
                                             as_torque_law(law, label),
                                             "load" if role == "loads" else "friction", label))
        object.__setattr__(self, "loads", tuple(self.loads))
        object.__setattr__(self, "friction", tuple(self.friction))
        object.__setattr__(self, "torques", tuple(applied))

    def net_torque(self, speed: float, t: float = 0.0, angle: float = 0.0) -> float:
        """``T_motor - sum T_load - sum T_friction`` [N m] at speed ``W`` [rad/s]."""
        return net_torque(self.torques, speed, t, angle)

    def bind(self, t0: float, t_end: float, resolution: int = 4096, *,
             model_inertia: float | None = None, source: str = "given"
             ) -> BoundTorqueDrive:
        """Integrate the spin over ``t0..t_end`` [s] with ``J_p`` = ``inertia`` or else
        ``model_inertia`` (``source`` says where that came from)."""
        inertia = self.inertia if self.inertia is not None else model_inertia
        if inertia is None or not (math.isfinite(inertia) and inertia > 0):
            raise ModelError("no polar inertia: give inertia= [kg m^2], or run the drive "
                             "through rs.transient, which takes it from the model (a rotor "
                             f"with polar inertia; got {inertia!r})", f"{self.name}.inertia")
        history = integrate_spin(self.torques, float(inertia), (float(t0), float(t_end)),
                                 (float(self.initial_speed), float(self.phi0)),
                                 resolution, self.name)
        return BoundTorqueDrive(self, float(inertia),
                                "given" if self.inertia is not None else source,
                                model_inertia, history)


@dataclass(frozen=True, eq=False)
class BoundTorqueDrive:
    """A :class:`TorqueDrive` on a span: ``speed``, ``acceleration``, ``angle`` of ``t``
    (the :class:`~.speed_profile.BoundSpeed` protocol) and the torques at the nodes."""

    drive: TorqueDrive
    inertia: float
    inertia_source: str
    model_inertia: float | None
    history: SpinHistory
    _recent: dict[float, tuple[float, float, bool]] = field(default_factory=dict,
                                                            repr=False)

    def _state(self, t: float) -> tuple[float, float, bool]:
        """``(W, phi, moving)``, remembered for the last few times (a step asks for the
        speed, angle and acceleration at the same times several times)."""
        hit = self._recent.get(t)
        if hit is None:
            if len(self._recent) >= 8:
                self._recent.clear()
            hit = self._recent[t] = self.history.state(t)
        return hit

    def speed(self, t: float) -> float:
        return self._state(t)[0]

    def angle(self, t: float) -> float:
        return self._state(t)[1]

    def acceleration(self, t: float) -> float:
        w, phi, moving = self._state(t)
        return net_torque(self.drive.torques, w, t, phi) / self.inertia if moving else 0.0

    def node_torques(self, t: float) -> tuple[np.ndarray, FloatArray]:
        """Nodes and signed torques on the shaft [N m] at ``t`` (motor +, loads -). At
        standstill the reactive loads share the holding torque in proportion to their
        breakaway values."""
        torques = self.drive.torques
        nodes = np.array([a.node for a in torques], dtype=np.int64)
        w, phi, moving = self._state(t)
        if moving:
            return nodes, np.array([a.value(w, t, phi) for a in torques])
        drive, breakaway = at_rest(torques, t, phi)
        values = np.array([a.value(0.0, t, phi) for a in torques])
        reactive = np.array([a.role != "motor" and a.law.reactive for a in torques])
        share = np.abs(values[reactive]) / breakaway if breakaway > 0 else 0.0
        values[reactive] = -drive * share
        return nodes, values

    def slopes(self, t: float) -> tuple[np.ndarray, FloatArray]:
        """Nodes and ``d(signed torque)/dW`` [N m s/rad] at ``t``: ``dT_m/dW`` at the
        drive node (negative: slip damping), ``-dT_L/dW`` at the load nodes."""
        w, phi, _ = self._state(t)
        torques = self.drive.torques
        return (np.array([a.node for a in torques], dtype=np.int64),
                np.array([a.sign * a.law.slope(w, t, phi) for a in torques]))

    def describe(self) -> dict[str, object]:
        d = self.drive
        segments = self.history.segments
        end = segments[-1].t_end
        return {
            "kind": "torque", "name": d.name, "inertia": self.inertia,
            "inertia_source": self.inertia_source, "model_inertia": self.model_inertia,
            "initial_speed": float(d.initial_speed), "phi0": float(d.phi0),
            "motor": {"node": d.torques[0].node, **d.torques[0].law.describe()},
            "loads": [{"node": a.node, **a.law.describe()} for a in d.torques
                      if a.role == "load"],
            "friction": [{"node": a.node, **a.law.describe()} for a in d.torques
                         if a.role == "friction"],
            "torque_damping": bool(d.torque_damping),
            "final_speed": self.speed(end), "stops": self.history.stops,
            "spin_evaluations": self.history.evaluations,
        }


def _node(value: Any, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 0:
        raise ModelError(f"must be a node number >= 0, got {value!r}", where)
    return int(value)


def _finite(value: Any, where: str) -> None:
    if not (isinstance(value, int | float) and not isinstance(value, bool)
            and math.isfinite(value)):
        raise ModelError(f"must be a finite number, got {value!r}", where)
