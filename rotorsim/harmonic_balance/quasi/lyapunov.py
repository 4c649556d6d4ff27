"""Stability of a quasi-periodic solution: the largest Lyapunov exponent of the variational
equation along the torus.

A small perturbation ``y`` of the torus ``q*(t)`` obeys the linear equation with
quasi-periodic coefficients

    M y'' + (C + W G + Ct(t)) y' + (K + Kt(t)) y = 0,

``Kt`` and ``Ct`` the nonlinear force's tangents along ``q*(t)``, ``theta = (w1 t, w2 t)``.
Both base frequencies are imposed from outside (unbalance and cage), so the torus has no
neutral phase directions: it is asymptotically stable when the largest Lyapunov exponent
``lambda_1 = lim (1/T) ln(|y(T)| / |y(0)|)`` is negative, unstable when it is positive
(Oseledets; for a periodic orbit ``lambda_1 = ln|mu_max| / T`` of its largest Floquet
multiplier).

The exponent is estimated by integrating one perturbation with the average-acceleration
Newmark rule (no numerical damping: growth rates are kept to second order in the step) over
``periods`` periods of ``w1``, renormalised once per period (Benettin et al., *Meccanica* 15
(1980) 9-20); the tangents are evaluated along the HB torus in one batched call. The
exponent is the growth rate over the second half of the horizon, after the perturbation has
aligned with the most unstable direction (the running estimate ``ln|y(t)| / t`` carries a
``1 / t`` bias from that alignment; it is returned too, to judge convergence).

References
----------
G. Benettin, L. Galgani, A. Giorgilli, J.-M. Strelcyn, "Lyapunov characteristic exponents
for smooth dynamical systems...", *Meccanica* 15 (1980) 9-20 and 21-30; issue 17 part 2.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.quasi.residual import QuasiProblem
from rotorsim.harmonic_balance.quasi.solve import QuasiSolution

FloatArray = NDArray[np.float64]
MAX_DENSE = 2000
"""Largest number of DOFs integrated (dense LU per step)."""


@dataclass(frozen=True, eq=False)
class LyapunovEstimate:
    """Largest Lyapunov exponent ``exponent`` [1/s] of a torus, its running estimate
    ``running`` after each renormalisation at times ``times`` [s], and the step ``dt`` [s]."""

    exponent: float
    running: FloatArray
    times: FloatArray
    dt: float

    @property
    def stable(self) -> bool:
        """A negative exponent: perturbations decay."""
        return self.exponent < 0.0


def largest_lyapunov_exponent(problem: QuasiProblem, solution: QuasiSolution, *,
                              periods: int = 40, steps_per_period: int = 256,
                              seed: int = 0) -> LyapunovEstimate:
    """The largest Lyapunov exponent of the variational equation along ``solution``.

    Parameters
    ----------
    problem : QuasiProblem
        The problem ``solution`` solves (all DOFs of ``solution.X``).
    periods : int
        Horizon in periods of ``w1``.
    steps_per_period : int
        Newmark steps per period of the faster base frequency.
    seed : int
        Of the random initial perturbation.

    Raises
    ------
    ModelError
        More than :data:`MAX_DENSE` DOFs, or a horizon or step count below 1.
    """
    n = problem.n
    if n > MAX_DENSE:
        raise ModelError(f"{n} DOFs: the Lyapunov estimate integrates at most {MAX_DENSE}",
                         "largest_lyapunov_exponent")
    if periods < 1 or steps_per_period < 8:
        raise ModelError("need periods >= 1 and steps_per_period >= 8",
                         "largest_lyapunov_exponent")
    w1, w2 = solution.w1, solution.w2
    dt = 2 * np.pi / (steps_per_period * max(w1, w2))
    per_period = int(np.ceil(2 * np.pi / w1 / dt))
    t = dt * np.arange(1, periods * per_period + 1, dtype=np.float64)
    Kt, Ct = _tangents(problem, solution, t)
    return _variational_growth(problem, w1, dt, per_period, Kt, Ct, seed)


def trajectory_lyapunov_exponent(problem: QuasiProblem, w1: float, w2: float,
                                 t: FloatArray, q: FloatArray, v: FloatArray, *,
                                 per_period: int, seed: int = 0) -> LyapunovEstimate:
    """The largest Lyapunov exponent of a recorded trajectory (not a torus): the
    variational equation integrated with the tangents of ``problem``'s force taken along
    the trajectory, renormalised every ``per_period`` steps (Benettin et al. 1980). A
    positive exponent, above the ``1 / T`` resolution of the record, marks chaos.

    Parameters
    ----------
    problem : QuasiProblem
        The equation of motion the trajectory solves (its nonlinear force's tangents).
    w1, w2 : float
        Base frequencies [rad/s]: the force is evaluated at the angles ``(w1 t, w2 t)``.
    t : array (S,)
        Equally spaced sample times [s] (the trajectory's phase origin at ``t = 0``);
        the step is their spacing.
    q, v : array (S, d)
        Displacements [m, rad] and velocities of the nonlinear DOFs at ``t``.
    per_period : int
        Steps between renormalisations (one shaft revolution).

    Raises
    ------
    ModelError
        Unequal spacing, mismatched shapes, or fewer than two renormalisations.
    """
    t = np.asarray(t, dtype=float)
    nl = np.asarray(problem.nl_dofs, dtype=np.int64)
    q, v = np.asarray(q, dtype=float), np.asarray(v, dtype=float)
    where = "trajectory_lyapunov_exponent"
    if t.ndim != 1 or t.size < 2 * per_period + 1 or per_period < 1:
        raise ModelError(f"need at least two renormalisations of {per_period} steps, got "
                         f"{t.size} samples", where)
    if q.shape != (t.size, nl.size) or v.shape != q.shape:
        raise ModelError(f"q and v must be ({t.size}, {nl.size}) (samples, nonlinear DOFs), "
                         f"got {q.shape} and {v.shape}", where)
    dt = float(t[1] - t[0])
    if not (dt > 0 and np.allclose(np.diff(t), dt, rtol=1e-9, atol=0.0)):
        raise ModelError("the sample times must be equally spaced and increasing", where)
    if problem.force is None or nl.size == 0:
        Kt, Ct = np.zeros((t.size - 1, nl.size, nl.size)), None
    else:
        _, dfdq, dfdv = problem.force(q[1:], v[1:], w1 * t[1:], w2 * t[1:])
        Kt, Ct = np.asarray(dfdq), None if dfdv is None else np.asarray(dfdv)
    steps = (t.size - 1) // per_period * per_period
    return _variational_growth(problem, w1, dt, per_period, Kt[:steps],
                               None if Ct is None else Ct[:steps], seed)


def _variational_growth(problem: QuasiProblem, w1: float, dt: float, per_period: int,
                        Kt: FloatArray, Ct: FloatArray | None, seed: int) -> LyapunovEstimate:
    """Benettin's estimate (module docstring) with the tangents ``Kt, Ct (steps, d, d)``
    at the ends of the steps of ``dt`` [s], renormalised every ``per_period`` steps."""
    n = problem.n
    n_steps = Kt.shape[0]
    t = dt * np.arange(1, n_steps + 1, dtype=np.float64)
    M, D, K = (_dense(A) for A in (problem.M, problem.damping(w1), problem.K))
    nl = np.asarray(problem.nl_dofs, dtype=np.int64)
    block = np.ix_(nl, nl)
    rng = np.random.default_rng(seed)
    y, v = rng.standard_normal(n), w1 * rng.standard_normal(n)
    scale = _norm(y, v, w1)
    y, v = y / scale, v / scale
    a = np.linalg.solve(M, -(D @ v + K @ y))
    log_growth, running, times = 0.0, [], []
    beta, gamma = 0.25, 0.5
    for i in range(n_steps):
        Ki, Di = K.copy(), D.copy()
        Ki[block] += Kt[i]
        if Ct is not None:
            Di[block] += Ct[i]
        y_pred = y + dt * v + (0.5 - beta) * dt**2 * a
        v_pred = v + (1 - gamma) * dt * a
        lhs = M + gamma * dt * Di + beta * dt**2 * Ki
        a = sl.solve(lhs, -(Di @ v_pred + Ki @ y_pred), check_finite=False)
        y = y_pred + beta * dt**2 * a
        v = v_pred + gamma * dt * a
        if (i + 1) % per_period == 0:
            size = _norm(y, v, w1)
            log_growth += np.log(size)
            y, v, a = y / size, v / size, a / size
            running.append(log_growth / t[i])
            times.append(t[i])
    running_arr, times_arr = np.array(running), np.array(times)
    growth = running_arr * times_arr              # ln of the total growth at each time
    half = len(times) // 2
    exponent = (growth[-1] - growth[half - 1]) / (times_arr[-1] - times_arr[half - 1]) \
        if half >= 1 else running_arr[-1]
    return LyapunovEstimate(float(exponent), running_arr, times_arr, dt)


def _tangents(problem: QuasiProblem, solution: QuasiSolution, t: FloatArray
              ) -> tuple[FloatArray, FloatArray | None]:
    """``Kt (S, d, d)`` and ``Ct`` along the torus at times ``t``."""
    nl = np.asarray(problem.nl_dofs, dtype=np.int64)
    d = nl.size
    if problem.force is None or d == 0:
        return np.zeros((t.size, d, d)), None
    q = solution.evaluate(t, nl)
    Dm = solution.aft.derivative_matrix(solution.w1, solution.w2)
    V = Dm @ solution.X[:, nl]
    k = solution.aft.harmonics.k
    phase = np.outer(t, k[:, 0] * solution.w1 + k[:, 1] * solution.w2)
    v = V[0] + np.cos(phase) @ V[1::2] + np.sin(phase) @ V[2::2]
    _, dfdq, dfdv = problem.force(q, v, solution.w1 * t, solution.w2 * t)
    return np.asarray(dfdq), None if dfdv is None else np.asarray(dfdv)


def _dense(A: Any) -> FloatArray:
    return np.asarray(A.toarray() if sp.issparse(A) else A, dtype=float)


def _norm(y: FloatArray, v: FloatArray, w: float) -> float:
    return float(np.sqrt(y @ y + (v @ v) / w**2))
