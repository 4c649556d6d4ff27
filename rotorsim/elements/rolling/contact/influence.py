"""Half-space influence coefficients and the non-negative pressure solve of a contact.

The normal surface displacement of an elastic half-space (two bodies combined through the
contact modulus ``E*``, ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2``) under a pressure ``p``
is Boussinesq's integral (seed 002 eq 2.26 without the friction term; Johnson 1985,
*Contact Mechanics*, eq 3.20)::

    u(x, y) = 1/(pi E*) int int p(x', y') / sqrt((x-x')^2 + (y-y')^2) dx' dy'.

A uniform pressure ``P`` on the rectangle ``|x'-x_j| <= a``, ``|y'-y_j| <= h`` gives at
``(x_i, y_i)`` the displacement ``P D_ij / (pi E*)`` with Love's closed form (seed 002
eq 2.27; Johnson eq 3.25)::

    D_ij = F(X+a, Y+h) + F(X-a, Y-h) - F(X-a, Y+h) - F(X+a, Y-h),
    F(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|),   X = x_i - x_j,  Y = y_i - y_j.

(The absolute values make ``F`` a primitive of ``1/r`` for every sign of ``X, Y``.)

**Contact problem.** With the rigid approach ``delta_i`` of the two bodies at element
``i`` less the initial gap (profile drop, transverse curvature), the pressures
``P >= 0`` satisfy the complementarity conditions (Kalker; Johnson section 5.9)::

    C P >= delta,   P >= 0,   P . (C P - delta) = 0,

``C`` symmetric positive definite (equal rectangles). It is the minimum of
``P.C P / 2 - P.delta`` over ``P >= 0``. :func:`solve_contact` solves a batch of such
problems at once by the active-set iteration of Kalker (solve on the contact set, drop
negative pressures, add penetrating elements; batched ``numpy.linalg.solve``), and falls
back to :func:`scipy.optimize.nnls` on ``L^T`` (``C = L L^T``) for any problem that has not
settled after ``max_iter`` iterations.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import cho_factor, solve_triangular
from scipy.optimize import nnls

from rotorsim.errors import ConvergenceError, ModelError

FloatArray = NDArray[np.float64]


def _primitive(x: FloatArray, y: FloatArray) -> FloatArray:
    """``F(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)``, 0 where a factor is 0."""
    ax, ay = np.abs(x), np.abs(y)
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = np.where(ax > 0.0, x * np.arcsinh(y / np.where(ax > 0.0, ax, 1.0)), 0.0)
        t2 = np.where(ay > 0.0, y * np.arcsinh(x / np.where(ay > 0.0, ay, 1.0)), 0.0)
    return np.asarray(t1 + t2)


def rectangle_influence(dx: ArrayLike, dy: ArrayLike, half_x: ArrayLike, half_y: ArrayLike
                        ) -> FloatArray:
    """Love's ``D = int int dx' dy' / r`` [m] of a rectangle of half sides ``half_x``,
    ``half_y`` [m] seen from the offset ``(dx, dy)`` [m] of the point from its centre
    (broadcast). The displacement of a uniform pressure ``P`` is ``P D / (pi E*)``.

    Examples
    --------
    >>> round(float(rectangle_influence(3.0, 5.0, 1.0, 0.5)), 10)
    0.3431565641
    """
    x, y = np.asarray(dx, dtype=float), np.asarray(dy, dtype=float)
    a, h = np.asarray(half_x, dtype=float), np.asarray(half_y, dtype=float)
    return np.asarray(_primitive(x + a, y + h) + _primitive(x - a, y - h)
                      - _primitive(x - a, y + h) - _primitive(x + a, y - h))


def grid_compliance(x: FloatArray, y: FloatArray, half_x: float, half_y: float,
                    e_star: float) -> FloatArray:
    """Compliance ``C`` (N, N) [m/Pa] of N equal rectangles centred at ``(x, y)`` (N,)
    [m]: ``u_i = sum_j C_ij P_j`` at the centres (uniform pressure ``P_j`` [Pa] on each)."""
    d = rectangle_influence(x[:, None] - x[None, :], y[:, None] - y[None, :], half_x,
                            half_y)
    return np.asarray(d / (np.pi * e_star))


def solve_contact(compliance: FloatArray, approach: FloatArray, max_iter: int = 60
                  ) -> tuple[FloatArray, int]:
    """Non-negative solution ``P`` (..., N) of ``C P >= delta``, ``P >= 0``,
    ``P.(C P - delta) = 0`` (module docstring), batched.

    Parameters
    ----------
    compliance : array (..., N, N)
        Symmetric positive definite ``C`` [m/Pa] (or per unit load, [m/N]).
    approach : array (..., N)
        Rigid approach less the initial gap ``delta`` [m]; ``<= 0`` where open.
    max_iter : int
        Active-set iterations before the NNLS fallback.

    Returns
    -------
    (P, iterations) : (array (..., N), int)
        The pressures (or loads) and the active-set iterations used.

    Examples
    --------
    >>> c = np.array([[2.0, 1.0], [1.0, 2.0]])
    >>> p, _ = solve_contact(c, np.array([1.0, -1.0]))
    >>> p.tolist()
    [0.5, 0.0]
    """
    c = np.asarray(compliance, dtype=float)
    d = np.asarray(approach, dtype=float)
    c, d = np.broadcast_arrays(c, d[..., None, :])
    d = d[..., 0, :]
    active = d > 0.0
    eye = np.eye(d.shape[-1], dtype=bool)
    p = np.zeros(d.shape)
    unsettled = np.ones(d.shape[:-1], dtype=bool)
    for it in range(1, max_iter + 1):
        both = active[..., :, None] & active[..., None, :]
        a = np.where(both, c, eye)  # identity rows/columns outside the contact set
        p = np.linalg.solve(a, np.where(active, d, 0.0)[..., None])[..., 0]
        negative = active & (p < 0.0)
        gap = np.einsum("...ij,...j->...i", c, np.where(active, np.maximum(p, 0.0), 0.0))
        penetrating = ~active & (gap < d - 1e-12 * np.abs(d).max(initial=0.0))
        unsettled = negative.any(axis=-1) | penetrating.any(axis=-1)
        if not unsettled.any():
            return np.where(active, np.maximum(p, 0.0), 0.0), it
        # Kalker: drop the negative pressures first; add penetrating elements only then
        drop = negative.any(axis=-1, keepdims=True)
        active = np.where(drop, active & ~negative, active | penetrating)
    p = np.where(active, np.maximum(p, 0.0), 0.0)
    flat_c = np.broadcast_to(c, (*d.shape, d.shape[-1])).reshape(-1, *c.shape[-2:])
    flat_d, flat_p = d.reshape(-1, d.shape[-1]), p.reshape(-1, d.shape[-1]).copy()
    for k in np.flatnonzero(unsettled.reshape(-1)):  # rare: only the unsettled problems
        flat_p[k] = _nnls_contact(flat_c[k], flat_d[k])
    return flat_p.reshape(d.shape), max_iter


def _nnls_contact(c: FloatArray, d: FloatArray) -> FloatArray:
    """``min P.C P/2 - P.d``, ``P >= 0`` as ``min |L^T P - L^-1 d|`` by NNLS."""
    low, _ = cho_factor(c, lower=True)
    lower = np.tril(low)
    rhs = solve_triangular(lower, d, lower=True)
    try:
        p, _ = nnls(lower.T, rhs, maxiter=50 * d.size)
    except RuntimeError as exc:  # pragma: no cover - scipy's own iteration limit
        raise ConvergenceError(f"NNLS contact solve did not converge: {exc}",
                               "solve_contact") from exc
    return np.asarray(p)


def check_positive(value: float, name: str, where: str) -> float:
    """``value`` as a float if positive and finite, else :class:`ModelError`."""
    v = float(value)
    if not (np.isfinite(v) and v > 0.0):
        raise ModelError(f"{name} must be positive and finite, got {value!r}", where)
    return v
