"""An independent periodic orbit for the ``rs.hb`` tests: shooting with scipy's DOP853.

Newton on the periodicity condition ``phi_T(y0) - y0 = 0`` of the first-order system
``y = [q, q']``, with the flow ``phi_T`` from ``scipy.integrate.solve_ivp`` (DOP853,
``rtol = 1e-10``) and its Jacobian (the monodromy matrix) from central differences of the
flow. Nothing of rotorsim is used: the system is written out from ``M, C, K``, the forcing
and a plain force function.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.integrate import solve_ivp

RTOL = 1e-10


def first_order(M, C, K, force: Callable[[np.ndarray, np.ndarray], np.ndarray],
                load: Callable[[float], np.ndarray]) -> Callable[[float, np.ndarray], np.ndarray]:
    """``y' = f(t, y)`` of ``M q'' + C q' + K q + force(q, v) = load(t)``."""
    Minv = np.linalg.inv(np.atleast_2d(M))
    C, K = np.atleast_2d(C), np.atleast_2d(K)
    n = Minv.shape[0]

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        q, v = y[:n], y[n:]
        return np.concatenate([v, Minv @ (load(t) - C @ v - K @ q - force(q, v))])

    return rhs


def flow(rhs, y0: np.ndarray, period: float) -> np.ndarray:
    """State after one period from ``y0``."""
    sol = solve_ivp(rhs, (0.0, period), y0, method="DOP853", rtol=RTOL,
                    atol=RTOL * max(1.0, float(np.abs(y0).max())))
    return sol.y[:, -1]


def periodic_orbit(rhs, y0: np.ndarray, period: float, tol: float = 1e-8,
                   max_iter: int = 12) -> tuple[np.ndarray, np.ndarray]:
    """Initial state of the periodic orbit near ``y0`` and its monodromy matrix.

    Converged when the Newton update is below ``tol`` (relative to ``max(1, |y|)``). A
    force with a kink (contact onset) leaves the integrated flow noisy at about
    ``100 rtol``, so the update stalls there: that level (1e-8) is the default."""
    y = np.asarray(y0, dtype=float).copy()
    for _ in range(max_iter):
        r = flow(rhs, y, period) - y
        h = 1e-6 * max(1.0, float(np.abs(y).max()))
        J = np.column_stack([(flow(rhs, y + h * e, period) - flow(rhs, y - h * e, period))
                             / (2 * h) for e in np.eye(y.size)])
        dy = np.linalg.solve(J - np.eye(y.size), -r)
        y += dy
        if np.abs(dy).max() <= tol * max(1.0, float(np.abs(y).max())):
            return y, J
    raise RuntimeError("shooting did not converge")


def fundamental(rhs, y0: np.ndarray, period: float, dof: int, samples: int = 2048) -> float:
    """``|Q_1|`` of DOF ``dof`` over one period of the orbit from ``y0`` (trapezoidal
    Fourier integral on ``samples`` equal steps, exact for the band-limited part)."""
    t = np.linspace(0.0, period, samples, endpoint=False)
    sol = solve_ivp(rhs, (0.0, period), y0, method="DOP853", rtol=RTOL,
                    atol=RTOL * max(1.0, float(np.abs(y0).max())), t_eval=t)
    c = np.fft.rfft(sol.y[dof])[1] * 2.0 / samples
    return float(abs(c))
