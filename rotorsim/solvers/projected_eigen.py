"""Quadratic eigenproblems projected on a real basis, and their residuals in the full space.

A Campbell diagram solves ``(lam^2 M + lam D(W) + K(W)) x = 0`` at many speeds ``W`` for the
same few low modes. Their shapes change slowly with ``W``, so all of them lie, to working
accuracy, in a subspace of small dimension ``m`` (tens of vectors for hundreds or thousands
of DOFs). With an orthonormal real basis ``V`` (``n x m``) of that subspace, the Galerkin
(Rayleigh-Ritz) projection ``V^T (lam^2 M + lam D + K) V y = 0`` is a dense ``m x m``
problem, and ``(lam, V y)`` are the Ritz pairs. A Ritz pair is accepted only when its residual
in the full space is small (:func:`shift_inverted_residuals`); otherwise the residual,
preconditioned by the shift-inverted operator, is added to the basis (:func:`extend_basis`),
which is one step of a Davidson-type subspace method (Saad, *Numerical Methods for Large
Eigenvalue Problems*, 2nd ed., SIAM 2011, sections 4.3 and 8.3; Bai et al., *Templates for
the Solution of Algebraic Eigenvalue Problems*, SIAM 2000, section 9.2 on quadratic
problems).

A real basis keeps the projected matrices real and, for a conservative gyroscopic system,
holds the left eigenvectors (the complex conjugates of the right ones) as well, so the Ritz
values are accurate to about the square of the residual.

Nothing here knows about rotors: matrices in, eigenpairs and norms out.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.solvers.eigen import RESOLUTION
from rotorsim.solvers.linear import Factorization

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

DROP_TOL = 1e-10
"""A new direction is kept when its part orthogonal to the basis is at least this fraction
of its norm (after two Gram-Schmidt passes); smaller remainders are round-off."""


def extend_basis(V: FloatArray, new: NDArray, drop_tol: float = DROP_TOL) -> FloatArray:
    """Orthonormal basis of ``span(V) + span(Re new, Im new)``.

    Parameters
    ----------
    V : array (n, m)
        Orthonormal columns (``m`` may be 0).
    new : array (n, p), real or complex
        Directions to add; complex columns add their real and imaginary parts.
    drop_tol : float
        Relative size below which the remainder of a direction is dropped.

    Returns
    -------
    array (n, m + r)
        ``V`` followed by ``r <= 2p`` new orthonormal columns.

    Examples
    --------
    >>> V = extend_basis(np.zeros((3, 0)), np.array([[1.0], [0.0], [0.0]]))
    >>> extend_basis(V, np.array([[2.0, 1.0], [0.0, 1.0], [0.0, 0.0]])).shape
    (3, 2)
    """
    W = np.asarray(new)
    W = np.hstack([W.real, W.imag]) if np.iscomplexobj(W) else np.array(W, dtype=float)
    norms = np.linalg.norm(W, axis=0)
    W = W[:, norms > 0] / norms[norms > 0]
    if W.shape[1] == 0:
        return V
    for _ in range(2):  # classical Gram-Schmidt twice is enough (Giraud et al. 2005)
        W = W - V @ (V.T @ W)
    Q, R, _ = sl.qr(W, mode="economic", pivoting=True)
    diag = np.abs(np.diag(R))
    rank = int(np.sum(diag > drop_tol)) if diag.size else 0
    Q = Q[:, :rank]
    Q = Q - V @ (V.T @ Q)  # once more against V: the QR mixed in round-off of its parts
    Q, _ = np.linalg.qr(Q)
    return np.hstack([V, Q])


def project(A: sp.spmatrix | NDArray, V: FloatArray) -> FloatArray:
    """``V^T A V`` (``m x m``) of a sparse or dense ``n x n`` matrix."""
    return np.asarray(V.T @ (A @ V))


def projected_quadratic_eigen(Mr: FloatArray, Dr: FloatArray, Kr: FloatArray, sigma: float
                              ) -> tuple[ComplexArray, ComplexArray]:
    """All resolved eigenpairs of the dense ``m x m`` problem ``(lam^2 Mr + lam Dr + Kr) y = 0``.

    Solved, as :func:`rotorsim.solvers.eigen.quadratic_eigen` does for small problems, on
    the shift-inverted first-order form about the real shift ``sigma`` [rad/s], so the
    eigenvalues nearest ``sigma`` have their own relative accuracy whatever the rest of the
    projected spectrum; eigenvalues beyond the resolution of that form (:data:`RESOLUTION`)
    are left out.

    Returns
    -------
    values : complex array (k,)
        Eigenvalues [rad/s], nearest ``sigma`` first.
    vectors : complex array (m, k)
        Their eigenvectors in the basis coordinates.

    Raises
    ------
    numpy.linalg.LinAlgError
        ``Kr + sigma Dr + sigma^2 Mr`` is singular (``sigma`` is an eigenvalue).

    Examples
    --------
    >>> lam, _ = projected_quadratic_eigen(np.eye(1), np.zeros((1, 1)), 4 * np.eye(1), -0.1)
    >>> np.sort(lam.imag).round(12).tolist()
    [-2.0, 2.0]
    """
    T = _shift_inverted_form(Mr, Dr, Kr, sigma)
    mu, vectors = np.linalg.eig(T)  # measured 15 % faster than scipy.linalg.eig at 2m = 112
    resolved = np.abs(mu) > RESOLUTION * np.abs(T).sum(axis=0).max()
    lam = sigma + 1.0 / mu[resolved]
    order = np.argsort(np.abs(lam - sigma), kind="stable")
    return lam[order], vectors[:Mr.shape[0], resolved][:, order]


def projected_quadratic_values(Mr: FloatArray, Dr: FloatArray, Kr: FloatArray, sigma: float
                               ) -> ComplexArray:
    """The eigenvalues of :func:`projected_quadratic_eigen`, without eigenvectors [rad/s].

    LAPACK's Hessenberg QR without the Schur vectors costs about half of ``geev`` with them
    (measured 2.3 against 5.0 ms at ``2m = 120``); :func:`inverse_iteration` then gives the
    few eigenvectors that are wanted.
    """
    T = _shift_inverted_form(Mr, Dr, Kr, sigma)
    mu = np.linalg.eigvals(T)
    lam = sigma + 1.0 / mu[np.abs(mu) > RESOLUTION * np.abs(T).sum(axis=0).max()]
    return lam[np.argsort(np.abs(lam - sigma), kind="stable")]


def inverse_iteration(Mr: FloatArray, Dr: FloatArray, Kr: FloatArray, lam: ComplexArray
                      ) -> ComplexArray:
    """Eigenvectors ``(m, k)`` of ``(lam^2 Mr + lam Dr + Kr) y = 0`` for known simple
    eigenvalues ``lam`` (``k,``), by one step of inverse iteration each.

    For ``lam`` exact to rounding, one solve of the nearly singular matrix from a generic
    right-hand side leaves the other eigenvectors' parts at about ``eps |lam| / gap``
    (Golub & Van Loan, *Matrix Computations*, 4th ed., section 7.6.1), so the eigenvalues
    must be separated: the caller keeps close ones to a full eigensolve. The vectors are
    scaled to unit norm.
    """
    m = Mr.shape[0]
    if lam.size == 0:
        return np.zeros((m, 0), dtype=complex)
    L = lam[:, None, None]
    A = L**2 * Mr + L * Dr + Kr
    b = 1.0 + np.arange(m) / m  # generic: no eigenvector of a physical model is orthogonal to it
    b = np.broadcast_to(b.astype(complex)[:, None], (lam.size, m, 1))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        Y = np.linalg.solve(A, b)[:, :, 0].T
    return Y / np.linalg.norm(Y, axis=0)


def _shift_inverted_form(Mr: FloatArray, Dr: FloatArray, Kr: FloatArray, sigma: float
                         ) -> FloatArray:
    """``T`` (``2m x 2m``) whose eigenvalues are ``1 / (lam - sigma)``."""
    m = Mr.shape[0]
    P = Kr + sigma * Dr + sigma**2 * Mr
    X = -np.linalg.solve(P, np.hstack([Dr + sigma * Mr, Mr]))
    T = np.empty((2 * m, 2 * m))
    T[:m] = X
    T[m:] = sigma * X
    T[m:, :m] += np.eye(m)
    return T


def shift_inverted_residuals(lu: Factorization, M: sp.spmatrix, D: sp.spmatrix,
                             K: sp.spmatrix, values: ComplexArray, X: ComplexArray
                             ) -> tuple[FloatArray, ComplexArray]:
    """Relative residuals ``||P^-1 (lam^2 M + lam D + K) x|| / ||x||`` of eigenpairs.

    ``P = K + sigma D + sigma^2 M`` is the shifted matrix whose LU is ``lu`` (at any speed
    near the ones checked; it only defines the norm). ``P^-1`` turns the residual force into
    the displacement that would balance it, so the measure has no units and does not depend
    on the size of the largest stiffness (a 1e20 N/m pinned support adds nothing to it);
    it is the residual of the shift-inverted operator that ARPACK converges (per unit
    ``|lam - sigma| / |mu|``).

    Parameters
    ----------
    lu : Factorization
        LU of ``P`` (``n x n``).
    M, D, K : sparse (n, n)
        The full matrices at the speed of the pairs.
    values : complex array (k,)
    X : complex array (n, k)

    Returns
    -------
    relative : array (k,)
        The relative residuals [-].
    corrections : complex array (n, k)
        ``P^-1 r``, the preconditioned residual directions (to extend a basis with).
    """
    R = (M @ X) * values**2 + (D @ X) * values + K @ X
    Z = lu.solve(R)
    return np.linalg.norm(Z, axis=0) / np.linalg.norm(X, axis=0), Z
