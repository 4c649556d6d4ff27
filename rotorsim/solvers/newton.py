"""Damped Newton method with a backtracking line search on ``r(x) = 0``.

Rotor-agnostic (DESIGN section 1): the problem is a callback ``fun(x) -> (r, J)`` returning
the residual ``r`` (n,) and its Jacobian ``J = dr/dx`` (n, n), plus the scales that make
the unknowns and the residual components comparable (metres against radians, newtons
against newton-metres). All norms are taken on the scaled quantities
``x / x_scale`` and ``r / r_scale``.

One iteration solves ``J p = -r`` through :func:`~rotorsim.solvers.linear.factorize`
(a Levenberg-regularised step ``(J^T J + mu I) p = -J^T r`` when ``J`` is singular),
caps the scaled step at ``max_step`` and backtracks along ``p`` with quadratic
interpolation until the merit ``m = ||r / r_scale||^2 / 2`` satisfies the Armijo
condition ``m(x + a p) <= m(x) + c a m'(0)``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import DENSE_THRESHOLD, factorize
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
ResidualFunction = Callable[[FloatArray], tuple[FloatArray, FloatArray]]
"""``fun(x) -> (r, J)``: residual (n,) and its Jacobian (n, n)."""


@dataclass(frozen=True, eq=False)
class ResidualProblem:
    """A square nonlinear system ``r(x) = 0`` with its scales.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> (r, J)`` for ``x`` of shape (n,).
    x_scale : array (n,)
        Typical size of each unknown (positive).
    r_scale : array (n,)
        Size of each residual component that counts as "large" (positive): the solve stops
        when ``max |r / r_scale| <= tol``.
    residual : callable, optional
        ``residual(x) -> r`` alone, for the line search's trial points when the Jacobian
        costs much more than the residual (harmonic balance on a torus): ``fun`` is then
        called only at the accepted point.
    """

    fun: ResidualFunction
    x_scale: FloatArray
    r_scale: FloatArray
    residual: Callable[[FloatArray], FloatArray] | None = None

    @classmethod
    def scaled(cls, fun: ResidualFunction, n: int, x_scale: ArrayLike | None = None,
               r_scale: ArrayLike | None = None,
               residual: Callable[[FloatArray], FloatArray] | None = None
               ) -> ResidualProblem:
        """Problem with unit scales where none are given (checked: positive, finite)."""
        scales = []
        for name, value in (("x_scale", x_scale), ("r_scale", r_scale)):
            arr = np.ones(n) if value is None else np.broadcast_to(
                np.asarray(value, dtype=float), (n,)).copy()
            if not (np.all(np.isfinite(arr)) and np.all(arr > 0)):
                raise ModelError(f"{name} must be positive and finite, got {value!r}", "newton")
            scales.append(arr)
        return cls(fun, scales[0], scales[1], residual)


@dataclass(frozen=True, eq=False)
class NewtonState:
    """Iterate ``x`` with its residual, Jacobian and scaled residual norm ``residual``."""

    x: FloatArray
    r: FloatArray
    J: FloatArray
    residual: float
    iteration: int = 0
    step_length: float = 0.0


@dataclass(frozen=True)
class Newton:
    """Options of the damped Newton solver.

    Parameters
    ----------
    tol : float
        Converged when ``max |r / r_scale| <= tol``.
    max_iter : int
        Newton iterations before :class:`ConvergenceError`.
    max_step : float
        Largest scaled step ``max |p / x_scale|`` of one iteration (longer steps are
        shortened along their direction).
    armijo : float
        Sufficient-decrease constant ``c`` of the line search.
    max_backtracks : int
        Trial points per iteration before the line search is declared failed.
    where : str
        Label used in error messages.
    dense : bool
        Factorise every Jacobian with dense LU whatever its size (for Jacobians that are
        dense, such as those of harmonic balance on a torus); otherwise above
        :data:`~rotorsim.solvers.linear.DENSE_THRESHOLD` unknowns SuperLU is used.

    Examples
    --------
    >>> fun = lambda x: (np.array([x[0] ** 3 - 8.0]), np.array([[3.0 * x[0] ** 2]]))
    >>> problem = ResidualProblem.scaled(fun, 1)
    >>> state = Newton(tol=1e-12).solve(problem, [1.0])
    >>> round(float(state.x[0]), 12), state.iteration
    (2.0, 7)
    """

    tol: float = 1e-10
    max_iter: int = 50
    max_step: float = math.inf
    armijo: float = 1e-4
    max_backtracks: int = 40
    where: str = "newton"
    dense: bool = False

    def __post_init__(self) -> None:
        if not (self.tol > 0 and self.max_step > 0 and 0 < self.armijo < 0.5):
            raise ModelError("need tol > 0, max_step > 0 and 0 < armijo < 0.5", self.where)
        if self.max_iter < 0 or self.max_backtracks < 1:
            raise ModelError("need max_iter >= 0 and max_backtracks >= 1", self.where)

    def init(self, problem: ResidualProblem, x0: ArrayLike,
             stats: Stats | None = None) -> NewtonState:
        """Evaluate the residual at the starting point."""
        x = np.array(x0, dtype=float).reshape(-1)
        if x.shape != problem.x_scale.shape or not np.all(np.isfinite(x)):
            raise ModelError(f"x0 must be {problem.x_scale.size} finite numbers, got {x0!r}",
                             self.where)
        r, J = self._evaluate(problem, x, stats)
        if not (np.all(np.isfinite(r)) and np.all(np.isfinite(J))):
            raise ConvergenceError("residual or Jacobian not finite at the starting point",
                                   self.where, iteration=0)
        return NewtonState(x, r, J, self._norm(problem, r))

    def step(self, problem: ResidualProblem, state: NewtonState,
             stats: Stats | None = None) -> NewtonState:
        """One damped Newton iteration from ``state``."""
        if stats is not None:
            stats.iterations += 1
        rs, xs = problem.r_scale, problem.x_scale
        r_hat = state.r / rs
        j_hat = state.J * xs[None, :] / rs[:, None]
        p_hat = self._direction(j_hat, r_hat, state, stats)
        longest = float(np.max(np.abs(p_hat)))
        if longest > self.max_step:
            p_hat *= self.max_step / longest
            longest = self.max_step
        slope = float(r_hat @ (j_hat @ p_hat))  # m'(0) < 0 for a descent direction
        if not slope < 0.0:
            raise ConvergenceError("Newton direction is not a descent direction", self.where,
                                   iteration=state.iteration, residual=state.residual)
        merit0 = 0.5 * float(r_hat @ r_hat)
        alpha = 1.0
        for _ in range(self.max_backtracks):
            x = state.x + alpha * p_hat * xs
            if problem.residual is not None:      # the Jacobian only where accepted
                if stats is not None:
                    stats.residual_evaluations += 1
                r = np.asarray(problem.residual(x), dtype=float).reshape(-1)
                finite = bool(np.all(np.isfinite(r)))
                J = None
            else:
                r, J = self._evaluate(problem, x, stats)
                finite = bool(np.all(np.isfinite(r)) and np.all(np.isfinite(J)))
            merit = 0.5 * float(np.sum((r / rs) ** 2)) if finite else math.inf
            if merit <= merit0 + self.armijo * alpha * slope:
                if J is None:
                    r, J = self._evaluate(problem, x, stats)
                return NewtonState(x, r, J, self._norm(problem, r), state.iteration + 1,
                                   alpha * longest)
            if stats is not None:
                stats.rejected_steps += 1
            alpha = _backtrack(alpha, merit0, slope, merit)
        raise ConvergenceError("line search failed to reduce the residual", self.where,
                               iteration=state.iteration, residual=state.residual)

    def solve(self, problem: ResidualProblem, x0: ArrayLike,
              stats: Stats | None = None) -> NewtonState:
        """Iterate from ``x0`` until ``max |r / r_scale| <= tol``.

        Raises
        ------
        ConvergenceError
            After ``max_iter`` iterations, a failed line search or a singular zero Jacobian.
        """
        state = self.init(problem, x0, stats)
        while state.residual > self.tol:
            if state.iteration >= self.max_iter:
                raise ConvergenceError(f"no convergence in {self.max_iter} iterations",
                                       self.where, iteration=state.iteration,
                                       residual=state.residual)
            state = self.step(problem, state, stats)
        return state

    @staticmethod
    def _evaluate(problem: ResidualProblem, x: FloatArray,
                  stats: Stats | None) -> tuple[FloatArray, FloatArray]:
        if stats is not None:
            stats.residual_evaluations += 1
        r, J = problem.fun(x)
        return np.asarray(r, dtype=float).reshape(-1), np.asarray(J, dtype=float)

    @staticmethod
    def _norm(problem: ResidualProblem, r: FloatArray) -> float:
        return float(np.max(np.abs(r / problem.r_scale))) if r.size else 0.0

    def _direction(self, j_hat: FloatArray, r_hat: FloatArray, state: NewtonState,
                   stats: Stats | None) -> FloatArray:
        """Newton step in scaled variables; Levenberg-regularised if ``J`` is singular."""
        try:
            return -factorize(j_hat, stats=stats, where=self.where,
                              dense_threshold=self._threshold(j_hat)).solve(r_hat)
        except ConvergenceError:
            pass
        normal = j_hat.T @ j_hat
        size = float(np.max(np.abs(np.diag(normal))))
        if not size > 0.0:
            raise ConvergenceError("the Jacobian is zero: the residual does not depend on the "
                                   "unknowns here", self.where, iteration=state.iteration,
                                   residual=state.residual)
        regularised = normal + 1e-10 * size * np.eye(normal.shape[0])
        return -factorize(regularised, stats=stats, where=self.where,
                          dense_threshold=self._threshold(j_hat)).solve(j_hat.T @ r_hat)

    def _threshold(self, j_hat: FloatArray) -> int:
        return j_hat.shape[0] if self.dense else DENSE_THRESHOLD


def _backtrack(alpha: float, merit0: float, slope: float, merit: float) -> float:
    """Minimiser of the quadratic through ``m(0)``, ``m'(0)`` and ``m(alpha)``, safeguarded."""
    if not math.isfinite(merit):
        return 0.25 * alpha
    curvature = merit - merit0 - slope * alpha
    trial = -slope * alpha * alpha / (2.0 * curvature) if curvature > 0 else 0.5 * alpha
    return min(max(trial, 0.1 * alpha), 0.5 * alpha)
