"""Factorise once, solve many times: the only way rotorsim solves linear systems.

``factorize`` picks a dense LU for small matrices and SuperLU for large sparse ones; it
never forms an inverse.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError
from rotorsim.solvers.stats import Stats

DENSE_THRESHOLD = 120
"""Matrices up to this size are factorised densely (LAPACK is faster there)."""


@dataclass(frozen=True, eq=False)
class Factorization:
    """LU factors of a square matrix; :meth:`solve` accepts one or many right-hand sides."""

    n: int
    _dense: Any = None
    _sparse: Any = None
    _stats: Stats | None = None
    _complex: bool = False

    def slogdet(self) -> tuple[int, float]:
        """``(sign, log |det A|)`` from the LU factors, without overflow (``sign = 0`` and
        ``-inf`` for an exactly singular factor): ``det = sign(P_r) sign(P_c) prod(diag U)``.

        Examples
        --------
        >>> factorize(np.array([[0.0, 2.0], [3.0, 1.0]])).slogdet()[0]
        -1
        """
        if self._complex:
            raise TypeError("slogdet of a complex factorisation is not implemented")
        if self._dense is not None:
            lu, piv = self._dense
            diag = np.diag(lu)
            swaps = int(np.count_nonzero(piv != np.arange(piv.size)))
            perm_sign = -1 if swaps % 2 else 1
        else:
            diag = self._sparse.U.diagonal()
            perm_sign = _permutation_sign(self._sparse.perm_r) \
                * _permutation_sign(self._sparse.perm_c)
        if np.any(diag == 0.0):
            return 0, -math.inf
        negatives = int(np.count_nonzero(diag < 0.0))
        sign = perm_sign * (-1 if negatives % 2 else 1)
        return sign, float(np.sum(np.log(np.abs(diag))))

    def solve(self, b: NDArray) -> NDArray:
        """Solve ``A x = b`` for ``b`` of shape ``(n,)`` or ``(n, k)``."""
        if self._stats is not None:
            self._stats.solves += 1
        if self._dense is not None:
            lu, piv = self._dense
            rhs = np.asarray(b)
            (getrs,) = sl.get_lapack_funcs(("getrs",), (lu, rhs))
            x, info = getrs(lu, piv, rhs)  # LAPACK directly: no wrapper checks per solve
            if info != 0:
                raise ValueError(f"getrs failed with info = {info}")
            return x
        b = np.asarray(b)
        if np.iscomplexobj(b) and not self._complex:
            return self._sparse.solve(b.real) + 1j * self._sparse.solve(b.imag)
        return self._sparse.solve(b)


def factorize(
    A: sp.spmatrix | NDArray, *, stats: Stats | None = None, where: str = "linear solve",
    dense_threshold: int = DENSE_THRESHOLD, check_condition: bool = True,
) -> Factorization:
    """LU-factorise ``A`` (dense for small sizes, SuperLU otherwise).

    Parameters
    ----------
    A : sparse matrix or array, shape (n, n)
        Matrix to factorise.
    stats : Stats, optional
        Counter to increment.
    where : str
        Label used in the error message.
    dense_threshold : int
        Largest size factorised densely.
    check_condition : bool
        Dense path: judge singularity by the condition estimate (below). False checks only
        for a zero or non-finite pivot, for hot loops whose matrices are regular by
        construction (damped dynamic stiffnesses, tone by tone); its cost is then the LU's
        alone (the estimate doubles it at 150 rows).

    Raises
    ------
    ConvergenceError
        If the matrix is singular to working precision.

    Notes
    -----
    The dense path judges singularity by the condition number of ``A C``, where the
    diagonal ``C`` (powers of two) brings the largest entry of every column near 1. Partial
    pivoting is blind to column scaling, so the LU factors of ``A C`` are those of ``A``
    with the columns of ``U`` scaled, and the solution is exactly as accurate. A matrix that
    is only badly scaled, such as the stiffness of a rotor whose pinned supports are 1e20
    N/m springs beside a shaft of 1e7 N/m, is then not mistaken for a singular one.

    Examples
    --------
    >>> A = np.array([[1e20, -1e7], [-1e7, 2e7]])   # badly scaled, not singular
    >>> x = factorize(A).solve(A @ np.array([1.0, 2.0]))
    >>> bool(np.allclose(x, [1.0, 2.0], rtol=1e-12))
    True
    """
    n = A.shape[0]
    if stats is not None:
        stats.factorizations += 1
    if n <= dense_threshold:
        dense = A.toarray() if sp.issparse(A) else np.asarray(A)  # type: ignore[union-attr]
        with warnings.catch_warnings():  # singularity is reported below as ConvergenceError
            warnings.simplefilter("ignore", sl.LinAlgWarning)
            lu, piv = sl.lu_factor(dense, check_finite=False)
        if check_condition:
            singular = bool(_reciprocal_condition(dense, lu) < np.finfo(float).eps)
        else:
            pivots = np.abs(np.diagonal(lu))
            singular = not bool(np.all(np.isfinite(pivots)) and pivots.min(initial=np.inf) > 0)
        if singular:
            raise ConvergenceError("matrix is singular to working precision", where)
        return Factorization(n, _dense=(lu, piv), _stats=stats)
    try:
        lu_sparse = spl.splu(sp.csc_matrix(A))
    except RuntimeError as exc:  # SuperLU: "Factor is exactly singular"
        raise ConvergenceError(f"matrix is singular ({exc})", where) from exc
    return Factorization(n, _sparse=lu_sparse, _stats=stats, _complex=bool(np.iscomplexobj(A)))


def _reciprocal_condition(A: NDArray, lu: NDArray) -> float:
    """LAPACK estimate of ``1 / cond_1(A C)`` from the LU factors of ``A`` (0 for a zero
    pivot), ``C`` the column equilibration of ``A`` (see :func:`factorize`)."""
    d = np.abs(np.diag(lu))
    if not np.all(np.isfinite(d)) or d.min() == 0.0:
        return 0.0
    magnitude = np.abs(A)
    largest = magnitude.max(axis=0)
    ok = np.isfinite(largest) & (largest > 0)
    col = np.ldexp(1.0, np.where(ok, -np.round(np.log2(np.where(ok, largest, 1.0))), 0.0)
                   .astype(np.int64))
    # LU of A C: same L and pivots, U C (col: powers of two, exact); in place on one copy
    scaled = lu.copy()
    np.multiply(scaled, col, out=scaled, where=_upper(lu.shape[0]))
    (gecon,) = sl.get_lapack_funcs(("gecon",), (scaled,))
    rcond, _ = gecon(scaled, float((magnitude.sum(axis=0) * col).max()), norm="1")
    return float(rcond)


@functools.lru_cache(maxsize=8)
def _upper(n: int) -> NDArray[np.bool_]:
    """Mask of the upper triangle (diagonal included) of an ``n x n`` matrix (cached: the
    hot loops factorise many matrices of one size)."""
    return np.triu(np.ones((n, n), dtype=bool))


def _permutation_sign(perm: NDArray[np.int_]) -> int:
    """Sign of a permutation: ``(-1)^(n - cycles)``, cycles found by pointer doubling."""
    n = perm.size
    label = np.arange(n)
    jump = np.asarray(perm)
    for _ in range(max(1, int(n).bit_length())):
        label = np.minimum(label, label[jump])
        jump = jump[jump]
    cycles = int(np.count_nonzero(label == np.arange(n)))
    return -1 if (n - cycles) % 2 else 1
