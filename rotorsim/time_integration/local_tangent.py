"""Tangents that live on a few unknowns, and the low-rank solves they allow.

The restoring force of a rotor on nonlinear bearings acts on the bearing DOFs only (a few
tens of the model's hundreds or thousands), so its tangents ``dr/dq`` and ``dr/dv`` are
:class:`LocalMatrix` objects: an ``(n, n)`` matrix that is zero outside rows and columns
``dofs``. The iteration matrix of an implicit step is then ``S = S0 + P B P^T`` with the
constant part ``S0`` (mass, damping, gyroscopic and linear stiffness terms), ``P`` the
columns of the identity at ``dofs`` and a small ``k x k`` block ``B``. :class:`LowRankSolve`
solves with ``S`` by the Sherman-Morrison-Woodbury identity

    S^-1 b = y - Z (I + B Z_d)^-1 B y_d,   y = S0^-1 b,   Z = S0^-1 P,   Z_d = P^T Z,

so ``S0`` is factorised once per step size and spin speed (once per run at constant speed)
and each Newton iteration costs one solve with ``S0`` and one ``k x k`` LU: the condensation
of the step onto the nonlinear DOFs.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import Factorization
from rotorsim.time_integration.banded_lu import BandedLU

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
_GETRF, _GETRS = sl.get_lapack_funcs(("getrf", "getrs"), (np.zeros((1, 1)),))
"""LAPACK LU of the small capacitance matrix, called directly (no wrapper checks)."""


@dataclass(frozen=True, eq=False)
class LocalMatrix:
    """An ``(n, n)`` matrix that is zero outside rows and columns ``dofs``.

    Parameters
    ----------
    n : int
        Size of the full matrix.
    dofs : int array (k,)
        Distinct indices of the nonzero rows and columns.
    block : array (k, k)
        The entries ``A[dofs][:, dofs]``.

    Examples
    --------
    >>> A = LocalMatrix(4, np.array([1, 3]), np.array([[2.0, -1.0], [-1.0, 2.0]]))
    >>> (A @ np.ones(4)).tolist()
    [0.0, 1.0, 0.0, 1.0]
    """

    n: int
    dofs: IntArray
    block: FloatArray

    @classmethod
    def trusted(cls, n: int, dofs: IntArray, block: FloatArray) -> LocalMatrix:
        """Build without validation (``dofs`` distinct int64 indices, ``block`` (k, k))."""
        out = object.__new__(cls)
        for name, value in (("n", n), ("dofs", dofs), ("block", block)):
            object.__setattr__(out, name, value)
        return out

    def __post_init__(self) -> None:
        dofs = np.asarray(self.dofs, dtype=np.int64).reshape(-1)
        block = np.asarray(self.block, dtype=float)
        k = dofs.size
        if block.shape != (k, k):
            raise ModelError(f"block has shape {block.shape}, expected ({k}, {k})",
                             "LocalMatrix")
        if k and (dofs.min() < 0 or dofs.max() >= self.n or np.unique(dofs).size != k):
            raise ModelError(f"dofs must be distinct indices in 0..{self.n - 1}",
                             "LocalMatrix")
        object.__setattr__(self, "dofs", dofs)
        object.__setattr__(self, "block", block)

    @property
    def shape(self) -> tuple[int, int]:
        return (self.n, self.n)

    def __matmul__(self, x: FloatArray) -> FloatArray:
        out = np.zeros(self.n, dtype=np.result_type(x, self.block))
        out[self.dofs] = self.block @ np.asarray(x)[self.dofs]
        return out

    def toarray(self) -> FloatArray:
        """Dense ``(n, n)`` copy."""
        out = np.zeros((self.n, self.n))
        out[np.ix_(self.dofs, self.dofs)] = self.block
        return out

    def tocsr(self) -> sp.csr_matrix:
        """CSR copy with the ``k x k`` nonzero pattern."""
        rows = np.repeat(self.dofs, self.dofs.size)
        cols = np.tile(self.dofs, self.dofs.size)
        return sp.csr_matrix((self.block.ravel(), (rows, cols)), shape=self.shape)


def embed(terms: list[tuple[float, LocalMatrix | None]]) -> tuple[IntArray, FloatArray]:
    """``sum(c * A)`` of local matrices as ``(dofs, block)`` on the union of their DOFs."""
    present = [(c, A) for c, A in terms if A is not None]
    first = present[0][1].dofs
    if all(A.dofs is first for _, A in present):
        block = present[0][0] * present[0][1].block
        for c, A in present[1:]:
            block = block + c * A.block
        return first, block
    dofs = np.unique(np.concatenate([A.dofs for _, A in present]))
    block = np.zeros((dofs.size, dofs.size))
    for c, A in present:
        pos = np.searchsorted(dofs, A.dofs)
        block[np.ix_(pos, pos)] += c * A.block
    return dofs, block


@dataclass(frozen=True, eq=False)
class BaseFactors:
    """``S0`` factorised, with ``Z = S0^-1 P`` for the DOFs ``dofs``."""

    lu: Factorization | BandedLU
    dofs: IntArray
    Z: FloatArray

    @classmethod
    def build(cls, lu: Factorization | BandedLU, dofs: IntArray) -> BaseFactors:
        P = np.zeros((lu.n, dofs.size))
        P[dofs, np.arange(dofs.size)] = 1.0
        return cls(lu, dofs, np.asarray(lu.solve(P)).reshape(lu.n, dofs.size))


@dataclass(frozen=True, eq=False)
class LowRankSolve:
    """Solves with ``S0 + P B P^T`` (module docstring); duck-types ``Factorization``."""

    base: BaseFactors
    capacitance: Any
    block: FloatArray

    @classmethod
    def build(cls, base: BaseFactors, block: FloatArray, where: str) -> LowRankSolve:
        """Factorise the capacitance matrix ``I + B Z_d``.

        Raises
        ------
        ConvergenceError
            When the updated iteration matrix is singular.
        """
        cap = np.eye(block.shape[0]) + block @ base.Z[base.dofs]
        lu, piv, _ = _GETRF(cap)
        d = np.abs(np.diag(lu))
        if not np.all(np.isfinite(d)) or d.min() <= 1e-14 * max(d.max(), 1.0):
            raise ConvergenceError(f"iteration matrix is singular ({where})", where)
        return cls(base, (lu, piv), block)

    @property
    def n(self) -> int:
        return self.base.lu.n

    def solve(self, b: FloatArray) -> FloatArray:
        """``S^-1 b`` for ``b`` of shape ``(n,)``."""
        y = np.asarray(self.base.lu.solve(b))
        lu, piv = self.capacitance
        w, _ = _GETRS(lu, piv, self.block @ y[self.base.dofs])
        return y - self.base.Z @ w
