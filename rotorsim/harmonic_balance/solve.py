"""One periodic solution by a damped Newton solve of the harmonic-balance equations.

``solve_point(residual, omega, x0=None, *, param=0.0, ...) -> PeriodicSolution`` runs
:class:`rotorsim.solvers.newton.Newton` on ``residual.evaluate`` at fixed ``omega`` and
``param`` and raises :class:`~rotorsim.errors.ConvergenceError` when it fails.
``sample_convergence`` measures the aliasing error of the AFT at a solution (how much the
residual changes when the number of time samples is doubled).

Scales: the solve stops when ``max |r| <= tol * r_scale``; by default ``r_scale`` is the
largest excitation coefficient (1 N without excitation) and ``x_scale`` the largest
``|x0|`` (1 when ``x0`` is zero) -- pass them for problems whose unknowns mix metres and
radians or whose forcing is zero.

References
----------
Seed 002 section 3.5.2.1 (Newton iteration ``P_{i+1} = P_i - f / f'`` on the HB equations).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import Status
from rotorsim.harmonic_balance.fourier import AFT, FloatArray
from rotorsim.harmonic_balance.residual import HBResidual, as_unknowns
from rotorsim.solvers.continuation_core import ROUNDOFF
from rotorsim.solvers.newton import Newton, ResidualProblem
from rotorsim.solvers.stats import Stats
from rotorsim.solvers.threads import capped_by_size


@dataclass(frozen=True, eq=False)
class PeriodicSolution:
    """A converged harmonic-balance point.

    Attributes
    ----------
    x : array (m,)
        Unknowns of the residual it was solved with (condensed or full).
    coefficients : array (2H + 1, n)
        Fourier coefficients of all DOFs (layout of :mod:`~rotorsim.harmonic_balance.fourier`)
        [m, rad].
    omega : float
        Fundamental frequency [rad/s].
    param : float
        Continuation parameter.
    harmonics, samples : int
        ``H`` and ``N``.
    residual : float
        Final ``max |r| / r_scale``.
    stats : dict
        ``iterations``, ``residual_evaluations``, ``factorizations``, ``solves``,
        ``rejected_steps``, ``wall_time`` [s], ...
    status : Status
    """

    x: FloatArray
    coefficients: FloatArray
    omega: float
    param: float
    harmonics: int
    samples: int
    residual: float
    stats: dict[str, float]
    status: Status = Status.OK

    def time_response(self, samples: int = 256) -> tuple[FloatArray, FloatArray]:
        """Phases ``tau`` (samples,) [rad] and displacements ``q`` (samples, n) over one
        period (``t = tau / omega``)."""
        aft = AFT(self.harmonics)
        tau = 2.0 * np.pi * np.arange(samples) / samples
        return tau, aft.basis(tau) @ self.coefficients

    def amplitude(self, dof: int, samples: int = 1024) -> float:
        """Half the peak-to-peak value of DOF ``dof`` over a period (on ``samples``
        phases) [m, rad]."""
        q = self.time_response(samples)[1][:, dof]
        return 0.5 * float(q.max() - q.min())


@capped_by_size(lambda residual, *_, **__: residual.size)
def solve_point(residual: HBResidual, omega: float, x0: ArrayLike | None = None, *,
                param: float = 0.0, tol: float = 1e-10, max_iter: int = 50,
                x_scale: ArrayLike | None = None, r_scale: ArrayLike | None = None,
                newton: Newton | None = None) -> PeriodicSolution:
    """Solve ``residual(x, omega, param) = 0`` by damped Newton from ``x0``.

    Parameters
    ----------
    residual : HBResidual
        From :func:`~rotorsim.harmonic_balance.residual.make_residual`.
    omega : float
        Fundamental frequency [rad/s].
    x0 : array (residual.size,), optional
        Initial guess (zeros by default).
    param : float
        Continuation parameter value.
    tol, max_iter : float, int
        Stop when ``max |r / r_scale| <= tol``, or below the round-off floor of the
        residual at ``x0`` where that is above ``tol`` (:func:`_floor`); fail after
        ``max_iter`` iterations.
    x_scale, r_scale : float or array (residual.size,), optional
        Scales of the unknowns and residuals (see the module docstring).
    newton : Newton, optional
        Full solver options (overrides ``tol`` and ``max_iter``).

    Raises
    ------
    ConvergenceError
        When Newton does not converge (iteration and residual in the message).

    Examples
    --------
    Duffing ``x'' + 0.1 x' + x + x^3 = cos(t)`` with one harmonic:

    >>> from rotorsim.harmonic_balance.problem import HBProblem
    >>> from rotorsim.harmonic_balance.residual import make_residual
    >>> cubic = lambda q, v, tau, w, p: (q**3, 3 * q[:, :, None]**2, None)
    >>> pb = HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1), nl_dofs=[0], force=cubic,
    ...                excitation=[[0.0], [1.0], [0.0]])
    >>> sol = solve_point(make_residual(pb, 1), 1.0)
    >>> a = np.hypot(*sol.coefficients[1:, 0])
    >>> round(float(a), 6), bool(abs(a**2 * ((0.75 * a**2) ** 2 + 0.01) - 1.0) < 1e-9)
    (1.098418, True)
    """
    stats, newton_stats = Stats(), Stats()
    x_start = np.zeros(residual.size) if x0 is None else as_unknowns(x0, residual.size)
    F = residual.problem.excitation_coefficients(residual.aft, omega, param)
    r_default = float(np.abs(F).max()) or 1.0
    x_default = float(np.abs(x_start).max()) or 1.0
    r_s = np.asarray(r_default if r_scale is None else r_scale, dtype=float)
    solver = newton if newton is not None else Newton(
        tol=max(tol, _floor(residual, x_start, omega, param, r_s)), max_iter=max_iter,
        where=f"harmonic balance at omega = {omega:.6g} rad/s")

    def fun(x: FloatArray) -> tuple[FloatArray, FloatArray]:
        ev = residual.evaluate(x, omega, param, stats=stats)
        assert ev.jacobian is not None
        return ev.r, ev.jacobian

    scaled = ResidualProblem.scaled(fun, residual.size,
                                    x_default if x_scale is None else x_scale,
                                    r_default if r_scale is None else r_scale)
    state = solver.solve(scaled, x_start, stats=newton_stats)
    return PeriodicSolution(state.x, residual.expand(state.x, omega, param), float(omega),
                            float(param), residual.harmonics, residual.samples,
                            state.residual, _merge(stats, newton_stats))


def sample_convergence(residual: HBResidual, x: ArrayLike, omega: float,
                       param: float = 0.0, r_scale: float | None = None) -> float:
    """Change of the residual at ``x`` when the number of time samples is doubled.

    Returns ``max |r_2N(x) - r_N(x)| / r_scale`` (``r_scale`` as in :func:`solve_point`).
    At a converged point ``r_N(x) ~ 0``, so this is the residual the aliasing of the
    ``N``-point AFT leaves in the better-resolved equations: increase ``N`` until it is
    below the Newton tolerance.

    Examples
    --------
    A cubic at ``H = 1`` needs ``N >= 4 H + 1 = 5`` samples for an exact transform:

    >>> from rotorsim.harmonic_balance.problem import HBProblem
    >>> from rotorsim.harmonic_balance.residual import make_residual
    >>> cubic = lambda q, v, tau, w, p: (q**3, 3 * q[:, :, None]**2, None)
    >>> pb = HBProblem(np.eye(1), np.eye(1), nl_dofs=[0], force=cubic)
    >>> x = [0.0, 1.0, 0.0]
    >>> sample_convergence(make_residual(pb, 1, samples=3), x, 1.0) > 0.1
    True
    >>> sample_convergence(make_residual(pb, 1, samples=5), x, 1.0) < 1e-15
    True
    """
    finer = residual.with_discretization(samples=2 * residual.samples)
    r = residual.evaluate(x, omega, param, jacobian=False).r
    r2 = finer.evaluate(x, omega, param, jacobian=False).r
    if r_scale is None:
        F = residual.problem.excitation_coefficients(residual.aft, omega, param)
        r_scale = float(np.abs(F).max()) or 1.0
    return float(np.abs(r2 - r).max()) / r_scale


def _floor(residual: HBResidual, x: FloatArray, omega: float, param: float,
           r_scale: FloatArray) -> float:
    """Round-off floor of ``max |r / r_scale|`` near ``x``: ``ROUNDOFF eps`` times the
    largest scaled size of the terms of the residual (the rule of
    :data:`rotorsim.solvers.continuation_core.ROUNDOFF`)."""
    terms = residual.evaluate(x, omega, param).terms
    if terms is None:
        return 0.0
    return ROUNDOFF * float(np.finfo(float).eps) * float(np.max(terms / r_scale, initial=0.0))


def _merge(evaluations: Stats, newton: Stats) -> dict[str, float]:
    """Newton's counters, with the residual evaluations and condensation factorisations
    counted by the residual."""
    out = newton.finish()
    out["residual_evaluations"] = evaluations.residual_evaluations
    out["factorizations"] += evaluations.factorizations
    out["solves"] += evaluations.solves
    out["wall_time"] = evaluations.finish()["wall_time"]
    return out
