"""The constant part of a Newmark iteration matrix at a speed node, assembled in one pass.

A run-up factorises ``S(s) = c_M M + c_C C + c_C s G + c_K K`` at a few speed nodes ``s``
(:mod:`~rotorsim.time_integration.newmark_step`). Summing four sparse matrices anew at each
node costs about as much as the factorisation itself (sparse additions, format conversions,
pattern merges). :class:`SpeedNodeMatrix` merges the patterns once per step size: it keeps
each matrix's entries aligned on the union pattern, so a node costs four vector operations.
The sum is formed term by term in the order of :func:`~.problem.combine` and exact zeros are
dropped as sparse additions drop them, so the matrix handed to the factorisation is the one
``combine`` gives, bit for bit (a test checks it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.time_integration.banded_lu import BandedLU, BandLayout, IntArray
from rotorsim.time_integration.problem import FloatArray, Matrix


@dataclass(frozen=True, eq=False)
class SpeedNodeMatrix:
    """``sum_i c_i A_i`` with one coefficient varying, on a pattern merged once.

    Attributes
    ----------
    n : int
        Size of the matrices.
    coefficients : tuple of float
        ``c_i`` of the terms; the one at ``varying`` is replaced at each evaluation.
    varying : int
        Index of the term whose coefficient varies (the gyroscopic one).
    aligned : tuple of arrays
        Each term's entries on the merged pattern (sparse: data vectors in CSC order,
        zeros where the term has no entry) or the dense matrices.
    indices, indptr : int arrays or None
        The merged CSC pattern (None for dense matrices).
    band : BandLayout or None
        Band storage of the merged pattern when its band is narrow (then :meth:`factorize`
        gives a banded LU).
    """

    n: int
    coefficients: tuple[float, ...]
    varying: int
    aligned: tuple[FloatArray, ...]
    indices: IntArray | None
    indptr: IntArray | None
    band: BandLayout | None = None

    @classmethod
    def build(cls, terms: list[tuple[float, Matrix | None]], varying: int,
              n: int) -> SpeedNodeMatrix | None:
        """Merge the terms ``(c_i, A_i)`` (absent matrices dropped); ``varying`` indexes
        ``terms``. None when the storage is mixed or a sparse matrix is not canonical (the
        caller then sums with :func:`~.problem.combine`)."""
        present = [(i, c, A) for i, (c, A) in enumerate(terms) if A is not None]
        if n <= DENSE_THRESHOLD or not any(sp.issparse(A) for _, _, A in present):
            dense = tuple(A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float)
                          for _, _, A in present)
            return cls._of(present, varying, n, dense, None, None)
        if not all(sp.issparse(A) and A.has_canonical_format for _, _, A in present):
            return None
        csc = [sp.csc_matrix(A) for _, _, A in present]
        for A in csc:
            A.sort_indices()
        ones = [sp.csc_matrix((np.ones(A.nnz), A.indices, A.indptr), shape=(n, n))
                for A in csc]  # stored zeros count: the sum of ones cannot cancel
        pattern = sp.csc_matrix(sum(ones[1:], start=ones[0]))
        pattern.sort_indices()
        keys = _keys(pattern, n)
        aligned = []
        for A in csc:
            data = np.zeros(keys.size)
            data[np.searchsorted(keys, _keys(A, n))] = A.data
            aligned.append(data)
        return cls._of(present, varying, n, tuple(aligned), pattern.indices, pattern.indptr,
                       BandLayout.of(pattern))

    @classmethod
    def _of(cls, present: list[tuple[int, float, Matrix]], varying: int, n: int,
            aligned: tuple[FloatArray, ...], indices: IntArray | None,
            indptr: IntArray | None, band: BandLayout | None = None) -> SpeedNodeMatrix:
        order = [i for i, _, _ in present]
        position = order.index(varying) if varying in order else -1
        return cls(n, tuple(c for _, c, _ in present), position, aligned, indices, indptr,
                   band)

    def factorize(self, coefficient: float, where: str,
                  dense_threshold: int = DENSE_THRESHOLD) -> Factorization | BandedLU:
        """LU of the sum with ``coefficient`` for the varying term: banded when the merged
        pattern's band is narrow, else as :func:`~rotorsim.solvers.linear.factorize`."""
        if self.band is not None:
            return self.band.factorize(self._total(coefficient), where)
        return factorize(self.at(coefficient), where=where, dense_threshold=dense_threshold)

    def at(self, coefficient: float) -> Matrix:
        """The sum with ``coefficient`` for the varying term: a CSC matrix without stored
        zeros, or a dense array."""
        total = self._total(coefficient)
        if self.indices is None or self.indptr is None:
            return total
        out = sp.csc_matrix((total, self.indices.copy(), self.indptr.copy()),
                            shape=(self.n, self.n))
        out.eliminate_zeros()
        return out


    def _total(self, coefficient: float) -> FloatArray:
        """The summed entries (in the order of :func:`~.problem.combine`)."""
        total = None
        for i, (c, data) in enumerate(zip(self.coefficients, self.aligned, strict=True)):
            term = (coefficient if i == self.varying else c) * data
            total = term if total is None else total + term
        if total is not None:
            return total
        return np.zeros((self.n, self.n)) if self.indices is None else np.zeros(0)


def _keys(A: sp.csc_matrix, n: int) -> IntArray:
    """Column-major position ``col * n + row`` of each stored entry of a CSC matrix
    (increasing for sorted indices)."""
    cols = np.repeat(np.arange(n, dtype=np.int64), np.diff(A.indptr))
    return cols * n + A.indices.astype(np.int64)
