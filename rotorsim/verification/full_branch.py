"""The full model's own branch of periodic orbits, traced by shooting continuation.

Where a harmonic-balance branch folds several times within a fraction of a percent of the
speed (the lightly damped default model at its critical speed), the orbits of the
time-integrated model sit a little away from the truncated series', and a fold's middle
sheet may not exist at the speeds where harmonic balance has it: the point-wise check of
:mod:`~.shooting_sides` then finds no orbit next to it. This module traces the full model's
branch itself through such a stretch, by pseudo-arclength continuation
(:func:`rotorsim.solvers.continuation.continue_branch`) of

    R(z, W) = P(z; W) - z = 0,

``P`` the period map of the average-acceleration scheme at speed ``W`` over the period
``2 pi / (r W)`` (``r`` the branch's fundamental per unit speed), ``z = (q, v)`` on the free
DOFs that harmonic balance does not hold. ``dR/dz = Phi - I`` is exact
(:func:`~rotorsim.time_integration.sensitivity_flow.average_acceleration_flow`), ``dR/dW``
a forward difference (one period more). The multipliers at each point are the eigenvalues of
``Phi``; the branch's events are where it turns (folds) and where the number of
multipliers outside the unit circle changes (the kind from the multiplier that crossed).
:func:`match_events` pairs them in order with harmonic balance's events of the same
stretch.

References
----------
Seydel (2010), *Practical Bifurcation and Stability Analysis*, sections 4.1-4.5 (arclength
continuation), 7.1-7.4 (shooting, monodromy, multipliers); seed 002 eqs 3.39-3.42.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.results.periodic import PeriodicResult
from rotorsim.solvers.continuation import Branch, Continuation, continue_branch
from rotorsim.time_integration.sensitivity_flow import average_acceleration_flow
from rotorsim.verification.event_modes import KINDS
from rotorsim.verification.full_shooting import speed_problem
from rotorsim.verification.mode_growth import kind_of

FloatArray = NDArray[np.float64]
WHERE = "full_model_branch"


@dataclass(frozen=True)
class FullEvent:
    """An event of the full model's branch.

    Attributes
    ----------
    kind : str
        "fold", "period_doubling", "neimark_sacker" or "branch_point".
    index : int
        The event lies between points ``index`` and ``index + 1``.
    speed : float
        Mid-point of the two speeds [rad/s].
    multiplier : complex
        The multiplier that crossed (on the more unstable side); NaN for a fold without
        a crossing (a turn of the branch only).
    """

    kind: str
    index: int
    speed: float
    multiplier: complex


@dataclass(frozen=True, eq=False)
class FullBranch:
    """The full model's branch (module docstring).

    Attributes
    ----------
    speed : array (P,)
        [rad/s].
    states : array (P, 2 m)
        ``(q, v)`` at phase 0 on the unknowns [m, rad, m/s, rad/s].
    multipliers : complex array (P, 2 m)
        By decreasing modulus.
    events : tuple of FullEvent
    branch : Branch
        The continuation's record (status, reason, tangents, counters).
    """

    speed: FloatArray
    states: FloatArray
    multipliers: NDArray[np.complex128]
    events: tuple[FullEvent, ...]
    branch: Branch = field(repr=False)


class _PeriodMap:
    """``R(z, W)`` with its Jacobians; keeps ``Phi`` of the last evaluations."""

    def __init__(self, system: Any, result: PeriodicResult, run: dict[str, Any],
                 ratio: float) -> None:
        free = system.dof_map.free
        self.held = np.flatnonzero(np.isin(free, result.held_dofs)).astype(np.int64)
        self.system, self.run, self.ratio = system, run, ratio
        self.phi0 = float(result.options.get("shaft_angle", 0.0))
        self.monodromy: dict[bytes, FloatArray] = {}

    def problem(self, speed: float) -> Any:
        return speed_problem(self.system, speed, self.run["excitation"], self.phi0,
                             self.held)[0]

    def __call__(self, z: FloatArray, speed: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        n = z.size // 2
        steps = self.run["steps_per_period"]
        flow = average_acceleration_flow(self.problem(speed), z[:n], z[n:], 0.0,
                                         2.0 * np.pi / (self.ratio * speed), steps)
        assert flow.monodromy is not None
        delta = 1e-7 * speed
        moved = average_acceleration_flow(self.problem(speed + delta), z[:n], z[n:], 0.0,
                                          2.0 * np.pi / (self.ratio * (speed + delta)),
                                          steps, sensitivities=False)
        end = np.concatenate([flow.q, flow.v])
        d_speed = (np.concatenate([moved.q, moved.v]) - end) / delta
        if len(self.monodromy) > 64:
            self.monodromy.clear()
        self.monodromy[_key(z, speed)] = flow.monodromy
        return end - z, flow.monodromy - np.eye(z.size), d_speed


def _key(z: FloatArray, speed: float) -> bytes:
    return np.append(z, speed).tobytes()


def full_model_branch(system: Any, result: PeriodicResult, start: tuple[FloatArray, float],
                      stop: float, run: dict[str, Any], *, max_points: int = 400,
                      max_step: float = 0.05) -> FullBranch:
    """Trace the full model's branch from a converged orbit up to speed ``stop``.

    Parameters
    ----------
    system : RotorSystem
    result : PeriodicResult
        The harmonic-balance branch (its held DOFs, shaft angle and frequency ratio).
    start : (array (2 m,), float)
        A converged orbit ``z`` (e.g. :class:`~.full_shooting.FullOrbit`) and its speed
        [rad/s].
    stop : float
        The speed where the branch ends [rad/s] (> the start).
    run : dict
        ``system``, ``excitation``, ``steps_per_period`` of :func:`rotorsim.verify_events`.
    max_points : int
        Most points.
    max_step : float
        Largest scaled arclength step (unknowns scaled by the start orbit's size).

    Returns
    -------
    FullBranch
    """
    z0, w0 = np.asarray(start[0], dtype=float), float(start[1])
    if not stop > w0:
        raise ModelError(f"stop {stop!r} must lie above the start {w0!r}", WHERE)
    ratio = float(result.fundamental[0] / result.speed[0])
    residual = _PeriodMap(system, result, run, ratio)
    n = z0.size // 2
    scale_q = max(float(np.ptp(z0[:n])), 1e-30)
    scale_v = max(float(np.ptp(z0[n:])), 1e-30)
    x_scale = tuple([scale_q] * n + [scale_v] * n)
    options = Continuation(initial_step=0.2 * max_step, max_step=max_step, min_step=1e-5,
                           lam_min=w0 - 1e-9 * w0, lam_max=stop, max_points=max_points,
                           tol=1e-9, x_scale=x_scale, r_scale=x_scale,
                           lam_scale=stop - w0, detect_loops=False)
    branch = continue_branch(residual, z0, w0, options)
    multipliers = np.empty((len(branch.lam), 2 * n), dtype=complex)
    for p, (z, w) in enumerate(zip(branch.x, branch.lam, strict=True)):
        phi = residual.monodromy.get(_key(z, float(w)))
        if phi is None:
            phi = residual(z, float(w))[1] + np.eye(2 * n)
        mu = np.linalg.eigvals(phi)
        multipliers[p] = mu[np.argsort(-np.abs(mu), kind="stable")]
    return FullBranch(branch.lam.copy(), branch.x.copy(), multipliers,
                      _events(branch, multipliers), branch)


def _events(branch: Branch, multipliers: NDArray[np.complex128]) -> tuple[FullEvent, ...]:
    """Turns of the branch and changes of the number of multipliers outside the circle."""
    events = []
    outside = np.sum(np.abs(multipliers) > 1.0, axis=1)
    direction = np.sign(branch.tangents[:, -1])
    for i in range(len(branch.lam) - 1):
        mid = 0.5 * float(branch.lam[i] + branch.lam[i + 1])
        turned = direction[i] * direction[i + 1] < 0
        crossed = outside[i] != outside[i + 1]
        mu = complex("nan")
        if crossed:
            side = i if outside[i] > outside[i + 1] else i + 1
            out = multipliers[side][np.abs(multipliers[side]) > 1.0]
            mu = complex(out[np.argmin(np.abs(out))])
        if turned:
            events.append(FullEvent("fold", i, mid, mu))
        elif crossed:
            kind = {"fold or branch point": "branch_point"}.get(kind_of(mu), kind_of(mu))
            events.append(FullEvent(kind, i, mid, mu))
    return tuple(events)


def match_events(kinds: list[str], full: tuple[FullEvent, ...]) -> list[int | None]:
    """Pair harmonic balance's events (their ``kinds`` in branch order) with the full
    branch's in order: each takes the first unused full event of its kind class after the
    previous match (a fold or branch point matches either). Returns the index into
    ``full`` of each, None where none is left."""
    out: list[int | None] = []
    next_free = 0
    for kind in kinds:
        wanted = KINDS.get(kind, kind)
        hit = None
        for j in range(next_free, len(full)):
            if KINDS.get(full[j].kind, full[j].kind) == wanted:
                hit = j
                break
        out.append(hit)
        if hit is not None:
            next_free = hit + 1
    return out


def describe(full: FullBranch) -> str:
    """One line per event of the full branch."""
    lines = []
    for e in full.events:
        mu = "" if not math.isfinite(abs(e.multiplier)) else f", multiplier {e.multiplier:.5g}"
        lines.append(f"{e.kind} at {e.speed:.6g} rad/s (points {e.index}-{e.index + 1}{mu})")
    return "\n".join(lines)
