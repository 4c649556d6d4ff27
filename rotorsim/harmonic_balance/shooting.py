"""Shooting: Floquet multipliers and periodic solutions from the real trajectory.

Hill's, Hsu's and the variational method take the force tangents along the harmonic-balance
orbit, a truncated Fourier series. For a contact that closes and opens (a stiffness step)
that orbit carries a Gibbs ripple and the contact duration it implies is off, and the
multipliers can be off by O(1) (issue 16: NLvib's unilateral spring, H = 21). Shooting
integrates the actual equation of motion instead (:mod:`~.shooting_flow`):

* :func:`shooting_multipliers` -- the monodromy matrix of one period of the real
  trajectory from a given state, e.g. the HB orbit's state at ``t = 0``
  (:func:`hb_state`), as a :class:`~.floquet.FloquetResult` with method "shooting";
* :func:`shoot` -- the periodic solution of a forced (non-autonomous) problem: Newton on
  ``R(y0) = y(T; y0) - y0 = 0`` with the Jacobian ``Phi(T) - I`` (invertible unless a
  multiplier is 1, i.e. away from folds), started from the HB state; it returns the
  corrected state and the multipliers of the orbit it converged to.

Cost. One period costs ``steps`` DOP853 steps of 12 right-hand sides each, every one a
force call on one sample and ``O(n^3)`` flops for ``A Phi`` on ``2n + 4n^2 + 1`` unknowns;
``steps`` grows with the stiffest mode (explicit stability, ``h < 3.3 / omega_max``) and
with the tolerance (about ``rtol^(-1/8)``) plus a few rejected steps per contact switch.
The NLvib example (n = 2, rtol = 1e-10) takes about 400 steps (5000 right-hand sides,
~0.1 s) per period; Newton from an HB guess needs 2-4 periods. Meant for small systems or a
Craig-Bampton stability model; for large stiff models prefer Hsu or Hill where the
Liouville and jump checks (:mod:`~.liouville`, :mod:`~.tangent_switches`) pass.

References
----------
R. Seydel, *Practical Bifurcation and Stability Analysis*, 3rd ed., Springer 2010,
sections 7.1-7.3; M. Krack, J. Gross, *Harmonic Balance for Nonlinear Vibration Problems*,
Springer 2019, section 3.5 (shooting as the reference for HB stability).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, Status
from rotorsim.harmonic_balance.floquet import FloquetResult, floquet_result
from rotorsim.harmonic_balance.fourier import FloatArray, derivative
from rotorsim.harmonic_balance.liouville import liouville_error
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import HBResidual
from rotorsim.harmonic_balance.shooting_flow import FirstOrderFlow, PeriodMap

SHOOTING_RTOL = 1e-10
"""Default DOP853 relative tolerance."""


@dataclass(frozen=True, eq=False)
class ShootingSolution:
    """A periodic solution found by shooting.

    Attributes
    ----------
    state : array (2n,)
        ``[q; v]`` at ``t = 0`` (phase 0) [m, m/s].
    floquet : FloquetResult
        Multipliers of the converged orbit (method "shooting").
    omega, param : float
    residual : float
        Final ``max |y(T) - y0|`` scaled by the state's size (see :func:`shoot`).
    iterations : int
        Newton iterations (periods integrated = iterations + 1).
    liouville_error : float
        :func:`~.liouville.liouville_error` of ``floquet`` against the trace integrated
        along the trajectory (an integration-accuracy check).
    stats : dict
        ``periods``, ``steps``, ``rhs_evaluations``, ``wall_time`` [s].
    status : Status
    """

    state: FloatArray
    floquet: FloquetResult
    omega: float
    param: float
    residual: float
    iterations: int
    liouville_error: float
    stats: dict[str, float]
    status: Status = Status.OK


def hb_state(residual: HBResidual, x: ArrayLike, omega: float, param: float = 0.0
             ) -> FloatArray:
    """State ``[q; v]`` (2n,) at phase 0 of the HB solution ``x`` [m, m/s].

    Examples
    --------
    >>> from rotorsim.harmonic_balance.problem import HBProblem
    >>> from rotorsim.harmonic_balance.residual import make_residual
    >>> res = make_residual(HBProblem(np.eye(1), np.eye(1)), 1, condense=False)
    >>> hb_state(res, [0.0, 2.0, 3.0], 0.5).tolist()    # 2 cos t/2 + 3 sin t/2
    [2.0, 1.5]
    """
    X = residual.expand(x, omega, param)
    basis = np.ones(X.shape[0])
    basis[2::2] = 0.0                                 # cos(0) = 1, sin(0) = 0
    return np.concatenate((basis @ X, omega * (basis @ derivative(X))))


def period_map(problem: HBProblem, y0: ArrayLike, omega: float, param: float = 0.0, *,
               rtol: float = SHOOTING_RTOL) -> PeriodMap:
    """One period of the real trajectory from ``y0`` with its monodromy matrix."""
    return FirstOrderFlow(problem, float(omega), float(param)).period(
        np.asarray(y0, dtype=float), rtol=rtol)


def shooting_multipliers(problem: HBProblem, y0: ArrayLike, omega: float,
                         param: float = 0.0, *, rtol: float = SHOOTING_RTOL,
                         autonomous: bool = False) -> FloquetResult:
    """Floquet multipliers from the monodromy of one period of the real trajectory.

    Parameters
    ----------
    problem : HBProblem
        Needs a nonsingular mass matrix.
    y0 : array (2n,)
        ``[q; v]`` at phase 0, e.g. :func:`hb_state` of an HB solution or
        :attr:`ShootingSolution.state`. The trajectory from ``y0`` is periodic only if
        ``y0`` lies on the periodic orbit; from an HB state of a non-smooth problem the
        monodromy is that of a nearby trajectory (use :func:`shoot` to correct it first).
    omega, param : float
        Fundamental frequency [rad/s] and parameter.
    rtol : float
        DOP853 tolerance (:mod:`~.shooting_flow`).
    autonomous : bool
        Exclude the trivial multiplier from the stability decision.

    Examples
    --------
    ``x'' + 0.1 x' + x = 0``: the multipliers are ``exp(lam T)`` with ``lam = -0.05 +-
    i sqrt(1 - 0.05^2)``.

    >>> pb = HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1))
    >>> fl = shooting_multipliers(pb, [0.0, 0.0], 0.7)
    >>> lam = -0.05 + 1j * np.sqrt(1 - 0.05**2)
    >>> bool(abs(fl.max_modulus - abs(np.exp(lam * 2 * np.pi / 0.7))) < 1e-9), fl.method
    (True, 'shooting')
    """
    clock = time.perf_counter()
    pm = period_map(problem, y0, omega, param, rtol=rtol)
    return _floquet(pm, omega, autonomous, clock)


def shoot(problem: HBProblem, omega: float, y0: ArrayLike, param: float = 0.0, *,
          tol: float = 1e-8, max_iter: int = 12, rtol: float = SHOOTING_RTOL,
          max_steps: int = 200_000) -> ShootingSolution:
    """Periodic solution of a forced problem by shooting from ``y0``.

    Newton on ``R(y0) = y(T; y0) - y0`` with ``dR/dy0 = Phi(T) - I``; converged when
    ``max |R_q| <= tol q_scale`` and ``max |R_v| <= tol omega q_scale``, ``q_scale =
    max(|q0|, |v0| / omega)`` of the current iterate (``tol`` must stay above the
    integration error, ~``rtol``).

    Parameters
    ----------
    problem : HBProblem
    omega : float
        Excitation (fundamental) frequency [rad/s]; the period is ``2 pi / omega``.
    y0 : array (2n,)
        Initial guess ``[q; v]`` at phase 0, e.g. :func:`hb_state`.
    param : float
    tol, max_iter : float, int
    rtol : float
        DOP853 tolerance.
    max_steps : int
        DOP853 steps per period before giving up (a very stiff problem).

    Raises
    ------
    ConvergenceError
        When Newton does not converge in ``max_iter`` iterations (iteration and residual
        in the message), ``Phi - I`` is singular (a fold) or a period needs more than
        ``max_steps`` steps.

    Examples
    --------
    Duffing ``x'' + 0.1 x' + x + x^3 = cos t`` from a zero guess (the orbit is unique at
    this frequency) agrees with harmonic balance at ``H = 13`` to its truncation error
    (4e-9; 2e-6 at ``H = 9``, 1e-11 at ``H = 17``):

    >>> from rotorsim.harmonic_balance.residual import make_residual
    >>> from rotorsim.harmonic_balance.solve import solve_point
    >>> cubic = lambda q, v, tau, w, p: (q**3, 3 * q[:, :, None]**2, None)
    >>> pb = HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1), nl_dofs=[0], force=cubic,
    ...                excitation=[[0.0], [1.0], [0.0]])
    >>> sol = shoot(pb, 1.0, [0.0, 0.0])
    >>> res = make_residual(pb, 13)
    >>> y_hb = hb_state(res, solve_point(res, 1.0).x, 1.0)
    >>> sol.status.name, bool(np.abs(sol.state - y_hb).max() < 1e-7), sol.floquet.stable
    ('OK', True, True)
    """
    clock = time.perf_counter()
    flow = FirstOrderFlow(problem, float(omega), float(param))
    y = np.asarray(y0, dtype=float).reshape(-1).copy()
    n = problem.n
    totals = {"periods": 0.0, "steps": 0.0, "rhs_evaluations": 0.0}
    error = math.inf
    for iteration in range(max_iter + 1):
        pm = flow.period(y, rtol=rtol, max_steps=max_steps)
        for key in ("steps", "rhs_evaluations"):
            totals[key] += pm.stats[key]
        totals["periods"] += 1.0
        R = pm.end - y
        q_scale = max(float(np.abs(y[:n]).max()), float(np.abs(y[n:]).max()) / omega)
        q_scale = q_scale if q_scale > 0 else 1.0
        error = max(float(np.abs(R[:n]).max()), float(np.abs(R[n:]).max()) / omega) / q_scale
        if error <= tol:
            fl = _floquet(pm, omega, False, clock, totals)
            return ShootingSolution(y, fl, float(omega), float(param), error, iteration,
                                    liouville_error(fl, pm.trace_integral), fl.stats)
        if iteration == max_iter:
            break
        try:
            y = y - np.linalg.solve(pm.monodromy - np.eye(2 * n), R)
        except np.linalg.LinAlgError as exc:
            raise ConvergenceError("Phi(T) - I is singular (a multiplier at 1: a fold)",
                                   f"shooting at omega = {omega:.6g} rad/s",
                                   iteration=iteration, residual=error) from exc
    raise ConvergenceError(f"no convergence in {max_iter} Newton iterations",
                           f"shooting at omega = {omega:.6g} rad/s", iteration=max_iter,
                           residual=error)


def _floquet(pm: PeriodMap, omega: float, autonomous: bool, clock: float,
             totals: dict[str, float] | None = None) -> FloquetResult:
    stats = {**(totals or {"periods": 1.0, **pm.stats}),
             "trace_integral": pm.trace_integral, "wall_time": time.perf_counter() - clock}
    return floquet_result(np.linalg.eigvals(pm.monodromy), omega, "shooting", stats,
                          autonomous=autonomous)
