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

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError, Status
from rotorsim.results.event_verification import EventCheck
from rotorsim.results.periodic import PeriodicResult
from rotorsim.solvers.continuation import Branch, Continuation, continue_branch
from rotorsim.solvers.threads import one_blas_thread
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.sensitivity_flow import average_acceleration_flow
from rotorsim.verification import shooting_sides
from rotorsim.verification.event_modes import KINDS
from rotorsim.verification.full_shooting import speed_problem
from rotorsim.verification.mode_growth import kind_of
from rotorsim.verification.shooting_sides import NEUTRAL

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


ProblemAt = Callable[[float], SecondOrderProblem]
"""``problem_at(W)``: the equation of motion at the parameter ``W`` (e.g. the speed)."""


class _PeriodMap:
    """``R(z, W)`` with its Jacobians; keeps ``Phi`` of the last evaluations."""

    def __init__(self, problem_at: ProblemAt, period_at: Callable[[float], float],
                 steps: int) -> None:
        self.problem_at, self.period_at, self.steps = problem_at, period_at, steps
        self.monodromy: dict[bytes, FloatArray] = {}

    def __call__(self, z: FloatArray, w: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        n = z.size // 2
        flow = average_acceleration_flow(self.problem_at(w), z[:n], z[n:], 0.0,
                                         self.period_at(w), self.steps)
        assert flow.monodromy is not None
        delta = 1e-7 * max(abs(w), 1e-300)
        moved = average_acceleration_flow(self.problem_at(w + delta), z[:n], z[n:], 0.0,
                                          self.period_at(w + delta), self.steps,
                                          sensitivities=False)
        end = np.concatenate([flow.q, flow.v])
        d_w = (np.concatenate([moved.q, moved.v]) - end) / delta
        if len(self.monodromy) > 64:
            self.monodromy.clear()
        self.monodromy[_key(z, w)] = flow.monodromy
        return end - z, flow.monodromy - np.eye(z.size), d_w


def _key(z: FloatArray, w: float) -> bytes:
    return np.append(z, w).tobytes()


@one_blas_thread()   # small dense and banded work per time step: no BLAS threads
def shooting_branch(problem_at: ProblemAt, period_at: Callable[[float], float],
                    start: tuple[FloatArray, float], stop: float, *, steps: int = 200,
                    max_points: int = 400, max_step: float = 0.05) -> FullBranch:
    """Trace the periodic orbits of ``problem_at(W)`` with period ``period_at(W)`` from a
    converged orbit up to the parameter ``stop`` (module docstring).

    Parameters
    ----------
    problem_at : callable
        ``problem_at(W) -> SecondOrderProblem``, periodic in time with ``period_at(W)``.
    period_at : callable
        ``period_at(W) -> T`` [s].
    start : (array (2 m,), float)
        A converged orbit ``z = (q, v)`` at ``t = 0`` (e.g. of
        :func:`~.full_shooting.shoot_full_model`) and its parameter ``W``.
    stop : float
        Where the branch ends (above the start): it ends when ``W`` reaches it, or below
        the start.
    steps : int
        Average-acceleration steps per period.
    max_points : int
        Most points.
    max_step : float
        Largest arclength step, the unknowns scaled by the start orbit's largest
        displacement and velocity, ``W`` by ``stop - W0``.

    Returns
    -------
    FullBranch
    """
    z0, w0 = np.asarray(start[0], dtype=float), float(start[1])
    if not stop > w0:
        raise ModelError(f"stop {stop!r} must lie above the start {w0!r}", WHERE)
    residual = _PeriodMap(problem_at, period_at, int(steps))
    n = z0.size // 2
    scale_q = max(float(np.max(np.abs(z0[:n]))), 1e-30)
    scale_v = max(float(np.max(np.abs(z0[n:]))), 1e-30)
    x_scale = tuple([scale_q] * n + [scale_v] * n)
    options = Continuation(initial_step=0.2 * max_step, max_step=max_step, min_step=1e-5,
                           lam_min=w0 - 1e-9 * abs(w0), lam_max=stop, max_points=max_points,
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


def full_model_branch(system: Any, result: PeriodicResult, start: tuple[FloatArray, float],
                      stop: float, run: dict[str, Any], *, max_points: int = 400,
                      max_step: float = 0.05) -> FullBranch:
    """:func:`shooting_branch` of the full rotor model in speed: the equation of motion of
    :func:`~.full_shooting.speed_problem` without the branch's held DOFs, with the branch's
    excitation and shaft angle, period ``2 pi / (r W)`` (``r`` the branch's fundamental
    per unit speed); ``run`` holds ``excitation`` and ``steps_per_period``."""
    held = np.flatnonzero(np.isin(system.dof_map.free, result.held_dofs)).astype(np.int64)
    phi0 = float(result.options.get("shaft_angle", 0.0))
    ratio = float(result.fundamental[0] / result.speed[0])

    def problem_at(w: float) -> SecondOrderProblem:
        return speed_problem(system, w, run["excitation"], phi0, held)[0]

    return shooting_branch(problem_at, lambda w: 2.0 * np.pi / (ratio * w), start, stop,
                           steps=run["steps_per_period"], max_points=max_points,
                           max_step=max_step)


_KIND_CLASSES = ("fold or branch point", "period_doubling", "neimark_sacker")


def _outside(mu: NDArray[np.complex128]) -> NDArray[np.int64]:
    """Multipliers outside the unit circle per kind class (real positive, real negative,
    complex); neutral ones (within ``NEUTRAL`` of the circle) do not count."""
    out = mu[np.abs(mu) > 1.0 + NEUTRAL]
    real = out.imag == 0.0
    return np.array([np.sum(real & (out.real > 0)), np.sum(real & (out.real < 0)),
                     np.sum(~real)], dtype=np.int64)


def _events(branch: Branch, multipliers: NDArray[np.complex128]) -> tuple[FullEvent, ...]:
    """Turns of the branch and changes of the number of multipliers outside the circle.

    Turns in consecutive intervals are one turn when their number is odd and none when it
    is even (the corrector's jitter at a turning point). A change of the count is an event
    of the kind class whose count changed with the total (a complex pair splitting into two
    real multipliers outside the circle changes no total: no event); a real crossing within
    :data:`NEAR` intervals of a turn is the fold's own, and two crossings of one kind that
    undo each other within :data:`NEAR` intervals are none."""
    counts = np.array([_outside(mu) for mu in multipliers])
    direction = np.sign(branch.tangents[:, -1])
    turns = [i for i in range(len(branch.lam) - 1) if direction[i] * direction[i + 1] < 0]
    folds: list[int] = []
    run: list[int] = []
    for i in [*turns, -10]:
        if run and i != run[-1] + 1:
            if len(run) % 2:
                folds.append(run[len(run) // 2])
            run = []
        run.append(i)
    events: list[tuple[FullEvent, int]] = []      # with the sign of the count's change
    for i in range(len(branch.lam) - 1):
        mid = 0.5 * float(branch.lam[i] + branch.lam[i + 1])
        change = counts[i + 1] - counts[i]
        total = int(change.sum())
        mu = complex("nan")
        kind = ""
        if total:
            k = int(np.argmax(change * np.sign(total)))
            kind = _KIND_CLASSES[k]
            side = i if total < 0 else i + 1
            out = multipliers[side][np.abs(multipliers[side]) > 1.0 + NEUTRAL]
            of_kind = [m for m in out if kind_of(complex(m)) == kind]
            mu = complex(min(of_kind, key=abs)) if of_kind else mu
        if i in folds:
            events.append((FullEvent("fold", i, mid, mu if kind == _KIND_CLASSES[0] else
                                     complex("nan")), 0))
        elif kind == _KIND_CLASSES[0] and any(abs(i - f) <= NEAR for f in folds):
            continue       # the fold's own real multiplier through +1, next to its turn
        elif kind:
            events.append((FullEvent({"fold or branch point": "branch_point"}.get(kind, kind),
                                     i, mid, mu), int(np.sign(total))))
    return tuple(e for e, _ in _without_returns(events))


NEAR = 3
"""Intervals within which a crossing next to a turn is the fold's own, and a crossing
undone by the opposite one of the same kind is a multiplier grazing the circle."""


def _without_returns(events: list[tuple[FullEvent, int]]) -> list[tuple[FullEvent, int]]:
    """Drop pairs of consecutive crossings of the same kind that undo each other within
    :data:`NEAR` intervals (a multiplier at the circle to the precision of the point
    spacing, e.g. next to a turn), repeatedly."""
    out: list[tuple[FullEvent, int]] = []
    for e, sign in events:
        if out and sign and out[-1][1] == -sign and out[-1][0].kind == e.kind \
                and e.index - out[-1][0].index <= NEAR:
            out.pop()
            continue
        out.append((e, sign))
    return out


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


def trace_unconfirmed(result: PeriodicResult, checks: list[EventCheck], run: dict[str, Any],
                      shots: dict[int, Any], max_points: int = 600,
                      notes: list[str] | None = None) -> list[EventCheck]:
    """The events ``checks`` leaves unconfirmed, checked against the full model's branch
    traced from a converged orbit before the first of them to beyond the last
    (``verify_events(..., measure="shooting", trace=True)``).

    The stretch starts at the nearest branch point before the first unconfirmed event
    whose orbit shooting found (``shots``, or shot now), and ends past the last one at the
    first point faster than every point of the stretch. Harmonic balance's events of the
    stretch are matched in order with the full branch's (:func:`match_events`); an
    unconfirmed event with a match of its kind is confirmed, with both speeds in its
    reason. ``notes`` receives the trace's span and every event of the full branch."""

    open_ = [c for c in checks if not c.confirmed]
    if not open_:
        return checks
    marks = [result.bifurcations[c.number].index for c in open_]
    start = None
    for p in range(min(marks), max(-1, min(marks) - 4 * run["reach"]), -1):
        if p not in shots:
            shots[p] = shooting_sides.shoot_point(result, p, run)
        if not isinstance(shots[p], str):
            start = p
            break
    speeds = np.asarray(result.speed, dtype=float)
    end = next((p for p in range(max(marks) + 1, len(result))
                if start is not None and speeds[p] > speeds[start:p].max()), None)
    if start is None or end is None:
        where = "before the first" if start is None else "after the last"
        return _with_note(checks, f"no branch point {where} unconfirmed event to trace the "
                          "full model's branch from or to")
    orbit = shots[start]
    full = full_model_branch(run["system"], result,
                             (np.concatenate([orbit.q, orbit.v]), float(speeds[start])),
                             float(speeds[end]), run, max_points=max_points)
    stretch = sorted((k for k, b in enumerate(result.bifurcations)
                      if start <= b.index < end), key=lambda k: result.bifurcations[k].index)
    span = (f"the full model's branch traced by shooting from {speeds[start]:.6g} to "
            f"{speeds[end]:.6g} rad/s ({len(full.speed)} points)")
    if notes is not None:
        notes.append(f"{span}: {_listing(full)}")
    if full.branch.status != Status.OK or not full.speed[-1] >= speeds[end] * (1 - 1e-12):
        return _with_note(checks, f"{span} stopped: {full.branch.reason}")
    found = dict(zip(stretch, match_events([result.bifurcations[k].kind for k in stretch],
                                           full.events), strict=True))
    out = []
    for c in checks:
        j = found.get(c.number)
        if c.confirmed or c.number not in found:
            out.append(c)
        elif j is None:
            out.append(dataclasses.replace(c, reason=f"{c.reason}; {span} has no "
                                           f"{c.event.kind.replace('_', ' ')} in its place "
                                           f"(events: {_listing(full)})"))
        else:
            e = full.events[j]
            mu = "" if not math.isfinite(abs(e.multiplier)) else \
                f", multiplier {e.multiplier.real:.5g}" if e.multiplier.imag == 0 else \
                f", |multiplier| {abs(e.multiplier):.5g}"
            out.append(dataclasses.replace(
                c, confirmed=True,
                reason=f"{span} has its {e.kind.replace('_', ' ')} in the same place of the "
                       f"sequence at {e.speed:.6g} rad/s ({e.speed - c.event.parameter:+.3g} "
                       f"rad/s from harmonic balance's{mu}); point-wise: {c.reason}"))
    return out


def _with_note(checks: list[EventCheck], note: str) -> list[EventCheck]:
    return [c if c.confirmed else dataclasses.replace(c, reason=f"{c.reason}; {note}")
            for c in checks]


def _listing(full: FullBranch) -> str:
    return ", ".join(f"{e.kind} {e.speed:.6g}" for e in full.events) or "none"
