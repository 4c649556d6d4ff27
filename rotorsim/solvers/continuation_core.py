"""Scaled residual, bordered linear algebra and the Newton corrector of continuation.

Rotor-agnostic (DESIGN section 1). A continuation problem is a callback

    residual(x, lam) -> (R, dR/dx, dR/dlam)

with ``R`` (m,), ``dR/dx`` (m, m) dense or scipy sparse and ``dR/dlam`` (m,). Everything
here works on the *scaled* unknowns ``y = (x / x_scale, lam / lam_scale)`` (m + 1,) and the
scaled residual ``R / r_scale``, so that metres, radians and newtons can be mixed: the
arclength, tangents and tolerances are all measured in scaled units.

The corrector solves the square bordered system of seed 002 eq 3.42,

    R(y) = 0,    b . y = target,

by Newton with an Armijo backtracking line search on ``||(R, b . y - target)||``; the
pseudo-arclength constraint of eq 3.41 is the case ``b`` = predictor direction and
``target = b . y_pred``; ``b = e_lam`` fixes the parameter. The tangent of eq 3.39 solves
``[[dR/dy], [b^T]] z = e_{m+1}`` and is ``z / |z|``; the sign of the determinant of that
bordered matrix is the branch-point test function.

References
----------
Seed 002 (bearing-rotor thesis) section 3.5.2.2, eqs 3.39-3.42. E. L. Allgower, K. Georg,
Introduction to Numerical Continuation Methods, SIAM 2003, chapters 2-3.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError, InconsistentModelError, RotorsimError
from rotorsim.solvers.bordered import BORDER_WEIGHT as BORDER_WEIGHT
from rotorsim.solvers.bordered import Tangent as Tangent
from rotorsim.solvers.bordered import bordered as bordered
from rotorsim.solvers.bordered import factor_bordered
from rotorsim.solvers.bordered import signed_log_det as signed_log_det
from rotorsim.solvers.bordered import tangent as tangent
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
Matrix = Any
"""A NumPy array or a scipy sparse matrix."""

ResidualCallback = Callable[[FloatArray, float], "tuple[Any, ...]"]
"""``residual(x, lam) -> (R (m,), dR/dx (m, m) dense or sparse, dR/dlam (m,))``,
optionally with a fourth item ``terms`` (m,): the size of the terms summed in each ``R_i``
(for the round-off floor, :data:`ROUNDOFF`; default ``|dR/dx| |x| + |dR/dlam| |lam|``)."""

EVALUATION_ERRORS: tuple[type[BaseException], ...] = (
    RotorsimError, ArithmeticError, ValueError, np.linalg.LinAlgError)
"""Exceptions of the residual callback that count as a failed evaluation (the step is cut)
rather than a programming error (anything else propagates, and so does an
:class:`~rotorsim.errors.InconsistentModelError`)."""


ROUNDOFF = 64.0
"""Convergence is judged against the floor that floating point can reach. Component ``i``
of the scaled residual sums terms of total size
``s_i = sum_j |dR_i/dy_j| |y_j| + |dR_i/dlam_hat| |lam_hat|`` (scaled units; e.g.
``|K| |x| + |f|`` for ``R = K x + r(x) - f(lam)``), so evaluating it carries an error of a
few ``eps s_i``, more after condensation or FFTs. The corrector accepts
``|R_i / r_i| <= max(tol, ROUNDOFF eps s_i)`` (and ``|b . y - target| <= max(tol,
ROUNDOFF eps |b| . |y|)``): a requested ``tol`` below round-off is met as well as it can
be instead of stopping the branch on a miss at round-off level."""


@dataclass(frozen=True, eq=False)
class Evaluation:
    """Scaled residual ``rh`` (m,), Jacobians ``jh`` (m, m) and ``jlh`` (m,) at ``y``, and
    the scaled size of the terms of ``rh`` when the callback gave it."""

    y: FloatArray
    rh: FloatArray
    jh: Matrix
    jlh: FloatArray
    terms: FloatArray | None = None

    @property
    def residual(self) -> float:
        """``max |R / r_scale|``."""
        return float(np.max(np.abs(self.rh))) if self.rh.size else 0.0

    def floor(self) -> FloatArray:
        """Round-off floor of each scaled residual component (m,) (:data:`ROUNDOFF`)."""
        y = np.abs(self.y)
        terms = abs(self.jh) @ y[:-1] + np.abs(self.jlh) * y[-1]
        if self.terms is not None:
            terms = np.maximum(terms, self.terms)
        return ROUNDOFF * np.finfo(float).eps * np.asarray(terms).reshape(-1)

    def converged(self, tol: float) -> bool:
        """Every ``|R_i / r_i| <= max(tol, floor_i)`` (:data:`ROUNDOFF`)."""
        size = np.abs(self.rh)
        if not size.size or float(size.max()) <= tol:
            return True
        return bool(np.all(size <= np.maximum(tol, self.floor())))


@dataclass(frozen=True, eq=False)
class ScaledSystem:
    """The residual callback seen in scaled unknowns.

    Parameters
    ----------
    residual : callable
        See :data:`ResidualCallback`.
    x_scale, r_scale : arrays (m,)
        Positive scales of the unknowns and of the residual components.
    lam_scale : float
        Positive scale of the parameter.
    """

    residual: ResidualCallback
    x_scale: FloatArray
    r_scale: FloatArray
    lam_scale: float

    @property
    def m(self) -> int:
        """Number of unknowns ``x``."""
        return int(self.x_scale.size)

    def to_y(self, x: FloatArray, lam: float) -> FloatArray:
        """Scaled point ``(x / x_scale, lam / lam_scale)`` (m + 1,)."""
        return np.concatenate([x / self.x_scale, [lam / self.lam_scale]])

    def from_y(self, y: FloatArray) -> tuple[FloatArray, float]:
        """Physical ``(x, lam)`` of a scaled point."""
        return y[:-1] * self.x_scale, float(y[-1] * self.lam_scale)

    def evaluate(self, y: FloatArray, stats: Stats) -> Evaluation:
        """Scaled residual and Jacobians at ``y``.

        Raises
        ------
        ConvergenceError
            If the callback raises one of :data:`EVALUATION_ERRORS` or returns non-finite
            or wrongly shaped values.
        """
        stats.residual_evaluations += 1
        x, lam = self.from_y(y)
        try:
            r, jac, jlam, *extra = self.residual(x, lam)
        except EVALUATION_ERRORS as exc:
            if isinstance(exc, InconsistentModelError):
                raise
            raise ConvergenceError(f"residual evaluation failed at lam = {lam:.6g} "
                                   f"({type(exc).__name__}: {exc})", "continuation") from exc
        m = self.m
        rh = np.asarray(r, dtype=float).reshape(-1) / self.r_scale
        jlh = np.asarray(jlam, dtype=float).reshape(-1) * (self.lam_scale / self.r_scale)
        if rh.shape != (m,) or jlh.shape != (m,) or tuple(jac.shape) != (m, m):
            raise ConvergenceError(f"residual callback returned shapes {np.shape(r)}, "
                                   f"{jac.shape}, {np.shape(jlam)}; expected ({m},), "
                                   f"({m}, {m}), ({m},)", "continuation")
        if sp.issparse(jac):
            jh = sp.coo_matrix(jac, dtype=float)
            jh.data = jh.data * (self.x_scale[jh.col] / self.r_scale[jh.row])
            values = jh.data
        else:
            jh = np.asarray(jac, dtype=float) * (self.x_scale[None, :] / self.r_scale[:, None])
            values = jh
        if not (np.all(np.isfinite(rh)) and np.all(np.isfinite(jlh))
                and np.all(np.isfinite(values))):
            raise ConvergenceError(f"residual or Jacobian not finite at lam = {lam:.6g}",
                                   "continuation")
        terms = None
        if extra:
            terms = np.abs(np.asarray(extra[0], dtype=float).reshape(-1)) / self.r_scale
            if terms.shape != (m,) or not np.all(np.isfinite(terms)):
                terms = None
        return Evaluation(y, rh, jh, jlh, terms)


@dataclass(frozen=True, eq=False)
class Correction:
    """Outcome of :func:`correct`: last iterate, its evaluation (None if the first
    evaluation failed), iterations, whether it converged, and why not."""

    y: FloatArray
    evaluation: Evaluation | None
    iterations: int
    converged: bool
    message: str = ""
    evaluation_failed: bool = False
    relaxed: bool = False


@dataclass(frozen=True)
class CorrectorOptions:
    """Newton options of :func:`correct`: scaled residual tolerance, iterations, line
    search, optionally a tolerance on the last scaled Newton correction (needed where
    the residual is flat, e.g. quadratic near a branch point), the longest scaled
    Newton step (longer ones are shortened along their direction), and the residual below
    which a stalled iteration is accepted as relaxed (``stall_tol``, see :func:`correct`)."""

    tol: float = 1e-10
    max_iter: int = 10
    max_backtracks: int = 10
    armijo: float = 1e-4
    step_tol: float | None = None
    max_correction: float = math.inf
    stall_tol: float | None = None


def correct(system: ScaledSystem, y_start: FloatArray, border: FloatArray, target: float,
            options: CorrectorOptions, stats: Stats, *,
            hold_parameter: bool = False) -> Correction:
    """Newton with backtracking on ``R(y) = 0, border . y = target`` (seed 002 eq 3.42).

    Converged when ``max |R / r_scale| <= tol`` and ``|border . y - target| <= tol``, or
    within the round-off floor where that is above ``tol`` (:data:`ROUNDOFF`), and, with
    ``options.step_tol``, when the last Newton correction is below it too (the one just
    taken, or the one computed at the converged point, which is then not taken: no
    evaluation is spent to confirm a point already within ``step_tol``). Each
    iteration factorises the bordered Jacobian once; the trial points of the line search
    satisfy the Armijo condition ``m(a) <= (1 - 2 c a) m(0)`` on the merit
    ``m = |F|^2 / 2`` (the Newton direction has slope ``-2 m(0)``). Once the residual is
    below ``tol`` the full Newton step is taken (the merit is at round-off level).

    With ``options.stall_tol``, a Newton iteration that stalls (line search failure or
    ``max_iter`` used up) at ``max |R / r_scale| <= stall_tol`` and ``|b . y - target| <=
    stall_tol`` is accepted as ``relaxed``. Where the residual is not Lipschitz in ``y``
    (the contact damping ``beta_c K(delta) delta'`` of a rolling element whose HB sample
    sits at the contact onset, where ``dK/d delta ~ delta^(-1/2)``), Newton's linear model
    holds only in a vanishing neighbourhood and the line search takes ever smaller steps;
    ``stall_tol`` is the force imbalance, relative to the typical force, below which such a
    point is as good as the discretisation behind it.

    ``hold_parameter=True`` (with ``border = e_lam``, ``target = y_start[-1]``) keeps the
    parameter bit for bit at its start: the parameter component of every Newton step is
    set to zero instead of the round-off the solve leaves there, so a residual that caches
    work per parameter value (the condensation of a harmonic-balance residual, one LU per
    harmonic and ``omega``) does that work once per correction.
    """
    y = np.array(y_start, dtype=float)
    try:
        ev = system.evaluate(y, stats)
    except ConvergenceError as exc:
        return Correction(y, None, 0, False, str(exc), evaluation_failed=True)
    last_step = math.inf
    for iteration in range(options.max_iter + 1):
        g = float(border @ y) - target
        g_floor = ROUNDOFF * np.finfo(float).eps * float(np.abs(border) @ np.abs(y))
        small = ev.converged(options.tol) and abs(g) <= max(options.tol, g_floor)
        if small and (options.step_tol is None or last_step <= options.step_tol):
            return Correction(y, ev, iteration, True)
        if iteration == options.max_iter:
            break
        stats.iterations += 1
        matrix, weight = bordered(ev.jh, ev.jlh, border)
        try:
            fact = factor_bordered(matrix, stats, "corrector")
        except ConvergenceError as exc:
            return Correction(y, ev, iteration, False, str(exc))
        step = -fact.solve(np.concatenate([ev.rh, [weight * g]]))
        if hold_parameter:
            step[-1] = 0.0
        length = float(np.linalg.norm(step))
        if length > options.max_correction:  # a trust region: shorten, keep the direction
            step *= options.max_correction / length
        last_step = float(np.max(np.abs(step)))
        if small and options.step_tol is not None and last_step <= options.step_tol:
            # the correction still due is below step_tol: y is as close as asked, and the
            # step's evaluation would only confirm it
            return Correction(y, ev, iteration + 1, True)
        if small:
            trial, accepted, message = y + step, None, ""
            try:
                accepted = system.evaluate(trial, stats)
            except ConvergenceError as exc:
                message = str(exc)
        else:
            merit = 0.5 * (float(ev.rh @ ev.rh) + g * g)
            trial, accepted, message = _line_search(system, y, step, merit, border, target,
                                                    options, stats)
        if accepted is None:
            if _stalled_close(ev, g, options):
                return Correction(y, ev, iteration + 1, True, relaxed=True)
            return Correction(y, ev, iteration + 1, False,
                              message or "line search failed to reduce the residual "
                              f"({_miss(ev, options.tol)})", evaluation_failed=bool(message))
        y, ev = trial, accepted
    if _stalled_close(ev, float(border @ y) - target, options):
        return Correction(y, ev, options.max_iter, True, relaxed=True)
    return Correction(y, ev, options.max_iter, False,
                      f"corrector did not converge in {options.max_iter} iterations "
                      f"({_miss(ev, options.tol)})")


def _stalled_close(ev: Evaluation, g: float, options: CorrectorOptions) -> bool:
    """Whether a stalled corrector ended within ``options.stall_tol`` (:func:`correct`)."""
    limit = options.stall_tol
    return limit is not None and ev.residual <= limit and abs(g) <= limit


def _miss(ev: Evaluation, tol: float) -> str:
    """``residual .. against tol .. (round-off floor ..)`` of the component that misses
    its limit by the largest factor."""
    if not ev.rh.size:
        return "no residual"
    floor = ev.floor()
    i = int(np.argmax(np.abs(ev.rh) / np.maximum(tol, floor)))
    return (f"residual {abs(ev.rh[i]):.3e} against tol {tol:.3g}, round-off floor "
            f"{floor[i]:.3g}")


def _line_search(system: ScaledSystem, y: FloatArray, step: FloatArray, merit0: float,
                 border: FloatArray, target: float, options: CorrectorOptions,
                 stats: Stats) -> tuple[FloatArray, Evaluation | None, str]:
    """Backtrack along ``step`` until Armijo holds: ``(point, evaluation, "")``, or
    ``(y, None, message)`` where the message is the last evaluation failure ("" when the
    residual was finite but never decreased enough)."""
    alpha = 1.0
    failure = ""
    for _ in range(options.max_backtracks):
        trial = y + alpha * step
        try:
            ev = system.evaluate(trial, stats)
        except ConvergenceError as exc:
            merit, failure = math.inf, str(exc)
        else:
            g = float(border @ trial) - target
            merit = 0.5 * (float(ev.rh @ ev.rh) + g * g)
            if merit <= (1.0 - 2.0 * options.armijo * alpha) * merit0:
                return trial, ev, ""
            failure = ""
        curvature = merit - merit0 + 2.0 * merit0 * alpha
        quadratic = merit0 * alpha * alpha / curvature if math.isfinite(merit) \
            and curvature > 0 else 0.25 * alpha
        alpha = min(max(quadratic, 0.1 * alpha), 0.5 * alpha)
    return y, None, failure
