"""The constant part of an iteration matrix, ``sum_i c_i A_i``, summed in one pass.

A run-up factorises ``S_0(s) = c_M M + c_C C + c_C s G + c_K K`` at a few speed nodes ``s``
(:mod:`~rotorsim.time_integration.newmark_step`). Summing four sparse matrices anew at each
node costs about as much as the factorisation itself (sparse additions, format conversions,
pattern merges). :class:`MergedMatrices` merges the patterns once per problem: it keeps each
matrix's entries aligned on the union pattern, so any sum costs a few vector operations.
The sum is formed term by term in the order of :func:`~.problem.combine` and exact zeros are
dropped as sparse additions drop them, so the matrix handed to the factorisation is the one
``combine`` gives, bit for bit (a test checks it).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.solvers.linear import DENSE_THRESHOLD, Factorization, factorize
from rotorsim.time_integration.banded_lu import BandedLU, BandLayout, FloatArray, IntArray

BoolArray = NDArray[np.bool_]

Matrix = Any
"""A dense array or a scipy sparse matrix."""


@dataclass(frozen=True, eq=False)
class MergedMatrices:
    """Matrices ``A_i`` on one merged pattern, for sums ``sum_i c_i A_i``.

    Attributes
    ----------
    n : int
        Size of the matrices.
    present : tuple of int
        Positions (in the list given to :meth:`build`) of the matrices that are not None.
    aligned : tuple of arrays
        Each present matrix's entries on the merged pattern (sparse: data vectors in CSC
        order, zeros where the matrix has no entry) or the dense matrices.
    indices, indptr : int arrays or None
        The merged CSC pattern (None for dense matrices).
    band : BandLayout or None
        Band storage of the merged pattern when its band is narrow (then :meth:`factorize`
        gives a banded LU).
    local, local_entries, local_mask : arrays or None
        Rows and columns (k,) of a block that :meth:`factorize` may add and (sparse
        storage) the positions in the merged data of its entries where the flattened
        ``(k, k)`` mask is true (elsewhere the block is zero).
    """

    n: int
    present: tuple[int, ...]
    aligned: tuple[FloatArray, ...]
    indices: IntArray | None = None
    indptr: IntArray | None = None
    band: BandLayout | None = None
    local: IntArray | None = None
    local_entries: IntArray | None = None
    local_mask: BoolArray | None = None

    @classmethod
    def build(cls, matrices: Sequence[Matrix | None], n: int,
              local: tuple[IntArray, BoolArray] | None = None) -> MergedMatrices | None:
        """Merge the matrices (None entries are absent). Dense storage for ``n <=
        DENSE_THRESHOLD``, as :func:`~.problem.combine` sums, and for all-dense input unless
        its band is narrow (then the sparse pattern with a banded LU); None when dense and
        sparse are mixed or a sparse matrix is not canonical (the caller then sums with
        ``combine``). ``local = (dofs, pattern)`` makes room for a block on the rows and
        columns ``dofs`` (k,), nonzero where the ``(k, k)`` boolean ``pattern`` is true,
        added by :meth:`factorize`."""
        present = tuple(i for i, A in enumerate(matrices) if A is not None)
        given: list[Matrix] = [matrices[i] for i in present]
        if n <= DENSE_THRESHOLD or not any(sp.issparse(A) for A in given):
            dense = tuple(A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float)
                          for A in given)
            banded = None if n <= DENSE_THRESHOLD else cls._sparse(
                present, [sp.csr_matrix(A) for A in dense], n, local)
            return banded if banded is not None and banded.band is not None \
                else cls(n, present, dense, local=None if local is None else local[0])
        if not all(sp.issparse(A) and A.has_canonical_format for A in given):
            return None
        return cls._sparse(present, given, n, local)

    @classmethod
    def _sparse(cls, present: tuple[int, ...], given: list[Matrix], n: int,
                local: tuple[IntArray, BoolArray] | None) -> MergedMatrices:
        csc = [sp.csc_matrix(A) for A in given]
        for A in csc:
            A.sort_indices()
        ones = [sp.csc_matrix((np.ones(A.nnz), A.indices, A.indptr), shape=(n, n))
                for A in csc]  # stored zeros count: a sum of ones cannot cancel
        rows = cols = mask = None
        if local is not None:
            dofs, mask = local[0], local[1].ravel()
            rows, cols = np.repeat(dofs, dofs.size)[mask], np.tile(dofs, dofs.size)[mask]
            ones.append(sp.csc_matrix((np.ones(rows.size), (rows, cols)), shape=(n, n)))
        pattern = sp.csc_matrix(sum(ones[1:], start=ones[0]))
        pattern.sort_indices()
        keys = _keys(pattern, n)
        aligned = []
        for A in csc:
            data = np.zeros(keys.size)
            data[np.searchsorted(keys, _keys(A, n))] = A.data
            aligned.append(data)
        where = None
        if rows is not None and cols is not None:  # the block's entries on the pattern
            where = np.searchsorted(keys, cols * n + rows)
        return cls(n, present, tuple(aligned), pattern.indices, pattern.indptr,
                   BandLayout.of(pattern), None if local is None else local[0], where,
                   mask)

    def factorize(self, coefficients: Sequence[float], where: str,
                  dense_threshold: int = DENSE_THRESHOLD,
                  block: FloatArray | None = None) -> Factorization | BandedLU:
        """LU of ``sum_i c_i A_i`` (``coefficients`` in the order given to :meth:`build`),
        plus ``block`` (k, k) on the rows and columns ``local`` when given: banded when the
        merged pattern's band is narrow, else as :func:`~rotorsim.solvers.linear.factorize`.
        """
        total = self._total(coefficients)
        if block is not None:
            if self.local is None:
                raise ValueError("built without 'local' rows and columns for a block")
            if self.indices is None:
                total[np.ix_(self.local, self.local)] += block
            else:
                total[self.local_entries] += block.ravel()[self.local_mask]
        if self.band is not None:
            return self.band.factorize(total, where)
        if self.indices is None or self.indptr is None:
            return factorize(total, where=where, dense_threshold=dense_threshold)
        return factorize(self._csc(total), where=where, dense_threshold=dense_threshold)

    def at(self, coefficients: Sequence[float]) -> Matrix:
        """``sum_i c_i A_i``: a CSC matrix without stored zeros, or a dense array."""
        total = self._total(coefficients)
        return total if self.indices is None else self._csc(total)

    def _csc(self, data: FloatArray) -> sp.csc_matrix:
        """The merged pattern with the entries ``data``, without stored zeros."""
        assert self.indices is not None and self.indptr is not None
        out = sp.csc_matrix((data, self.indices.copy(), self.indptr.copy()),
                            shape=(self.n, self.n))
        out.eliminate_zeros()
        return out

    @property
    def dense(self) -> bool:
        """True when the matrices are stored dense."""
        return self.indices is None

    def _total(self, coefficients: Sequence[float]) -> FloatArray:
        """The summed entries, term by term in order (as :func:`~.problem.combine`)."""
        total = None
        for i, data in zip(self.present, self.aligned, strict=True):
            term = coefficients[i] * data
            total = term if total is None else total + term
        if total is not None:
            return total
        return np.zeros((self.n, self.n)) if self.indices is None else np.zeros(0)


def _keys(A: sp.csc_matrix, n: int) -> IntArray:
    """Column-major position ``col * n + row`` of each stored entry of a CSC matrix
    (increasing for sorted indices)."""
    cols = np.repeat(np.arange(n, dtype=np.int64), np.diff(A.indptr))
    return cols * n + A.indices.astype(np.int64)
