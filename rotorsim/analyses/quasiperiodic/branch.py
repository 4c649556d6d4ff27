"""``rs.quasi_periodic``: quasi-periodic unbalance responses over a speed range, by
pseudo-arclength continuation of the torus in the speed, with the torus's stability at
every point (issue 17).

The shaft and VC frequencies both follow the speed (``w2 = Z kappa W``). The torus's
bearing coefficients and the speed are continued together
(:func:`~rotorsim.solvers.continuation.continue_branch` on
:class:`~rotorsim.analyses.quasiperiodic.continuation.SpeedResidual`): where a lightly
damped resonance on Hertzian contacts bends over, the branch turns back at a fold and
carries on, as the periodic branches do. Scales: the unknowns by the largest coefficient
at the start, the residual by its Jacobian's row norms, the speed by the range; the
largest step is ``step / (stop - start)`` of that scaled arclength, times the size of the
response relative to the start (steps follow the growing orbit through a resonance). A
branch that stops (the step fell below its minimum: no torus beyond, or a torus breaking
up) says where and why, keeping what it has.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.quasiperiodic.branch_stability import branch_stability
from rotorsim.analyses.quasiperiodic.continuation import SpeedResidual
from rotorsim.analyses.quasiperiodic.point import (
    QuasiPeriodicPoint,
    solve_at,
    system_of,
    torus_of,
)
from rotorsim.analyses.quasiperiodic.problem import WHERE, RotorQuasiProblem
from rotorsim.analyses.quasiperiodic.refine import MAX_REFINEMENTS, StallWatch, finer
from rotorsim.analyses.quasiperiodic.stability import STABILITY_TOL, TorusStability
from rotorsim.errors import ModelError, Status
from rotorsim.harmonic_balance.quasi import QuasiSolution, TorusAFT
from rotorsim.options import Excitation
from rotorsim.solvers.continuation import Continuation, continue_branch
from rotorsim.solvers.threads import one_blas_thread

FloatArray = NDArray[np.float64]
BEYOND = (40, 60)
"""Default shaft revolutions settled and recorded by the transient run at each loss of
stability (issue 17 part 2: measured on the textbook rigid rotor, whose motions past the
loss settle within 10 revolutions and whose doubled and third-order tones need 20 to 40
recorded revolutions to be told apart)."""
STALL_TOL = 1e-6
"""Scaled residual at which a stalled corrector is accepted (contact onsets make the
residual non-smooth, as on periodic branches)."""


@dataclass(frozen=True, eq=False)
class QuasiPeriodicBranch:
    """Tori over speed.

    Attributes
    ----------
    points : tuple of QuasiPeriodicPoint
    exponents : array (P,)
        Largest real part of each torus's characteristic exponents [1/s] (the Hill
        method, or the largest Lyapunov exponent with ``stability="lyapunov"``; NaN when
        not computed).
    status : str
        ``"ok"`` (reached ``stop``) or ``"stopped"``.
    reason : str
        Why the branch stopped (empty when it reached ``stop``).
    unbalance, excitation
        Those of the tori (the transients of :attr:`beyond` use them).
    beyond : (int, int) or None
        Revolutions settled and recorded by the transient run at each loss of stability
        (:func:`~rotorsim.analyses.quasiperiodic.beyond.motion_beyond`); None: not run.
    """

    points: tuple[QuasiPeriodicPoint, ...]
    exponents: FloatArray
    status: str
    reason: str
    stability: tuple[TorusStability | None, ...] = ()
    stability_time: float = 0.0
    unbalance: tuple[tuple[int, float, float], ...] = ()
    excitation: Excitation | None = None
    beyond: tuple[int, int] | None = None

    @property
    def speeds(self) -> FloatArray:
        """[rad/s]."""
        return np.array([p.speed for p in self.points])

    @property
    def stable(self) -> NDArray[np.bool_]:
        """Growth per shaft revolution below :data:`~.stability.STABILITY_TOL` (False where
        the exponent was not computed)."""
        growth = np.nan_to_num(self.exponents, nan=np.inf) * 2 * np.pi / self.speeds
        return np.asarray(growth < STABILITY_TOL)

    def amplitude(self, node: int, dof: str, k1: int, k2: int) -> FloatArray:
        """Amplitude of the tone ``k1 W + k2 w2`` of ``(node, dof)`` at every speed."""
        return np.array([p.amplitude(node, dof, k1, k2) for p in self.points])

    def __len__(self) -> int:
        return len(self.points)


@one_blas_thread()   # small dense work throughout: Jacobians, bordered LU, Hill matrices
def quasi_periodic(model: Any, *, start: float, stop: float, step: float | None = None,
                   unbalance: Sequence[tuple[int, float, float]] = (),
                   harmonics: int | tuple[int, int] = (10, 3), truncation: str = "box",
                   samples: tuple[int, int] | None = None,
                   excitation: Excitation | None = None, nonlinear: Sequence[Any] = (),
                   stability: bool | str = True, periods: int = 40, tol: float = 1e-9,
                   max_points: int = 1000, beyond: tuple[int, int] | None = BEYOND
                   ) -> QuasiPeriodicBranch:
    """Quasi-periodic responses from ``start`` to ``stop`` [rad/s] (module docstring).

    Parameters
    ----------
    step : float, optional
        Largest step [rad/s] where the response is flat (default 1/50 of the range).
    harmonics, truncation, samples, excitation, nonlinear, tol
        As :func:`~rotorsim.analyses.quasiperiodic.point.quasi_periodic_point` (default
        box ``(10, 3)``: ten harmonics of the shaft frequency, three of the VC frequency).
    stability : bool or {"hill", "lyapunov"}
        Stability of every torus: its characteristic exponents by the quasi-periodic
        Hill method (True or "hill"; :meth:`QuasiPeriodicPoint.exponents`), or its
        largest Lyapunov exponent over ``periods`` revolutions ("lyapunov"; its
        resolution is about ``1 / T``, too coarse for very light damping); False: none.
    max_points : int
        Points of the branch at most.
    beyond : (int, int) or None
        Shaft revolutions settled and recorded by the transient that finds what the motion
        is where a torus loses stability (:class:`~rotorsim.results.torus_motion.
        MotionBeyond`, attached to the event by the result); None: not run (each run
        integrates the full model for their sum).

    Raises
    ------
    ModelError
        Bad range or step, or a model the point solver refuses.
    ConvergenceError
        The first point does not converge.
    """
    for name, value in (("start", start), ("stop", stop)):
        if not (np.isfinite(value) and value > 0):
            raise ModelError(f"must be a positive speed [rad/s], got {value!r}",
                             f"{WHERE}.{name}")
    if stop == start:
        raise ModelError("start and stop are equal", WHERE)
    span = abs(stop - start)
    h = span / 50 if step is None else float(step)
    if not (np.isfinite(h) and 0 < h <= span):
        raise ModelError(f"step must be in (0, {span:g}] rad/s, got {step!r}", f"{WHERE}.step")
    if beyond is not None and not (len(beyond) == 2 and int(beyond[0]) >= 0
                                   and int(beyond[1]) >= 4):
        raise ModelError(f"beyond must be (settle >= 0, record >= 4) revolutions or None, "
                         f"got {beyond!r}", f"{WHERE}.beyond")
    if stability not in (True, False, "hill", "lyapunov"):
        raise ModelError(f"stability must be True, False, 'hill' or 'lyapunov', got "
                         f"{stability!r}", f"{WHERE}.stability")
    system = system_of(model, nonlinear)
    torus = torus_of(harmonics, truncation)
    aft = TorusAFT(torus, samples)
    ex = excitation if excitation is not None else Excitation()
    unbalance = tuple(unbalance) or tuple(ex.unbalance or ())
    first = solve_at(system, float(start), torus, aft, ex, unbalance, tol)
    fun = SpeedResidual(system, first.rotor_problem, aft, unbalance)
    nl = np.asarray(first.rotor_problem.problem.nl_dofs)
    x0 = first.solution.X[:, nl].ravel()
    options = Continuation(
        initial_step=min(0.5 * h, h) / span, max_step=h / span, min_step=1e-6,
        direction=1 if stop > start else -1, lam_min=min(start, stop),
        lam_max=max(start, stop), max_points=int(max_points), tol=tol,
        x_scale=float(np.abs(x0).max(initial=0.0)) or 1.0, r_scale="auto", lam_scale=span,
        relative_step=True, stall_tol=max(STALL_TOL, tol))
    points, branch, refined = _segments(fun, first, x0, float(start), options)
    status = "ok" if branch.status == Status.OK else "stopped"
    end = float(branch.lam[-1])
    reason = ""
    if status != "ok" or abs(end - stop) > 1e-9 * max(abs(stop), 1.0):  # short of stop
        hint = ", raise max_points" if branch.reason == "max_points reached" else ""
        reason = f"{branch.reason or 'ended'} (at {end:.6g} rad/s, stop {stop:.6g}{hint})"
    if refined:
        reason = (reason + "; " if reason else "") + refined
    clock = time.perf_counter()
    checks: list[TorusStability | None] = [None] * len(points)
    if stability == "lyapunov":
        exponents = np.array([p.stability(periods=periods).exponent for p in points])
    elif stability:
        checks = list(branch_stability(points))
        exponents = np.array([c.exponents.largest for c in checks])  # type: ignore[union-attr]
    else:
        exponents = np.full(len(points), np.nan)
    return QuasiPeriodicBranch(points, exponents, status, reason, tuple(checks),
                               time.perf_counter() - clock, unbalance, ex,
                               None if beyond is None else (int(beyond[0]), int(beyond[1])))


def _segments(fun: SpeedResidual, first: QuasiPeriodicPoint, x0: FloatArray, lam0: float,
              options: Continuation) -> tuple[tuple[QuasiPeriodicPoint, ...], Any, str]:
    """The branch's points, its last segment's continuation result and a note of the grid
    refinements: where the branch stalls (:class:`~.refine.StallWatch`), it carries on
    from the last point before the stall on a grid twice as fine (:mod:`.refine`)."""
    points: list[QuasiPeriodicPoint] = []
    notes = []
    x, lam, orientation, budget = x0, lam0, None, options.max_points
    for refinement in range(MAX_REFINEMENTS + 1):
        watch = StallWatch(options.max_step)
        branch = continue_branch(
            fun, x, lam, dataclasses.replace(options, max_points=budget),
            monitor=watch if refinement < MAX_REFINEMENTS else None, orientation=orientation)
        end = watch.good + 1 if watch.good >= 0 else len(branch.lam)
        skip = 1 if points else 0          # the restart point is the last one kept
        points += [_point(fun, first, xi, float(w), float(r), int(it)) for xi, w, r, it in
                   list(zip(branch.x, branch.lam, branch.residuals, branch.iterations,
                            strict=True))[skip:end]]
        if watch.good < 0:                  # no stall
            break
        budget -= end - skip
        g = watch.good
        x, lam = branch.x[g], float(branch.lam[g])
        if g >= 1:      # along the last step; at the segment's start, as it was left
            orientation = np.append(branch.x[g] - branch.x[g - 1], lam - branch.lam[g - 1])
        fun = SpeedResidual(fun.system, first.rotor_problem, finer(fun.aft), fun.unbalance)
        notes.append(f"torus grid refined to {fun.aft.grid} at {lam:.6g} rad/s where the "
                     "branch stalled (contacts opening and closing)")
        if budget < 2:
            break
    return tuple(points), branch, "; ".join(notes)


def _point(fun: SpeedResidual, first: QuasiPeriodicPoint, x: FloatArray, speed: float,
           residual: float, iterations: int) -> QuasiPeriodicPoint:
    """A branch point as a :class:`QuasiPeriodicPoint` (its problem at its own speed)."""
    w2 = first.rotor_problem.vc_order * speed
    base = first.rotor_problem
    rp = RotorQuasiProblem(fun.problem_at(speed), base.active, base.static, base.vc_order,
                           speed, base.plan)
    solution = QuasiSolution(fun.full(x, speed), fun.aft, speed, w2, residual, iterations)
    return QuasiPeriodicPoint(speed, w2, solution, rp, first.system)
