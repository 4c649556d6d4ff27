"""Pseudo-arclength continuation stepper: options, state, ``init`` and ``step``.

The stepper follows the contract of DESIGN section 6: :class:`Continuation` is a frozen
options record, ``init(residual, x0, lam0)`` corrects the starting point at fixed ``lam``
and returns a :class:`ContinuationState`, and ``step(residual, state)`` returns the state
at the next accepted point of the branch ``R(x, lam) = 0``. A state holds only numbers and
arrays, so :mod:`rotorsim.solvers.continuation_checkpoint` stores it and a run resumes bit
for bit.

One step (seed 002 eqs 3.40-3.42):

1. predictor ``y_p = y + ds b`` along the direction ``b`` kept in the state: the unit
   tangent of the bordered system (eq 3.39), or the secant through the last two points
   after a non-smooth point;
2. corrector: damped Newton on ``R(y) = 0, b . (y - y_p) = 0`` (eqs 3.41-3.42);
3. the new tangent ``t`` solves ``[[dR/dy], [b^T]] t = e`` at the new point. The step is
   rejected and retried with ``ds / 2`` when the corrector fails, moves farther than
   ``ds``, or the tangent turns by more than ``max_angle``. After four rejections (and
   again at ``min_step``) a step in a local parametrisation (the predictor's largest
   component, or the parameter, held at its prediction) is tried and accepted as a
   corner: at a non-smooth point (a contact that opens or closes) the normal plane of the
   predictor may miss the branch. A turn that does not shrink when the step is halved
   marks a corner (contact onset, clearance): the point is accepted and the next
   predictor is the secant, as it is when the tangent solve fails. So does a branch
   whose curvature grows without bound towards a point, where every step is cut and
   accepted shorter than the last (a contact law ``max(x, 0)**1.5`` or a damping
   ``K(x) x'`` with ``K ~ x**0.5`` met by a harmonic-balance sample: the tangent turns
   like the square root of the distance, the steps would shrink geometrically towards
   that point and never pass it). After :data:`SHRINKS_TO_STEP_OVER` such steps, a trial
   that converged beyond it and was refused only for its turn is accepted as a corner.
   Such a trial is accepted at once when the shorter trials after it do not converge:
   they end in the non-smooth stretch the longer one stepped over;
4. the next ``ds`` grows (at most x2) when the corrector needed fewer than
   ``target_iterations`` iterations and the tangent turned little, and shrinks otherwise.

A point beyond ``lam_min``/``lam_max`` is replaced by the point on the bound (its ``lam``
exactly the bound) and ends the branch (status OK; NOT_CONVERGED when that point does not
converge), as does a branch that closes on its starting point. When the step falls below
``min_step`` the branch stops with a failure status and keeps its points. The corrector
judges convergence against the round-off floor where that is above ``tol``
(:data:`~.continuation_core.ROUNDOFF`).

References
----------
Seed 002 section 3.5.2.2, eqs 3.39-3.42. E. L. Allgower, K. Georg, Introduction to
Numerical Continuation Methods, SIAM 2003, sections 2.2 and 6.1 (step-size control).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    FloatArray,
    ResidualCallback,
    ScaledSystem,
    correct,
    tangent,
)
from rotorsim.solvers.continuation_local import LOCAL_AFTER, Accepted, angle, local_step
from rotorsim.solvers.continuation_state import (
    ContinuationCounters,
    ContinuationState,
    Scale,
    checked_scale,
    resolve_scales,
)
from rotorsim.solvers.stats import Stats

__all__ = ["Continuation", "ContinuationCounters", "ContinuationState"]

SHRINKS_TO_STEP_OVER = 3
"""Consecutive steps cut and accepted shorter than the last (``ContinuationState.shrinks``)
after which a converged trial refused only for its turn is accepted as a corner (module
docstring, item 3). On a smooth branch the step settles where the turn is about
``max_angle / 2`` instead of shrinking geometrically."""

CORNER_RATIO = 0.8
"""A turn that keeps more than this fraction when the step is halved is a corner (a smooth
curve halves it, a ``max(x, 0)**1.5`` contact law keeps 0.71 of it, a corner keeps all)."""


@dataclass(frozen=True)
class Continuation:
    """Options of pseudo-arclength continuation of ``R(x, lam) = 0``.

    Parameters
    ----------
    initial_step, min_step, max_step : float
        Scaled arclength steps ``ds`` (see ``x_scale``): first trial (default
        ``min(0.1, max_step)``), smallest before the branch stops with a failure, largest.
    direction : {1, -1}
        Initial direction of travel in ``lam``.
    lam_min, lam_max : float
        Parameter bounds; the branch ends on the bound it reaches.
    max_points : int
        Points of the branch, the starting point included (used by ``continue_branch``).
    tol : float
        Corrector tolerance on ``max |R / r_scale|``.
    max_iter : int
        Corrector iterations per trial step.
    target_iterations : int
        Corrector iterations aimed at by the step-size control.
    max_angle : float
        Largest turn of the tangent over one step [rad] before the step is halved.
    x_scale, r_scale : float, sequence of m floats, or "auto"
        Scales of the unknowns and of the residual. "auto": ``max |x0|`` for ``x`` (at a
        zero start the size of the Newton step from it, see
        :func:`~.continuation_state.resolve_scales`); for ``R`` the row norms
        ``max_j |dR_i/dx_j| x_scale_j`` at the start.
    lam_scale : float or "auto"
        Scale of the parameter ("auto": ``|lam0|``, 1 if zero). The arclength is
        ``ds^2 = |dx / x_scale|^2 + (dlam / lam_scale)^2``.
    max_backtracks : int
        Line-search trials per corrector iteration.
    detect_loops : bool
        End the branch when it returns to its starting point (isolas, closed curves).
    relative_step : bool
        Let the step grow with the solution: the largest step is ``max_step`` times
        ``max(1, max |x / x_scale|)``. Along a resonance whose amplitude grows to many
        times the scale of the unknowns (set at the start), a fixed ``max_step`` would
        take a number of points proportional to the amplitude; the turn of the tangent
        and the corrector's iterations still bound the step.
    stall_tol : float, optional
        Accept a corrector that stalls at a scaled residual at most ``stall_tol``
        (:func:`~.continuation_core.correct`; counted as ``relaxed_points``), for
        residuals that are not smooth where contacts open and close.

    Examples
    --------
    >>> def circle(x, lam):
    ...     return np.array([x[0]**2 + lam**2 - 1.0]), np.array([[2 * x[0]]]), np.array([2 * lam])
    >>> cont = Continuation(initial_step=0.2, max_step=0.2)
    >>> state = cont.init(circle, [0.9], 0.0)
    >>> round(float(state.x[0]), 12), state.tangent.round(6).tolist()
    (1.0, [0.0, 1.0])
    >>> state = cont.step(circle, state)
    >>> state.point, round(float(state.x[0] ** 2 + state.lam ** 2), 12)
    (1, 1.0)
    """

    initial_step: float | None = None
    min_step: float = 1e-6
    max_step: float = 1.0
    direction: int = 1
    lam_min: float = -math.inf
    lam_max: float = math.inf
    max_points: int = 500
    tol: float = 1e-10
    max_iter: int = 10
    target_iterations: int = 4
    max_angle: float = 0.5
    x_scale: Scale = 1.0
    r_scale: Scale = 1.0
    lam_scale: float | Literal["auto"] = 1.0
    max_backtracks: int = 10
    detect_loops: bool = True
    relative_step: bool = False
    stall_tol: float | None = None

    def __post_init__(self) -> None:
        where = "Continuation"
        if self.initial_step is None:
            object.__setattr__(self, "initial_step", max(min(0.1, self.max_step),
                                                         self.min_step))
        assert self.initial_step is not None
        if not 0 < self.min_step <= self.initial_step <= self.max_step < math.inf:
            raise ModelError("need 0 < min_step <= initial_step <= max_step < inf, got "
                             f"{self.min_step}, {self.initial_step}, {self.max_step}", where)
        if self.direction not in (1, -1):
            raise ModelError(f"direction must be 1 or -1, got {self.direction!r}", where)
        if not self.lam_min < self.lam_max:
            raise ModelError(f"need lam_min < lam_max, got {self.lam_min}, {self.lam_max}",
                             where)
        for name, least in (("max_points", 2), ("max_iter", 1), ("target_iterations", 1),
                            ("max_backtracks", 1)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | np.integer) \
                    or value < least:
                raise ModelError(f"{name} must be an integer >= {least}, got {value!r}",
                                 where)
        if not (self.tol > 0 and 0 < self.max_angle < math.pi):
            raise ModelError("need tol > 0 and 0 < max_angle < pi", where)
        if self.stall_tol is not None and not self.stall_tol >= self.tol:
            raise ModelError(f"stall_tol must be at least tol = {self.tol:g}, got "
                             f"{self.stall_tol!r}", where)
        for name in ("x_scale", "r_scale", "lam_scale"):
            object.__setattr__(self, name, checked_scale(name, getattr(self, name)))

    @property
    def corrector(self) -> CorrectorOptions:
        """Newton options of the corrector."""
        return CorrectorOptions(self.tol, self.max_iter, self.max_backtracks,
                                stall_tol=self.stall_tol)

    def init(self, residual: ResidualCallback, x0: ArrayLike, lam0: float, *,
             orientation: ArrayLike | None = None) -> ContinuationState:
        """Correct ``x0`` at fixed ``lam0`` and compute the first tangent.

        The tangent points along ``direction`` in ``lam``; with ``orientation``, a vector
        ``(dx (m,), dlam)`` in the units of ``(x, lam)``, it points along ``orientation``
        instead (its scaled dot product with the tangent is positive): a branch leaving a
        bifurcation point away from it, whichever way it turns in ``lam``.

        Raises
        ------
        ModelError
            For a badly shaped or non-finite start or ``lam0`` outside the bounds.
        ConvergenceError
            If the starting point does not converge or has no tangent.
        """
        x = np.array(x0, dtype=float).reshape(-1)
        if not (x.size and np.all(np.isfinite(x)) and math.isfinite(lam0)):
            raise ModelError(f"x0 and lam0 must be finite, got {x0!r}, {lam0!r}", "continuation")
        if not self.lam_min <= lam0 <= self.lam_max:
            raise ModelError(f"lam0 = {lam0} is outside [{self.lam_min}, {self.lam_max}]",
                             "continuation")
        stats = Stats()
        system = ScaledSystem(residual, *resolve_scales(
            residual, x, float(lam0), self.x_scale, self.r_scale, self.lam_scale, stats))
        y_start = system.to_y(x, float(lam0))
        e_lam = np.zeros(x.size + 1)
        e_lam[-1] = 1.0
        corr = correct(system, y_start, e_lam, float(y_start[-1]), self.corrector, stats)
        if not corr.converged or corr.evaluation is None:
            raise ConvergenceError(f"starting point not converged at fixed lam = {lam0}: "
                                   f"{corr.message}", "continuation", step=0,
                                   iteration=corr.iterations)
        tan = tangent(corr.evaluation, e_lam, stats) or tangent(
            corr.evaluation, np.full(x.size + 1, (x.size + 1) ** -0.5), stats)
        if tan is None:
            raise ConvergenceError("no tangent at the starting point: the bordered "
                                   "Jacobian is singular", "continuation", step=0)
        flip = self.direction if abs(tan.t[-1]) < 1e-12 else \
            self.direction * (1 if tan.t[-1] > 0 else -1)
        if orientation is not None:
            flip = 1 if float(tan.t @ _scaled_direction(system, orientation)) >= 0 else -1
        t = flip * tan.t
        xc, lam = system.from_y(corr.y)
        return ContinuationState(
            xc, lam, t, t, float(self.initial_step or 0.0), 0, corr.iterations, 0.0, True,
            flip * tan.det_sign, tan.log_det, corr.evaluation.residual, system.x_scale,
            system.r_scale, system.lam_scale, corr.y, t,
            ContinuationCounters().plus(stats, point_iterations=corr.iterations))

    def step(self, residual: ResidualCallback, state: ContinuationState) -> ContinuationState:
        """Next point of the branch (or ``state`` marked finished with a reason)."""
        if state.finished:
            return state
        system = state.system(residual)
        stats = Stats()
        y0 = system.to_y(state.x, state.lam)
        accepted, rejected, failure = self._advance(system, state, y0, stats)
        if accepted is None:
            status = Status.FAILED if failure[1] else Status.NOT_CONVERGED
            return dataclasses.replace(
                state, counters=state.counters.plus(stats, rejected=rejected),
                status=int(status), finished=True,
                reason=f"step size below min_step = {self.min_step:g} ({failure[0]})")
        lam_new = float(accepted.y[-1] * system.lam_scale)
        if not self.lam_min <= lam_new <= self.lam_max:
            return self._land_on_bound(system, state, y0, accepted, stats, rejected)
        return self._accept(system, state, y0, accepted, stats, rejected)

    def _advance(self, system: ScaledSystem, state: ContinuationState, y0: FloatArray,
                 stats: Stats) -> tuple[Accepted | None, int, tuple[str, bool]]:
        """Predict and correct, halving ``ds`` on failure: ``(accepted, rejections,
        (last failure, evaluation failed))``."""
        b, ds = state.predictor, state.step_size
        rejected, previous_turn = 0, math.inf
        over: Accepted | None = None    # the first trial refused only for its turn
        while True:
            y_pred = y0 + ds * b
            corr = correct(system, y_pred, b, float(b @ y_pred),
                           dataclasses.replace(self.corrector, max_correction=ds), stats)
            failure = (corr.message, corr.evaluation_failed)
            if corr.converged and np.linalg.norm(corr.y - y_pred) > ds:
                failure = ("the corrector moved farther than the step", False)
            elif corr.converged and corr.evaluation is not None:
                tan = tangent(corr.evaluation, b, stats)
                turn = 0.0 if tan is None else angle(b, tan.t)
                smooth_turn = tan is not None and turn <= self.max_angle
                corner = ds <= self.min_step or turn > CORNER_RATIO * previous_turn
                if smooth_turn or corner or tan is None:
                    return (Accepted(corr.y, tan, corr.iterations, corr.evaluation.residual,
                                      ds, turn, not smooth_turn, corr.relaxed), rejected,
                            failure)
                previous_turn = turn
                failure = (f"the tangent turned by {turn:.3g} rad > max_angle", False)
                if over is None:
                    over = Accepted(corr.y, tan, corr.iterations, corr.evaluation.residual,
                                    ds, turn, True, corr.relaxed)
                if state.shrinks >= SHRINKS_TO_STEP_OVER:   # step over a singular point
                    return over, rejected + 1, failure
            elif over is not None and not corr.converged:   # a barrier the trial passed
                return over, rejected + 1, failure
            rejected += 1
            if rejected == LOCAL_AFTER or ds <= self.min_step:
                local = local_step(system, dataclasses.replace(self.corrector,
                                                               max_correction=ds), y0, b,
                                   ds, stats)
                if local is not None:
                    return local, rejected, failure
            if ds <= self.min_step:
                return None, rejected, failure
            ds = max(0.5 * ds, self.min_step)

    def _accept(self, system: ScaledSystem, state: ContinuationState, y0: FloatArray,
                acc: Accepted, stats: Stats, rejected: int) -> ContinuationState:
        """State at an accepted point, with the next predictor and step size."""
        chord = acc.y - y0
        secant = chord / np.linalg.norm(chord)
        use_secant = acc.corner
        factor = min(2.0, max(0.5, self.target_iterations / max(acc.iterations, 1)))
        if acc.turn > 0.0:
            factor = min(factor, max(0.5, 0.5 * self.max_angle / acc.turn))
        if rejected or use_secant:
            factor = min(factor, 1.0)
        t = secant if acc.tangent is None else acc.tangent.t
        x, lam = system.from_y(acc.y)
        largest = self.max_step
        if self.relative_step:
            largest *= max(1.0, float(np.max(np.abs(acc.y[:-1]), initial=0.0)))
        new = dataclasses.replace(
            state, x=x, lam=lam, tangent=t, predictor=secant if use_secant else t,
            step_size=min(largest, max(self.min_step, acc.ds * factor)),
            point=state.point + 1, iterations=acc.iterations, last_step=acc.ds,
            smooth=not use_secant, det_sign=0 if acc.tangent is None else acc.tangent.det_sign,
            log_det=math.nan if acc.tangent is None else acc.tangent.log_det,
            residual=acc.residual,
            shrinks=state.shrinks + 1 if rejected and not acc.corner and acc.ds < state.last_step
            else 0,
            counters=state.counters.plus(stats, rejected=rejected, secant=int(use_secant),
                                         point_iterations=acc.iterations,
                                         relaxed=int(acc.relaxed)))
        if self.detect_loops and state.point >= 1 and _closes(state, y0, acc.y):
            return dataclasses.replace(new, finished=True, reason="closed loop")
        return new

    def _land_on_bound(self, system: ScaledSystem, state: ContinuationState, y0: FloatArray,
                       acc: Accepted, stats: Stats, rejected: int) -> ContinuationState:
        """Replace a point beyond a bound by the point on it and end the branch."""
        lam_new = float(acc.y[-1] * system.lam_scale)
        name, bound = ("lam_max", self.lam_max) if lam_new > self.lam_max \
            else ("lam_min", self.lam_min)
        reason = f"{name} = {bound:g} reached"
        done = dataclasses.replace(state, finished=True, reason=reason,
                                   counters=state.counters.plus(stats, rejected=rejected))
        if state.lam == bound:
            return done
        frac = (bound - state.lam) / (lam_new - state.lam)
        e_lam = np.zeros(y0.size)
        e_lam[-1] = 1.0
        corr = correct(system, y0 + frac * (acc.y - y0), e_lam, bound / system.lam_scale,
                       self.corrector, stats)
        ev = corr.evaluation if corr.converged else None
        tan = None if ev is None else tangent(ev, state.predictor, stats)
        if ev is None or tan is None:
            return dataclasses.replace(
                done, counters=state.counters.plus(stats, rejected=rejected),
                status=int(Status.NOT_CONVERGED),
                reason=f"{name} = {bound:g} not reached: the point on the bound did not "
                       f"converge ({corr.message or 'singular'})")
        landed = Accepted(corr.y, tan, acc.iterations + corr.iterations, ev.residual,
                           float(np.linalg.norm(corr.y - y0)), angle(state.predictor, tan.t),
                           False)
        new = self._accept(system, state, y0, landed, stats, rejected)
        # exactly on the bound (the constraint holds to tol; the bound itself is exact)
        return dataclasses.replace(new, lam=float(bound), finished=True, reason=reason)


def _scaled_direction(system: ScaledSystem, orientation: ArrayLike) -> FloatArray:
    """``orientation`` ``(dx, dlam)`` (m + 1,) in scaled unknowns (ModelError if it is not
    a finite vector of that size)."""
    d = np.asarray(orientation, dtype=float).reshape(-1)
    if d.shape != (system.m + 1,) or not np.all(np.isfinite(d)):
        raise ModelError(f"orientation must be {system.m + 1} finite numbers (dx, dlam), got "
                         f"shape {d.shape}", "continuation")
    return np.concatenate([d[:-1] / system.x_scale, [d[-1] / system.lam_scale]])


def _closes(state: ContinuationState, y0: FloatArray, y1: FloatArray) -> bool:
    """Does the chord ``y0 -> y1`` pass by the branch's first point, in its direction?"""
    u = y1 - y0
    length2 = float(u @ u)
    s = float((state.origin - y0) @ u) / length2
    if not 0.0 < s <= 1.0 or float(state.origin_tangent @ u) <= 0.0:
        return False
    return float(np.linalg.norm(y0 + s * u - state.origin)) <= 0.1 * math.sqrt(length2)
