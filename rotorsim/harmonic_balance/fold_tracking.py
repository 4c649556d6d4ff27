"""Folds (limit points) by the extended system, located and continued in a second parameter.

At a fold of ``R(x, lam) = 0`` the Jacobian ``dR/dx`` is singular. Seed 002 (section
3.5.2.2) appends ``dR/dx phi = 0`` to ``R = 0`` with a normalisation of ``phi``; here the
extended system in the unknowns ``(x, phi, lam)`` is

    R(x, lam) = 0,    dR/dx (x_scale * phi) = 0,    (phi . phi - 1) / 2 = 0,

with ``phi`` the null vector in scaled unknowns, so ``|phi| = 1`` is meaningful when the
unknowns have different units. Its Jacobian needs the second derivatives of ``R`` only
along ``v = x_scale * phi``; by symmetry of second derivatives

    d/dx (dR/dx v) = d/de dR/dx (x + e v),   d/dlam (dR/dx v) = d/de dR/dlam (x + e v),

so two extra callback evaluations (central differences in ``e``) give the whole Jacobian.
The residual itself is exact, so the fold found is exact; only Newton's rate depends on the
difference step.

:func:`locate_fold` solves the system for one parameter; :func:`track_folds` continues it
in a second parameter ``mu`` with :func:`~rotorsim.solvers.continuation.continue_branch`,
giving the fold curve ``lam(mu)`` that bounds the region of coexisting solutions (the jump
map of a frequency response, for instance).

References
----------
Seed 002 section 3.5.2.2 (``dF/dP phi = 0`` appended to ``F = 0``). A. Griewank, G. W.
Reddien, SIAM J. Numer. Anal. 21 (1984) 176-185; W. Govaerts, Numerical Methods for
Bifurcations of Dynamical Equilibria, SIAM 2000, chapter 4.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.continuation import Branch, Continuation, continue_branch
from rotorsim.solvers.continuation_core import FloatArray, Matrix, ResidualCallback
from rotorsim.solvers.linear import factorize

TwoParameterResidual = Callable[[FloatArray, float, float], "tuple[Any, Any, Any, Any]"]
"""``residual(x, lam, mu) -> (R, dR/dx, dR/dlam, dR/dmu)``."""


@dataclass(frozen=True, eq=False)
class FoldPoint:
    """A fold: unknowns ``x`` (m,), parameter ``lam``, null vector ``phi`` (m,) of
    ``dR/dx`` in scaled unknowns (unit length), Newton iterations and final scaled
    residual of the extended system."""

    x: FloatArray
    lam: float
    phi: FloatArray
    iterations: int
    residual: float


@dataclass(frozen=True, eq=False)
class FoldCurve:
    """Folds continued in a second parameter: ``mu`` (P,), fold parameter ``lam`` (P,),
    unknowns ``x`` (P, m), null vectors ``phi`` (P, m), and the underlying branch of the
    extended system (status, stats, reason)."""

    mu: FloatArray
    lam: FloatArray
    x: FloatArray
    phi: FloatArray
    branch: Branch


def extended_system(residual: TwoParameterResidual, x_scale: FloatArray, x: FloatArray,
                    phi: FloatArray, lam: float, mu: float, fd_step: float = 1e-5,
                    ) -> tuple[FloatArray, Matrix, FloatArray]:
    """Fold system ``G(x, phi, lam; mu)`` (2m + 1,), its Jacobian in ``(x, phi, lam)`` and
    ``dG/dmu``; rows in the units of ``R`` (last row dimensionless).

    Parameters
    ----------
    residual : callable
        ``residual(x, lam, mu) -> (R, dR/dx, dR/dlam, dR/dmu)``.
    x_scale : array (m,)
        Scales of ``x``; ``phi`` is a null vector of ``dR/dx diag(x_scale)``.
    fd_step : float
        Difference step along ``phi`` in scaled unknowns (times ``max(1, |x / x_scale|)``).
    """
    r, jac, jlam, jmu = _call(residual, x, lam, mu)
    v = x_scale * phi
    e = fd_step * max(1.0, float(np.max(np.abs(x / x_scale))))
    _, jac_p, jlam_p, jmu_p = _call(residual, x + e * v, lam, mu)
    _, jac_m, jlam_m, jmu_m = _call(residual, x - e * v, lam, mu)
    hess_v = (jac_p - jac_m) / (2.0 * e)
    g = np.concatenate([r, jac @ v, [0.5 * (float(phi @ phi) - 1.0)]])
    column = (jlam_p - jlam_m) / (2.0 * e)
    jac_phi = jac @ sp.diags(x_scale) if sp.issparse(jac) else jac * x_scale[None, :]
    blocks = [[jac, None, jlam[:, None]], [hess_v, jac_phi, column[:, None]],
              [None, phi[None, :], None]]
    m = x.size
    if sp.issparse(jac):
        J = sp.bmat([[sp.csr_matrix(b) if b is not None else None for b in row]
                     for row in blocks], format="csr")
    else:
        J = np.block([[blocks[0][0], np.zeros((m, m)), blocks[0][2]],
                      [np.asarray(hess_v), jac_phi, column[:, None]],
                      [np.zeros((1, m)), phi[None, :], np.zeros((1, 1))]])
    dmu = np.concatenate([jmu, (jmu_p - jmu_m) / (2.0 * e), [0.0]])
    return g, J, dmu


def locate_fold(residual: ResidualCallback, x: ArrayLike, lam: float, phi: ArrayLike, *,
                x_scale: ArrayLike = 1.0, r_scale: ArrayLike = 1.0, lam_scale: float = 1.0,
                tol: float = 1e-12, max_iter: int = 20, fd_step: float = 1e-5) -> FoldPoint:
    """Newton on the extended system from a point near a fold.

    Parameters
    ----------
    residual : callable
        ``residual(x, lam) -> (R, dR/dx, dR/dlam)``.
    x, lam : start near the fold, e.g. where the tangent's ``lam`` component changes sign.
    phi : array-like (m,)
        Start for the null vector in scaled unknowns, e.g. the ``x`` part of the tangent.
    x_scale, r_scale, lam_scale : scales of the unknowns, the residual and ``lam``.
    tol : float
        Converged when ``max |R / r_scale|``, ``max |dR/dx v / r_scale|`` and the
        normalisation residual are below ``tol``.

    Raises
    ------
    ConvergenceError
        If Newton fails (no fold nearby, or a non-smooth turning point).

    Examples
    --------
    >>> def s_curve(x, lam):
    ...     return x**3 - x + lam, np.diag(3 * x**2 - 1), np.ones(1)
    >>> f = locate_fold(s_curve, [0.5], 0.4, [1.0])
    >>> bool(abs(f.lam - 2 / (3 * np.sqrt(3))) < 1e-14), round(float(f.x[0]) ** 2, 14)
    (True, 0.33333333333333)
    """
    x0 = np.array(x, dtype=float).reshape(-1)
    m = x0.size
    xs = np.broadcast_to(np.asarray(x_scale, dtype=float), (m,)).astype(float)
    rs = np.broadcast_to(np.asarray(r_scale, dtype=float), (m,)).astype(float)
    p0 = np.array(phi, dtype=float).reshape(-1)
    if p0.shape != (m,) or not np.linalg.norm(p0) > 0:
        raise ModelError(f"phi must be a nonzero vector of {m} entries", "locate_fold")
    two = _with_mu(residual)
    w_scale = np.concatenate([xs, np.ones(m), [lam_scale]])
    g_scale = np.concatenate([rs, rs, [1.0]])
    w = np.concatenate([x0, p0 / np.linalg.norm(p0), [lam]])
    for iteration in range(max_iter + 1):
        g, J, _ = extended_system(two, xs, w[:m], w[m:2 * m], float(w[-1]), 0.0, fd_step)
        size = float(np.max(np.abs(g / g_scale)))
        if not np.isfinite(size):
            break
        if size <= tol:
            return FoldPoint(w[:m], float(w[-1]), w[m:2 * m], iteration, size)
        if iteration == max_iter:
            break
        J_hat = sp.diags(1.0 / g_scale) @ J @ sp.diags(w_scale) if sp.issparse(J) \
            else J * (w_scale[None, :] / g_scale[:, None])
        step = factorize(J_hat, where="locate_fold").solve(-g / g_scale)
        w = w + step * w_scale
    raise ConvergenceError("extended system did not converge", "locate_fold",
                           iteration=iteration, residual=size)


def track_folds(residual: TwoParameterResidual, fold: Any, mu0: float,
                options: Continuation | None = None, *, x_scale: ArrayLike = 1.0,
                r_scale: ArrayLike = 1.0, lam_scale: float = 1.0, fd_step: float = 1e-5,
                **driver: Any) -> FoldCurve:
    """Continue a fold in the second parameter ``mu``.

    Parameters
    ----------
    residual : callable
        ``residual(x, lam, mu) -> (R, dR/dx, dR/dlam, dR/dmu)``.
    fold : FoldPoint or BifurcationEvent
        A fold at ``mu0``: from :func:`locate_fold`, or a fold event of
        :func:`~rotorsim.harmonic_balance.bifurcation.detect_bifurcations` (its
        ``null_vector`` is used as ``phi``).
    options : Continuation, optional
        Options of the continuation in ``mu``; its scales are replaced by those of the
        extended unknowns ``(x, phi, lam)`` built from ``x_scale`` and ``lam_scale``.
    driver
        Passed to :func:`~rotorsim.solvers.continuation.continue_branch` (checkpoint,
        resume, progress, monitor).

    Returns
    -------
    FoldCurve

    Examples
    --------
    ``x^3 - mu x + lam = 0`` folds on ``lam = 2 (mu / 3)^(3/2)`` (and its mirror image):

    >>> def cusp(x, lam, mu):
    ...     return x**3 - mu * x + lam, np.diag(3 * x**2 - mu), np.ones(1), -x
    >>> fold = locate_fold(lambda x, lam: cusp(x, lam, 1.0)[:3], [0.6], 0.4, [1.0])
    >>> curve = track_folds(cusp, fold, 1.0, Continuation(direction=-1, max_points=6))
    >>> bool(np.allclose(curve.lam, 2 * (curve.mu / 3) ** 1.5, atol=1e-10))
    True
    """
    m = fold.x.size
    phi = getattr(fold, "phi", None)
    phi = np.asarray(fold.null_vector if phi is None else phi, dtype=float)
    xs = np.broadcast_to(np.asarray(x_scale, dtype=float), (m,)).astype(float)
    rs = np.broadcast_to(np.asarray(r_scale, dtype=float), (m,)).astype(float)
    opts = dataclasses.replace(
        options if options is not None else Continuation(),
        x_scale=tuple(np.concatenate([xs, np.ones(m), [lam_scale]])),
        r_scale=tuple(np.concatenate([rs, rs, [1.0]])))

    def fun(z: FloatArray, mu: float) -> tuple[FloatArray, Matrix, FloatArray]:
        return extended_system(residual, xs, z[:m], z[m:2 * m], float(z[-1]), mu, fd_step)

    branch = continue_branch(fun, np.concatenate([fold.x, phi, [fold.lam]]), mu0, opts,
                             **driver)
    return FoldCurve(branch.lam, branch.x[:, -1], branch.x[:, :m], branch.x[:, m:2 * m],
                     branch)


def _with_mu(residual: ResidualCallback) -> TwoParameterResidual:
    def two(x: FloatArray, lam: float, mu: float) -> tuple[Any, Any, Any, Any]:
        r, jac, jlam = residual(x, lam)[:3]
        return r, jac, jlam, np.zeros(x.size)

    return two


def _call(residual: TwoParameterResidual, x: FloatArray, lam: float,
          mu: float) -> tuple[FloatArray, Matrix, FloatArray, FloatArray]:
    r, jac, jlam, jmu = residual(x, lam, mu)
    jac = sp.csr_matrix(jac, dtype=float) if sp.issparse(jac) else np.asarray(jac, dtype=float)
    return (np.asarray(r, dtype=float).reshape(-1), jac,
            np.asarray(jlam, dtype=float).reshape(-1), np.asarray(jmu, dtype=float).reshape(-1))
