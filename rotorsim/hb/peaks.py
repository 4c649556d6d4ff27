"""The largest amplitude of a branch, refined between its points.

Between the neighbours ``y_a = y_{i-1}`` and ``y_b = y_{i+1}`` of the largest branch point
(scaled unknowns ``y = (x / x_scale, Omega / Omega_scale)``), a point at chord abscissa
``s`` is the solution of

    R(x, Omega) = 0,    u . (y - y_a - s u) = 0,    u = y_b - y_a,

(the hyperplane through the chord point, orthogonal to the chord: well posed through
folds, as in the location of bifurcations). Brent's bounded search over ``s in [0, 1]``
maximises the amplitude measure of the solved point; each evaluation starts Newton from
the last solution. The search stops when ``s`` is known to ``S_TOL``: the amplitude then
carries an error of order ``S_TOL^2`` times its curvature, far below the solve tolerance.

References
----------
R. P. Brent, *Algorithms for Minimization without Derivatives*, Prentice-Hall 1973, ch. 5.
Seed 002 section 3.5.2.2 (pseudo-arclength correction).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from rotorsim.harmonic_balance.fourier import FloatArray
from rotorsim.harmonic_balance.residual import HBResidual
from rotorsim.hb import measures
from rotorsim.hb.result import Peak

S_TOL = 1e-9
"""Tolerance of the chord abscissa."""

NEWTON_TOL = 1e-11
"""Newton stops when the scaled update is below this."""


def refine_peak(fun: Callable[..., tuple[FloatArray, ...]], residual: HBResidual,
                branch: object, i: int, dof: int, measure: str) -> Peak:
    """Largest ``measure`` of DOF ``dof`` between branch points ``i - 1`` and ``i + 1``.

    Falls back to the branch point ``i`` (``refined=False``) if a chord point does not
    converge.
    """
    import scipy.optimize as so

    xs, ls = np.asarray(branch.x_scale), float(branch.lam_scale)  # type: ignore[attr-defined]
    X, lam = branch.x, branch.lam  # type: ignore[attr-defined]
    ya = np.concatenate([X[i - 1] / xs, [lam[i - 1] / ls]])
    yb = np.concatenate([X[i + 1] / xs, [lam[i + 1] / ls]])
    u = yb - ya
    state = {"y": np.concatenate([X[i] / xs, [lam[i] / ls]])}

    def value(s: float) -> float:
        y = _chord_point(fun, state["y"], ya + s * u, u, xs, ls)
        if y is None:
            raise ArithmeticError("chord point did not converge")
        state["y"] = y
        x, omega = y[:-1] * xs, float(y[-1] * ls)
        return -float(measures.amplitude(residual.expand(x, omega), dof, measure))

    a_i = -value(float(np.dot(state["y"] - ya, u) / np.dot(u, u)))
    try:
        best = so.minimize_scalar(value, bounds=(0.0, 1.0), method="bounded",
                                  options={"xatol": S_TOL})
        value(float(best.x))
    except ArithmeticError:
        return Peak(float(lam[i]), a_i, i, False)
    y = state["y"]
    return Peak(float(y[-1] * ls), max(-float(best.fun), a_i), i, True)


def _chord_point(fun: Callable[..., tuple[FloatArray, ...]], y0: FloatArray, yp: FloatArray,
                 u: FloatArray, xs: FloatArray, ls: float,
                 max_iter: int = 20) -> FloatArray | None:
    """Newton on ``R = 0``, ``u . (y - yp) = 0`` from ``y0`` (scaled unknowns)."""
    y = y0 + u * float(np.dot(yp - y0, u) / np.dot(u, u))
    for _ in range(max_iter):
        r, J, r_lam, *_ = fun(y[:-1] * xs, float(y[-1] * ls))
        A = np.block([[np.asarray(J) * xs[None, :], (np.asarray(r_lam) * ls)[:, None]],
                      [u[None, :]]])
        rhs = -np.concatenate([r, [np.dot(u, y - yp)]])
        try:
            dy = np.linalg.solve(A, rhs)
        except np.linalg.LinAlgError:
            return None
        y = y + dy
        if not np.all(np.isfinite(y)):
            return None
        if float(np.max(np.abs(dy))) <= NEWTON_TOL * max(1.0, float(np.max(np.abs(y)))):
            return y
    return None
