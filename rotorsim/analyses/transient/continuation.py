"""Continue a finished rotor transient: ``rs.transient(model, t_end, dt,
initial=previous)``.

A :class:`~rotorsim.results.transient.TransientResult` carries its final
:class:`~rotorsim.results.transient_state.TransientState`: the physical state of all free
DOFs, the shaft angle and speed, and the stepper's own state (for Newmark ``q``, ``v``,
``a``; for the Adams method also its acceleration history), in the coordinates the stepper
integrated. A continuation

- runs over ``(previous.t, t_end)``;
- keeps the shaft angle continuous: the speed profile's start angle ``phi0`` becomes the
  previous final angle, so ``phi(t0)`` equals it exactly (the speed at ``t0`` must equal
  the previous final speed: a jump in speed is refused);
- restores the stepper state as it was, so the continued samples equal those of an
  uninterrupted run up to round-off (docs/validation.md);
- refuses another model, DOF count, method or reduced basis, or a start time other than
  the previous end, with a :class:`~rotorsim.errors.ModelError` naming what differs.

The loads (unbalance, gravity, forces) are not compared: they are the caller's.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from rotorsim.analyses.transient.speed_profile import BoundSpeed
from rotorsim.assembly.reduction import ReducedBasis
from rotorsim.assembly.system import RotorSystem
from rotorsim.errors import ModelError
from rotorsim.results.transient import TransientResult
from rotorsim.results.transient_state import TransientState
from rotorsim.time_integration.base import State, TimeStepper
from rotorsim.time_integration.integrate import IntegrationResult
from rotorsim.time_integration.problem import FINGERPRINT_VERSION, SecondOrderProblem

WHERE = "transient.initial"
SPEED_RTOL = 1e-9
"""Relative mismatch allowed between the previous final speed and the continued profile's
speed at its start (both are evaluated by the same formulas: equal up to round-off)."""


def previous_state(initial: Any) -> TransientState | None:
    """The final state to continue from when ``initial`` is a result (or its state)."""
    if isinstance(initial, TransientResult):
        if initial.final is None:
            raise ModelError("this result carries no final state (written by an older "
                             "rotorsim?): it cannot be continued", WHERE)
        return initial.final
    return initial if isinstance(initial, TransientState) else None


def continued_span(previous: TransientState, t_end: float | Sequence[float]
                   ) -> tuple[float, float]:
    """``(previous.t, t_end)``; a given start must be the previous end."""
    if np.ndim(t_end) == 0:
        t0, end = previous.t, float(t_end)  # type: ignore[arg-type]
    else:
        t0, end = (float(x) for x in t_end)  # type: ignore[union-attr]
        if t0 != previous.t:
            raise ModelError(f"the previous run ended at t = {previous.t!r} s; its "
                             f"continuation starts there, not at {t0!r} s",
                             "transient.t_end")
    if not (math.isfinite(end) and end > t0):
        raise ModelError(f"t_end ({end!r} s) must be after the end of the previous run "
                         f"({t0!r} s)", "transient.t_end")
    return t0, end


def continued_speed(profile: Any, previous: TransientState) -> Any:
    """The profile starting at the previous final angle (its ``phi0`` replaced); a torque
    drive also starts from the previous final speed (its ``initial_speed``)."""
    if not dataclasses.is_dataclass(profile) or isinstance(profile, type):
        return profile
    names = {f.name for f in dataclasses.fields(profile)}
    changes: dict[str, float] = {}
    if "phi0" in names:
        changes["phi0"] = previous.angle
    if "initial_speed" in names:
        changes["initial_speed"] = previous.speed
    return dataclasses.replace(profile, **changes) if changes else profile


def check_start(previous: TransientState, system: RotorSystem, profile: BoundSpeed,
                t0: float) -> None:
    """Refuse a continuation on another DOF count, or with a jump in speed or angle."""
    if previous.q.shape != (system.n_free,):
        raise ModelError(f"the previous run has {previous.q.size} free DOFs, this model "
                         f"{system.n_free}: continue on the same model", WHERE)
    speed, angle = profile.speed(t0), profile.angle(t0)
    if abs(speed - previous.speed) > SPEED_RTOL * max(abs(previous.speed), 1.0):
        raise ModelError(f"the speed at t = {t0!r} s is {speed!r} rad/s, the previous run "
                         f"ended at {previous.speed!r} rad/s: give a speed schedule that "
                         f"continues it", "transient.speed")
    if abs(angle - previous.angle) > SPEED_RTOL * max(abs(previous.angle), 1.0):
        raise ModelError(f"the shaft angle at t = {t0!r} s is {angle!r} rad, the previous "
                         f"run ended at {previous.angle!r} rad", "transient.speed")


def start_state(previous: TransientState, full: Any,
                problem: SecondOrderProblem, stepper: TimeStepper, dt: float,
                basis: ReducedBasis | None) -> State:
    """The stepper state to continue from, after checking model, method and basis."""
    if stepper.name != previous.method:
        raise ModelError(f"the previous run used {previous.method!r}, not "
                         f"{stepper.name!r}: continue with the same method", "transient.method")
    if not previous.problem.startswith(FINGERPRINT_VERSION):
        raise ModelError("the previous state was stored by an older rotorsim, whose model "
                         "fingerprint cannot be compared: run it again", WHERE)
    if full.fingerprint != previous.problem:
        raise ModelError("the model differs from the previous run's (its mass, stiffness, "
                         "damping or gyroscopic matrices, or which loads and nonlinear "
                         "elements it has): continue on the same model", WHERE)
    size = 0 if basis is None else basis.size
    if size != previous.reduction or previous.stepper.q.shape != (problem.n,):
        raise ModelError(f"the previous run integrated {previous.stepper.q.size} "
                         f"{'reduced ' if previous.reduction else ''}coordinates, this one "
                         f"{problem.n}: give the same reduction", "transient.reduction")
    return dataclasses.replace(previous.stepper, dt=dt)


def final_state(run: IntegrationResult, full: Any,
                problem: SecondOrderProblem, basis: ReducedBasis | None,
                profile: BoundSpeed, dt: float, reduction_speed: float) -> TransientState:
    """The run's final state: physical on all free DOFs, and the stepper's as it is."""
    s = run.state
    T = None if basis is None else basis.T
    q, v, a = (x if T is None else T @ x for x in (s.q, s.v, s.a))
    return TransientState(
        t=float(s.t), q=np.array(q), v=np.array(v), a=np.array(a),
        angle=float(profile.angle(s.t)), speed=float(profile.speed(s.t)),
        method=run.method, dt=float(dt), problem=full.fingerprint,
        reduction=0 if basis is None else basis.size, reduction_speed=float(reduction_speed),
        stepper=dataclasses.replace(s, cache=None))
