"""Energy minimisation with exact gradient and Hessian: local and multi-start global.

Rotor-agnostic (DESIGN section 1). An energy callback returns the value, gradient and
Hessian; the scales ``x_scale`` (typical size of each unknown) and ``energy_scale`` make
the problem dimensionless: the solvers work on ``x / x_scale`` and
``E / energy_scale``, and "converged" means ``max |g x_scale| / energy_scale <= tol``.

* :func:`minimize_energy`: one start, a trust-region Newton method of SciPy
  (``"trust-exact"`` by default) on the exact derivatives.
* :class:`rotorsim.solvers.global_search.GlobalSearch`: the multi-start search for every
  minimum (its own module).

References
----------
Seed 000 section 3 and Fig. 4 (energy method: global search of all admissible minima);
Nocedal & Wright, *Numerical Optimization* (2006), ch. 4 (trust regions, exact subproblem).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import factorize
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
EnergyFunction = Callable[[FloatArray], tuple[float, FloatArray, FloatArray]]
"""``fun(x) -> (E, g, H)`` for one point ``x`` (n,)."""
BatchEnergyFunction = Callable[[FloatArray], tuple[FloatArray, FloatArray, FloatArray]]
"""``fun(X) -> (E (S,), G (S, n), H (S, n, n))`` for ``S`` points ``X`` (S, n)."""

LOCAL_METHODS = ("trust-exact", "trust-krylov", "trust-ncg", "trust-constr", "Newton-CG")
"""SciPy methods accepted by :func:`minimize_energy` (all use the exact Hessian)."""


@dataclass(frozen=True, eq=False)
class LocalMinimum:
    """A converged point: ``x`` (n,), energy, gradient (n,) and the eigenvalues (n,),
    ascending, of the dimensionless Hessian ``H x_scale x_scale^T / energy_scale``.

    ``hits`` is the number of starts that reached it (global search), ``iterations`` the
    iterations of the (first) start that found it.
    """

    x: FloatArray
    energy: float
    gradient: FloatArray
    hessian_eigenvalues: FloatArray
    iterations: int
    hits: int = 1

    @property
    def positive_definite(self) -> bool:
        """Smallest Hessian eigenvalue positive (relative to the largest, 1e-12)."""
        w = self.hessian_eigenvalues
        return bool(w.size == 0 or w[0] > 1e-12 * max(float(np.abs(w).max()), 1e-300))


def scales(n: int, x_scale: ArrayLike | None, energy_scale: float,
           where: str) -> FloatArray:
    """Validated scale of each unknown, shape ``(n,)`` (ones when not given)."""
    xs = np.ones(n) if x_scale is None else np.broadcast_to(
        np.asarray(x_scale, dtype=float), (n,)).copy()
    if not (np.all(np.isfinite(xs)) and np.all(xs > 0) and np.isfinite(energy_scale)
            and energy_scale > 0):
        raise ModelError("x_scale and energy_scale must be positive and finite", where)
    return xs


def minimize_energy(fun: EnergyFunction, x0: ArrayLike, *, x_scale: ArrayLike | None = None,
                    energy_scale: float = 1.0, method: str = "trust-exact",
                    tol: float = 1e-10, max_iter: int = 200, stats: Stats | None = None,
                    where: str = "minimize_energy") -> LocalMinimum:
    """Local minimum of ``fun`` from ``x0`` by a SciPy trust-region Newton method.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> (E, g, H)``.
    x0 : array (n,)
        Starting point.
    x_scale, energy_scale
        Scales (module docstring).
    method : str
        One of :data:`LOCAL_METHODS`.
    tol : float
        Bound on the scaled gradient.
    max_iter : int
        Iteration limit of the SciPy method.

    Raises
    ------
    ConvergenceError
        If the scaled gradient is still above ``tol`` at the end.

    Examples
    --------
    >>> f = lambda x: (float((x[0] - 1) ** 4 + x[0] ** 2), np.array([4 * (x[0] - 1) ** 3
    ...      + 2 * x[0]]), np.array([[12 * (x[0] - 1) ** 2 + 2.0]]))
    >>> round(float(minimize_energy(f, [3.0]).x[0]), 8)
    0.41024549
    """
    if method not in LOCAL_METHODS:
        raise TypeError(f"{where}: unknown method {method!r}; valid: {LOCAL_METHODS}")
    x_start = np.array(x0, dtype=float).reshape(-1)
    xs = scales(x_start.size, x_scale, energy_scale, where)
    cache: dict[str, tuple[FloatArray, tuple[float, FloatArray, FloatArray]]] = {}

    def scaled(y: FloatArray) -> tuple[float, FloatArray, FloatArray]:
        hit = cache.get("last")
        if hit is not None and np.array_equal(hit[0], y):
            return hit[1]
        if stats is not None:
            stats.residual_evaluations += 1
        e, g, h = fun(y * xs)
        out = (float(e) / energy_scale, np.asarray(g) * xs / energy_scale,
               np.asarray(h) * np.outer(xs, xs) / energy_scale)
        cache["last"] = (y.copy(), out)
        return out

    import scipy.optimize as so  # slow to import: on first use

    options: dict[str, float | int] = {"maxiter": max_iter}
    options["xtol" if method == "Newton-CG" else "gtol"] = tol
    result = so.minimize(lambda y: scaled(y)[0], x_start / xs, jac=lambda y: scaled(y)[1],
                         hess=lambda y: scaled(y)[2], method=method, options=options)
    y = np.asarray(result.x, dtype=float)
    e, g, h = scaled(y)
    iterations = int(getattr(result, "nit", 0))
    y, e, g, h, polish = _polish(scaled, y, e, g, h, tol)
    iterations += polish
    if stats is not None:
        stats.iterations += iterations
    residual = float(np.max(np.abs(g))) if g.size else 0.0
    if not (np.isfinite(e) and residual <= tol):
        raise ConvergenceError(f"{method} did not converge ({result.message})", where,
                               iteration=iterations, residual=residual)
    return LocalMinimum(y * xs, e * energy_scale,
                        g * energy_scale / xs, np.asarray(np.linalg.eigvalsh(h), dtype=float),
                        iterations)


def _polish(scaled: Callable[[FloatArray], tuple[float, FloatArray, FloatArray]],
            y: FloatArray, e: float, g: FloatArray, h: FloatArray, tol: float,
            max_steps: int = 8) -> tuple[FloatArray, float, FloatArray, FloatArray, int]:
    """Full Newton steps on the exact gradient while it decreases, until ``|g| <= tol``.

    Near the minimum the energy changes by less than its round-off (``~1e-16 |E|``), so the
    trust-region acceptance test can stop SciPy slightly short of ``tol``; there the
    Newton step on the gradient is what the trust-region method would take anyway.
    """
    steps = 0
    while steps < max_steps and float(np.max(np.abs(g), initial=0.0)) > tol:
        w = np.linalg.eigvalsh(h)
        if w.size == 0 or w[0] <= 1e-12 * abs(w[-1]):
            break  # not locally convex: leave it to the caller's check
        y_new = y - factorize(h, where="newton polish").solve(g)
        e_new, g_new, h_new = scaled(y_new)
        if not (np.isfinite(e_new) and np.max(np.abs(g_new)) < np.max(np.abs(g))):
            break
        y, e, g, h = y_new, e_new, g_new, h_new
        steps += 1
    return y, e, g, h, steps
