"""The rigid spin equation of a torque-driven rotor, integrated once over the whole span.

``J_p W' = T_motor(W, t, phi) - sum T_load(W, t, phi) - sum T_friction(W, t, phi)``,
``phi' = W`` (Genta, *Dynamics of Rotating Systems*, Springer 2005, on the equation of
motion about the spin axis of a rotor driven by a torque; Friswell et al., *Dynamics of
Rotating Machines*, CUP 2010, ch. 2 on torsional systems driven by a torque), integrated by
scipy's ``solve_ivp`` (DOP853, ``rtol`` 1e-10) with dense output, so ``W(t)``, ``W'(t)``
and ``phi(t)`` are known to about 1e-10 wherever the transient asks.

Standstill: the speed never goes negative (DESIGN section 3: ``W >= 0``). When a
coast-down reaches ``W = 0`` (an event of the integration), the rotor stops and stays
stopped while the drive torque at rest ``T_m(0) - sum T_active(0)`` lies within the
breakaway torque of the reactive loads ``sum |T_reactive(0)|`` (static friction); it starts
again when the drive torque exceeds it, and a drive torque below ``-breakaway`` would turn
the rotor backwards: a :class:`~rotorsim.errors.ModelError` naming the drive.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from rotorsim.analyses.transient.torque_laws import TorqueLaw
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError

RTOL = 1e-10
"""Relative tolerance of the spin integration."""
MAX_SEGMENTS = 1000
"""Most stop/start segments in one run."""


@dataclass(frozen=True)
class AppliedTorque:
    """A torque law acting at ``node``: ``role`` ``"motor"`` (drives, sign +1), ``"load"``
    or ``"friction"`` (oppose, sign -1); ``label`` names it in messages."""

    node: int
    law: TorqueLaw
    role: str
    label: str

    @property
    def sign(self) -> float:
        return 1.0 if self.role == "motor" else -1.0

    def value(self, speed: float, t: float, angle: float) -> float:
        """Signed torque on the shaft [N m]; a non-finite value is a ModelError."""
        v = float(self.law.torque(speed, t, angle))
        if not math.isfinite(v):
            raise ModelError(f"torque is {v!r} at W = {speed:.6g} rad/s, t = {t:.6g} s",
                             self.label)
        return self.sign * v


@dataclass(frozen=True)
class Segment:
    """``t_start..t_end`` moving (``solution`` the dense output of ``[W, phi]``) or
    stopped at ``angle``."""

    t_start: float
    t_end: float
    solution: Any = None
    angle: float = 0.0

    @property
    def moving(self) -> bool:
        return self.solution is not None


@dataclass(frozen=True, eq=False)
class SpinHistory:
    """``W(t)``, ``phi(t)`` of the rigid spin as a list of segments."""

    segments: tuple[Segment, ...]
    evaluations: int

    @cached_property
    def _starts(self) -> FloatArray:
        return np.array([s.t_start for s in self.segments])

    def segment(self, t: float) -> Segment:
        if len(self.segments) == 1:
            return self.segments[0]
        i = max(int(np.searchsorted(self._starts, t, side="right")) - 1, 0)
        return self.segments[i]

    def state(self, t: float) -> tuple[float, float, bool]:
        """``(W, phi, moving)`` at ``t`` (held at the ends outside the span)."""
        t = min(max(t, self.segments[0].t_start), self.segments[-1].t_end)
        seg = self.segment(t)
        if not seg.moving:
            return 0.0, seg.angle, False
        y = seg.solution(t)
        return max(float(y[0]), 0.0), float(y[1]), True

    @property
    def stops(self) -> list[float]:
        """Times at which the rotor came to rest [s]."""
        return [s.t_start for s in self.segments if not s.moving]


def net_torque(torques: Sequence[AppliedTorque], speed: float, t: float,
               angle: float) -> float:
    """``T_motor - sum T_load - sum T_friction`` [N m]."""
    return sum(a.value(speed, t, angle) for a in torques)


def at_rest(torques: Sequence[AppliedTorque], t: float, angle: float
            ) -> tuple[float, float]:
    """``(drive, breakaway)`` at standstill: the torque of the motor and the active loads,
    and the sum of the reactive loads' magnitudes at ``W = 0`` [N m]."""
    drive, breakaway = 0.0, 0.0
    for a in torques:
        v = a.value(0.0, t, angle)
        if a.role != "motor" and a.law.reactive:
            breakaway += abs(v)
        else:
            drive += v
    return drive, breakaway


def integrate_spin(torques: Sequence[AppliedTorque], inertia: float, span: tuple[float, float],
                   start: tuple[float, float], resolution: int, where: str) -> SpinHistory:
    """Integrate the spin equation over ``span`` from ``start = (W0, phi0)``.

    ``resolution`` sets the largest step of a stopped segment (whose only job is to find
    when the drive breaks away), ``(t_end - t0) / resolution``.
    """
    t, t_end = span
    speed, angle = start
    max_step = (t_end - t) / max(int(resolution), 16)
    segments: list[Segment] = []
    evaluations = 0
    for _ in range(MAX_SEGMENTS):
        drive, breakaway = at_rest(torques, t, angle)
        if speed <= 0.0 and drive < -breakaway:
            raise ModelError(f"at rest at t = {t:.6g} s the drive torque {drive:.6g} N m "
                             f"overcomes the breakaway torque {breakaway:.6g} N m of the "
                             "reactive loads backwards: the rotor would turn backwards "
                             "(rotorsim spins about +z only, W >= 0)", where)
        if speed > 0.0 or drive > breakaway:
            seg, nfev = _moving(torques, inertia, (t, t_end), (speed, angle), where)
            speed, angle = 0.0, float(seg.solution(seg.t_end)[1])
        else:
            seg, nfev = _stopped(torques, (t, t_end), angle, max_step, where)
            if seg.t_end <= t:  # at the breakaway torque exactly: it moves
                seg, nfev = _moving(torques, inertia, (t, t_end), (0.0, angle), where)
                speed, angle = 0.0, float(seg.solution(seg.t_end)[1])
        evaluations += nfev
        segments.append(seg)
        t = seg.t_end
        if t >= t_end:
            return SpinHistory(tuple(segments), evaluations)
    raise ModelError(f"more than {MAX_SEGMENTS} stops and restarts of the rotor", where)


def _moving(torques: Sequence[AppliedTorque], inertia: float, span: tuple[float, float],
            start: tuple[float, float], where: str) -> tuple[Segment, int]:
    from scipy.integrate import solve_ivp

    def rhs(t: float, y: FloatArray) -> list[float]:
        return [net_torque(torques, float(y[0]), t, float(y[1])) / inertia, float(y[0])]

    def stopped(t: float, y: FloatArray) -> float:
        return float(y[0])

    stopped.terminal = True  # type: ignore[attr-defined]
    stopped.direction = -1.0  # type: ignore[attr-defined]
    scale = max(1.0, abs(start[0]))
    atol = [RTOL * 1e-2 * scale, RTOL * 1e-2 * scale * (span[1] - span[0])]
    sol = solve_ivp(rhs, span, list(start), method="DOP853", rtol=RTOL, atol=atol,
                    dense_output=True, events=stopped)
    if sol.status < 0:
        raise ModelError(f"integration of the spin equation failed: {sol.message}", where)
    t_stop = float(sol.t_events[0][0]) if sol.t_events[0].size else float(sol.t[-1])
    return Segment(span[0], t_stop, sol.sol), int(sol.nfev)


def _stopped(torques: Sequence[AppliedTorque], span: tuple[float, float], angle: float,
             max_step: float, where: str) -> tuple[Segment, int]:
    """Standstill until the drive breaks away (or the span ends)."""
    from scipy.integrate import solve_ivp

    def breaks_away(t: float, y: FloatArray) -> float:
        drive, breakaway = at_rest(torques, t, angle)
        return drive - breakaway

    def turns_back(t: float, y: FloatArray) -> float:
        drive, breakaway = at_rest(torques, t, angle)
        return drive + breakaway

    for event, direction in ((breaks_away, 1.0), (turns_back, -1.0)):
        event.terminal = True  # type: ignore[attr-defined]
        event.direction = direction  # type: ignore[attr-defined]
    sol = solve_ivp(lambda t, y: [0.0], span, [angle], method="RK23", max_step=max_step,
                    events=(breaks_away, turns_back))
    t_next = float(sol.t[-1])
    return Segment(span[0], t_next, None, angle), int(sol.nfev)
