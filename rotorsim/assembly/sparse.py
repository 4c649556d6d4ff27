"""One shared CSR sparsity pattern for all global matrices.

Element blocks are scattered into the pattern with ``numpy.bincount`` over precomputed
positions, so building M, C, G or K is one vectorised call and never rebuilds the pattern.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.elements.base import FloatArray


@dataclass(frozen=True, eq=False)
class SparsityPattern:
    """CSR pattern of an ``n x n`` matrix and the scatter positions of its entries.

    Build it with :meth:`from_blocks`: for every group of element blocks, ``positions`` holds
    the CSR data index of each block entry (``-1`` where the entry touches a fixed DOF).
    """

    n: int
    indptr: NDArray[np.int64]
    indices: NDArray[np.int64]
    positions: tuple[NDArray[np.int64], ...]

    @classmethod
    def from_blocks(cls, n: int, dof_groups: list[NDArray[np.int64]]) -> SparsityPattern:
        """Pattern from groups of element DOF index arrays.

        Parameters
        ----------
        n : int
            Matrix size (free DOFs).
        dof_groups : list of int arrays ``(E, d)``
            Free-DOF index of each element DOF, ``-1`` for fixed DOFs.
        """
        keys, valid = [], []
        for dofs in dof_groups:
            rows = np.repeat(dofs[:, :, None], dofs.shape[1], axis=2)
            cols = np.repeat(dofs[:, None, :], dofs.shape[1], axis=1)
            ok = (rows >= 0) & (cols >= 0)
            keys.append(np.where(ok, rows * n + cols, -1).ravel())
            valid.append(ok.ravel())
        all_keys = np.concatenate(keys) if keys else np.zeros(0, dtype=np.int64)
        unique, inverse = np.unique(all_keys[all_keys >= 0], return_inverse=True)
        positions, start = [], 0
        for k in keys:
            pos = np.full(k.size, -1, dtype=np.int64)
            ok = k >= 0
            count = int(ok.sum())
            pos[ok] = inverse[start : start + count]
            start += count
            positions.append(pos)
        rows = unique // n
        indptr = np.zeros(n + 1, dtype=np.int64)
        np.add.at(indptr, rows + 1, 1)
        return cls(n=n, indptr=np.cumsum(indptr), indices=unique % n,
                   positions=tuple(positions))

    @property
    def nnz(self) -> int:
        return int(self.indices.size)

    def scatter(self, group: int, blocks: FloatArray) -> FloatArray:
        """CSR data array holding the summed entries of ``blocks`` (E, d, d) of ``group``."""
        pos = self.positions[group]
        ok = pos >= 0
        return np.bincount(pos[ok], weights=np.ravel(blocks)[ok], minlength=self.nnz).astype(float)

    def matrix(self, data: FloatArray) -> sp.csr_matrix:
        """CSR matrix with this pattern and ``data``."""
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))
