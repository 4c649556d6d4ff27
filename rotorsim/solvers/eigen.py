"""Quadratic eigenvalue problem ``(lam^2 M + lam D + K) x = 0`` of a damped gyroscopic system.

Both paths work on the shift-inverted first-order form, so that the eigenvalues nearest the
real shift ``sigma`` (the low modes) are resolved to their own relative accuracy, whatever
the scale of the rest of the spectrum (e.g. 1e20 N/m springs for pinned supports beside a
shaft of 1e7 N/m). With ``A = [[0, I], [-K, -D]]``, ``B = [[I, 0], [0, M]]`` and
``T = (A - sigma B)^-1 B``, the eigenvalues are ``lam = sigma + 1 / mu`` for the eigenvalues
``mu`` of ``T``; applying ``T`` to ``y`` needs one LU of the ``n x n`` matrix
``P = K + sigma D + sigma^2 M``:

``x1 = -P^-1 (M y2 + (D + sigma M) y1)``, ``x2 = y1 + sigma x1``.

Small problems form ``T`` densely and use LAPACK on all its eigenvalues; large ones use
ARPACK for the wanted few. The default shift is scale-aware (:func:`default_shift`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError
from rotorsim.solvers.linear import Factorization, factorize
from rotorsim.solvers.stats import Stats

DENSE_EIGEN_THRESHOLD = 40
"""Problems with at most this many DOFs are solved densely (LAPACK on all 2n eigenvalues);
above it, shift-invert ARPACK for the wanted few is much faster (measured: 8 ms vs 80 ms
at 150 DOFs)."""

SHIFT_FRACTION = 1e-3
"""Default shift ``sigma = -SHIFT_FRACTION * w_ref`` (see :func:`default_shift`): small
beside every elastic mode, so modes are found in order of ``|lam|`` and ARPACK sees them
well separated, but large enough that ``P = K + sigma^2 M`` stays regular (condition about
``1 / SHIFT_FRACTION^2``) when ``K`` is singular (rigid-body modes)."""

DENSE_SHIFT_FRACTION = 0.1
"""The dense path, which computes every eigenvalue, inverts about ``-DENSE_SHIFT_FRACTION
w_ref`` when no shift is given (results are still ordered by distance from the default
shift): a larger shift widens the band of resolved eigenvalues, ``|lam|`` up to about
``DENSE_SHIFT_FRACTION w_ref / RESOLUTION``."""

RESOLUTION = 1e-9
"""Dense path: eigenvalues ``mu`` of ``T`` with ``|mu| <= RESOLUTION ||T||_1`` are not
resolved (LAPACK's absolute error ``~eps ||T||`` would exceed ``2e-7 |mu|``); they are
infinite eigenvalues (massless DOFs) or the penalty modes of near-rigid springs, far above
the modes of interest, and are left out (``EigenPairs.unresolved`` counts them)."""


RIGID_ROUNDING = 100.0
"""An eigenvector ``x`` is a rigid-body mode when its elastic energy ``x^H K x`` is at most
``RIGID_ROUNDING eps |x|^T |K| |x|``, the rounding level of ``K x`` (:func:`rounding_energy`);
measured: at most 0.13 times ``eps |x|^T |K| |x|`` for free axial/torsional modes, at least
1e7 times for the lowest bending mode of a 1000-element shaft, with supports of 1e6 to
1e30 N/m. The test does not depend on the stiffest spring of the model."""


def rounding_energy(vectors: NDArray, K: sp.spmatrix) -> NDArray[np.float64]:
    """``RIGID_ROUNDING eps |x|^T |K| |x|`` for each column ``x`` of ``vectors`` [J per
    unit amplitude squared]: elastic energies below it are zero to working precision."""
    size = np.abs(vectors)
    return RIGID_ROUNDING * np.finfo(float).eps * np.einsum("ij,ij->j", size,
                                                            abs(K) @ size)


@dataclass(frozen=True, eq=False)
class EigenPairs:
    """Eigenvalues ``(k,)`` [rad/s, complex] and displacement eigenvectors ``(n, k)``.

    ``sigma`` is the shift used [rad/s]; ``unresolved`` counts the eigenvalues the dense
    path left out as beyond its resolution (see :data:`RESOLUTION`); ``limit`` is then the
    smallest of them in magnitude [rad/s] (``inf`` when none).
    """

    values: NDArray[np.complex128]
    vectors: NDArray[np.complex128]
    sigma: float = -1.0
    unresolved: int = 0
    limit: float = np.inf


ROUNDING_STIFFNESS = 1e-10
"""Diagonal stiffnesses below this fraction of the median one are taken as round-off."""


def default_shift(M: sp.spmatrix, K: sp.spmatrix) -> float:
    """Scale-aware shift ``-SHIFT_FRACTION * w_ref`` [rad/s], ``w_ref^2 = min K_ii / M_ii``.

    ``K_ii / M_ii`` is the Rayleigh quotient of a unit vector on DOF ``i``, so ``w_ref``
    bounds the lowest elastic frequency from above; the minimum is taken over the DOFs with
    ``K_ii > 0`` and ``M_ii > 0``, so stiff springs on a few DOFs (pinned supports) do not
    change it, and entries below ``ROUNDING_STIFFNESS`` times the median ``K_ii`` (round-off
    of a linearisation) are skipped. ``-1`` when no DOF has both.

    Examples
    --------
    >>> import scipy.sparse as sp
    >>> default_shift(sp.identity(2), sp.diags([1e20, 4e10]))  # -1e-3 sqrt(4e10)
    -200.0
    >>> default_shift(sp.identity(2), sp.diags([8e-25, 4e10]))  # 8e-25: round-off
    -200.0
    """
    k_ii = np.asarray(K.diagonal(), dtype=float).real
    m_ii = np.asarray(M.diagonal(), dtype=float).real
    ok = (k_ii > 0) & (m_ii > 0) & np.isfinite(k_ii) & np.isfinite(m_ii)
    if not np.any(ok):
        return -1.0
    # a stiffness at the rounding level (a direction a linearised bearing does not hold,
    # 1e-25 N/m beside 1e7) is no reference either: drop entries far below the median
    ok &= k_ii > ROUNDING_STIFFNESS * float(np.median(k_ii[ok]))
    return -SHIFT_FRACTION * float(np.sqrt(np.min(k_ii[ok] / m_ii[ok])))


def quadratic_eigen(
    M: sp.spmatrix,
    D: sp.spmatrix,
    K: sp.spmatrix,
    k: int,
    *,
    sigma: float | None = None,
    sparse: bool | None = None,
    stats: Stats | None = None,
) -> EigenPairs:
    """The ``k`` eigenvalues of ``lam^2 M + lam D + K`` nearest ``sigma``.

    Parameters
    ----------
    M, D, K : sparse matrices (n, n)
        Mass, damping (including ``W G``) and stiffness.
    k : int
        Number of eigenvalues wanted (each of a complex pair counts).
    sigma : float, optional
        Real shift [rad/s]; default :func:`default_shift`.
    sparse : bool, optional
        Force the sparse (ARPACK) or dense (LAPACK) path; default by size.
    stats : Stats, optional
        Counters to increment.

    Returns
    -------
    EigenPairs
        Sorted by distance from ``sigma``; fewer than ``k`` when fewer exist or are
        resolved.

    Raises
    ------
    ConvergenceError
        ``P = K + sigma D + sigma^2 M`` is singular (``sigma`` is an eigenvalue), or ARPACK
        did not converge.
    """
    n = M.shape[0]
    if stats is not None:
        stats.eigen_solves += 1
    shift = default_shift(M, K) if sigma is None else float(sigma)
    use_sparse = n > DENSE_EIGEN_THRESHOLD if sparse is None else sparse
    M, D, K = (sp.csr_matrix(x) for x in (M, D, K))
    if use_sparse and k < 2 * n - 1:
        lu = _shifted_lu(M, D, K, shift, stats)
        mu, vectors = _arpack(_operator(M, D, lu, shift), k, n, shift)
        if stats is not None:
            stats.iterations += 1
        values, unresolved, limit = shift + 1.0 / mu, 0, np.inf
    else:
        pivot = shift if sigma is not None else shift * DENSE_SHIFT_FRACTION / SHIFT_FRACTION
        values, vectors, unresolved, limit = _dense(M, D, _shifted_lu(M, D, K, pivot, stats),
                                                    pivot)
    order = np.argsort(np.abs(values - shift), kind="stable")[:k]  # nearest sigma first
    return EigenPairs(values=np.asarray(values[order], dtype=complex), vectors=vectors[:n, order],
                      sigma=shift, unresolved=unresolved, limit=limit)


def _shifted_lu(M: sp.csr_matrix, D: sp.csr_matrix, K: sp.csr_matrix, sigma: float,
                stats: Stats | None) -> Factorization:
    return factorize(K + sigma * D + sigma**2 * M, stats=stats,
                     where=f"eigen shift-invert (sigma = {sigma:.6g} rad/s)")


def _operator(M: sp.csr_matrix, D: sp.csr_matrix, lu: Factorization,
              sigma: float) -> spl.LinearOperator:
    """``T`` on the balanced state ``(x, v / s)`` with ``s = |sigma| / SHIFT_FRACTION``, the
    frequency scale of the model, so that both halves of an eigenvector are of similar
    size whatever the units: ARPACK's accuracy then does not depend on the scale of the
    model (measured: 1e-8 instead of 1e-11 for a model with all stiffnesses divided by
    2e11, without this balance). The eigenvalues are unchanged."""
    n = M.shape[0]
    DsM = D + sigma * M
    s = abs(sigma) / SHIFT_FRACTION if sigma != 0 else 1.0
    Ms = M * s

    def apply(y: NDArray) -> NDArray:
        y1, y2 = y[:n], y[n:]
        x1 = -lu.solve(Ms @ y2 + DsM @ y1)
        return np.concatenate([x1, (y1 + sigma * x1) / s])

    return spl.LinearOperator((2 * n, 2 * n), matvec=apply, dtype=float)


def _dense(M: sp.csr_matrix, D: sp.csr_matrix, lu: Factorization, sigma: float
           ) -> tuple[NDArray, NDArray, int, float]:
    """All resolved eigenvalues ``lam`` [rad/s] from the dense ``T``, their eigenvectors
    (first-order form), the number left out and the smallest ``|lam|`` among those."""
    n = M.shape[0]
    X = -lu.solve(np.hstack([(D + sigma * M).toarray(), M.toarray()]))
    T = np.vstack([X, np.hstack([np.eye(n), np.zeros((n, n))]) + sigma * X])
    mu, vectors = sl.eig(T, check_finite=False)
    resolved = np.abs(mu) > RESOLUTION * np.abs(T).sum(axis=0).max()
    dropped = mu[~resolved]
    limit = float(np.min(np.abs(sigma + 1.0 / dropped[dropped != 0]), initial=np.inf))
    lam = sigma + 1.0 / mu[resolved]
    return lam, vectors[:, resolved], int(dropped.size), limit


def start_vector(n: int) -> NDArray[np.float64]:
    """Fixed (seeded) ARPACK starting vector: results are reproducible bit for bit."""
    return np.random.default_rng(20261121).standard_normal(n)


def _arpack(op: spl.LinearOperator, k: int, n: int, sigma: float) -> tuple[NDArray, NDArray]:
    """ARPACK with a retry on a larger Krylov space; converged pairs are kept even when
    ARPACK reports that its iteration limit was reached."""
    ncv = min(2 * n, max(2 * k + 1, 40))
    for attempt in range(2):
        try:
            return spl.eigs(op, k=k, which="LM", ncv=ncv, tol=1e-11, maxiter=2000,
                            v0=start_vector(op.shape[0]))
        except spl.ArpackNoConvergence as exc:
            if exc.eigenvalues is not None and len(exc.eigenvalues) >= k:
                return exc.eigenvalues, exc.eigenvectors
            if attempt == 1:
                raise ConvergenceError(
                    f"ARPACK found {len(exc.eigenvalues)} of {k} eigenvalues nearest the "
                    f"shift sigma = {sigma:.6g} rad/s (ncv={ncv}): the modes are clustered "
                    "as seen from sigma; pass a sigma near the wanted frequencies, ask for "
                    "fewer modes or use sparse=False",
                    "quadratic_eigen",
                ) from exc
            ncv = min(2 * n, 2 * ncv)
    raise AssertionError("unreachable")
