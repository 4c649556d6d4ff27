"""Ritz pairs of a reduced Campbell's projected problems at one speed.

:mod:`~rotorsim.analyses.linear.campbell_reduced` keeps one orthonormal real basis per
uncoupled block of DOFs (:class:`Block`) and, at each speed, asks here for the ``n_wanted``
lowest elastic Ritz pairs over all blocks (:func:`ritz_pairs`). The cost of a speed is the
dense eigenvalue problem of the largest block: its eigenvalues only are computed, then the
eigenvectors of the pairs kept, by inverse iteration (:class:`Spectrum`); the rigid-body
test of :func:`~rotorsim.analyses.linear.modal.modal` runs only on pairs whose ``|lam|``
could pass it (:func:`_rigid_bound`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.linear.modal import _elastic_indices
from rotorsim.assembly.system import SystemMatrices
from rotorsim.solvers.eigen import RIGID_ROUNDING
from rotorsim.solvers.projected_eigen import (
    inverse_iteration,
    projected_quadratic_eigen,
    projected_quadratic_values,
)

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
IntArray = NDArray[np.int64]


@dataclass
class Block:
    """DOFs of one uncoupled block, its basis and the projected constant matrices."""

    dofs: IntArray
    V: FloatArray
    reduced: dict[str, FloatArray] = field(default_factory=dict)
    solved: dict[str, FloatArray] = field(default_factory=dict)
    """``P^-1 A V`` on the block's DOFs for ``A`` in ``M, C, G, K`` (constant matrices only):
    residuals of Ritz pairs then cost dense products instead of sparse ones and a solve."""
    pairs: tuple[ComplexArray, ComplexArray] | None = None
    """The projected eigenpairs of a block whose projected ``G`` is zero (axial, torsional):
    the same at every speed, solved once per basis."""
    solved_stack: FloatArray | None = None
    """``[P^-1 M V, P^-1 C V, P^-1 G V, P^-1 K V]`` side by side."""
    rigid_bound: tuple[int, float] | None = None
    """Basis size and :func:`_rigid_bound` for it."""
    rigid_known: dict[int, bool] = field(default_factory=dict)
    """Rigid-body verdicts on the columns of :attr:`pairs`."""


@dataclass(frozen=True, eq=False)
class RitzPairs:
    """Kept Ritz pairs: eigenvalues ``(k,)``, shapes on the free DOFs ``(n, k)``, the block
    of each pair ``(k,)`` and, per block, the basis coordinates of its pairs."""

    values: ComplexArray
    vectors: ComplexArray
    block: IntArray
    coordinates: dict[int, ComplexArray]


def ritz_pairs(blocks: list[Block], speed: float, n_wanted: int, shift: float,
          mats: SystemMatrices, abs_k: sp.csr_matrix | None, n_rigid: int,
          rigid_test: bool = True) -> RitzPairs:
    """The ``n_wanted`` lowest elastic Ritz pairs of all blocks, on the free DOFs.

    Only the ``2 (n_wanted + n_rigid) + 8`` pairs nearest the shift over all blocks are
    candidates (``n_rigid``: the most rigid-body modes a sample had). With ``rigid_test``,
    those whose ``|lam|`` is within :func:`_rigid_bound` are lifted to the full space and
    tested for rigid-body motion. Without it (constant matrices whose samples had no
    rigid-body mode: ``K`` is then regular, and a pair with ``K x`` at the rounding level
    cannot exist at any speed) no pair is tested. Only the kept pairs are lifted, and only
    their eigenvectors are computed (:class:`Spectrum`).
    """
    n = mats.M.shape[0]
    n_candidates = 2 * (n_wanted + n_rigid) + 8
    spectra = {k: Spectrum(block, speed, shift, n_candidates)
               for k, block in enumerate(blocks) if block.V.shape[1]}
    lam = np.concatenate([s.values for s in spectra.values()])
    which = np.concatenate([np.full(s.values.size, k) for k, s in spectra.items()])
    col = np.concatenate([np.arange(s.values.size) for s in spectra.values()])
    order = np.argsort(np.abs(lam - shift), kind="stable")[:n_candidates]
    rigid = np.zeros(order.size, dtype=bool)
    if rigid_test:
        bounds = {k: _rigid_bound(blocks[k], mats, abs_k) for k in spectra}
        suspect = np.flatnonzero(np.abs(lam[order])
                                 <= np.array([bounds[int(k)] for k in which[order]]))
        rigid[suspect] = _rigid_suspects(blocks, spectra, lam[order[suspect]],
                                         which[order[suspect]], col[order[suspect]], mats,
                                         abs_k)
    keep = _elastic_indices(lam[order], rigid)[:n_wanted]
    sel = order[keep]
    X = _lift(blocks, spectra, which[sel], col[sel], n)
    kept = {int(k): spectra[int(k)].vectors(col[sel][which[sel] == k])
            for k in np.unique(which[sel])}
    return RitzPairs(lam[sel], X, which[sel], kept)


SEPARATION = 1e-7
"""Eigenvalues of a projected problem closer than this (relative) to another get their
eigenvectors from a full dense eigensolve, not from inverse iteration (whose error goes as
``eps / separation``)."""


class Spectrum:
    """Eigenvalues of one block's projected problem at one speed (nearest the shift first),
    and their eigenvectors on demand.

    A block whose projected ``G`` is zero has the same pairs at every speed: they are solved
    once per basis (with eigenvectors) and kept in the block. Otherwise only the eigenvalues
    are computed, and the eigenvectors of the pairs asked for by
    :func:`~rotorsim.solvers.projected_eigen.inverse_iteration`, unless two of the
    ``n_candidates`` nearest the shift are closer than :data:`SEPARATION` or an inverse
    iteration fails: then all pairs come from one full dense eigensolve.
    """

    def __init__(self, block: Block, speed: float, shift: float, n_candidates: int):
        r = block.reduced
        self._matrices = (r["M"], r["C"] + speed * r["G"], r["K"])
        self._shift = shift
        self._Y: ComplexArray | None = None
        self._cache: dict[int, ComplexArray] = {}
        if block.pairs is None and not np.any(r["G"]):
            block.pairs = projected_quadratic_eigen(*self._matrices, shift)
        if block.pairs is not None:
            self.values, self._Y = block.pairs
        else:
            self.values = projected_quadratic_values(*self._matrices, shift)
            if not _separated(self.values, n_candidates):
                self._full()

    def _full(self) -> ComplexArray:
        values, Y = projected_quadratic_eigen(*self._matrices, self._shift)
        if values.size != self.values.size or not np.allclose(values, self.values,
                                                               rtol=1e-8, atol=0.0):
            raise np.linalg.LinAlgError("the eigenvalues of a projected problem differ "
                                        "between two dense eigensolves")
        self.values, self._Y = values, Y
        return Y

    def vectors(self, cols: IntArray) -> ComplexArray:
        """Basis coordinates ``(m, len(cols))`` of the pairs ``cols``."""
        if self._Y is not None:
            return self._Y[:, cols]
        missing = [int(c) for c in cols if int(c) not in self._cache]
        if missing:
            try:
                Y = inverse_iteration(*self._matrices, self.values[missing])
            except np.linalg.LinAlgError:
                return self._full()[:, cols]
            if not np.all(np.isfinite(Y)):
                return self._full()[:, cols]
            self._cache.update(zip(missing, Y.T, strict=True))
        return np.stack([self._cache[int(c)] for c in cols], axis=1)


def _separated(values: ComplexArray, n_candidates: int) -> bool:
    """Whether each of the ``n_candidates`` first ``values`` is farther than
    :data:`SEPARATION` (relative) from every other value."""
    head = values[:n_candidates]
    distance = np.abs(head[:, None] - values[None, :])
    distance[np.arange(head.size), np.arange(head.size)] = np.inf
    return bool(np.all(distance.min(axis=1, initial=np.inf)
                       > SEPARATION * np.maximum(np.abs(head), np.finfo(float).tiny)))


def _rigid_bound(block: Block, mats: SystemMatrices, abs_k: sp.csr_matrix | None) -> float:
    """An upper bound [rad/s] of the rigid-body threshold of :func:`_rigid_mask` for every
    Ritz pair of ``block``: pairs with a larger ``|lam|`` need no test.

    For ``x = V y`` (``||x|| = ||y||``): ``|x|^T |K| |x| <= || |K| ||_2 ||y||^2 <=
    ||K||_inf ||y||^2`` (``K`` symmetric, so ``||K||_1 = ||K||_inf``) and
    ``x^H M x = y^H Mr y >= mu_min(Mr) ||y||^2``, so the threshold
    ``sqrt(RIGID_ROUNDING eps |x|^T |K| |x| / x^H M x)`` is at most
    ``sqrt(RIGID_ROUNDING eps ||K||_inf / mu_min(Mr))``. Kept per basis.
    """
    if block.rigid_bound is None or block.rigid_bound[0] != block.V.shape[1]:
        abs_k = abs(mats.K) if abs_k is None else abs_k
        k_norm = float(np.max(np.asarray(abs_k[block.dofs].sum(axis=1)).ravel(), initial=0.0))
        mu_min = float(np.linalg.eigvalsh(block.reduced["M"])[0])
        bound = np.inf if mu_min <= 0 else np.sqrt(RIGID_ROUNDING * np.finfo(float).eps
                                                   * k_norm / mu_min)
        block.rigid_bound = (block.V.shape[1], bound)
    return block.rigid_bound[1]


def _rigid_suspects(blocks: list[Block], spectra: dict[int, Spectrum], lam: ComplexArray,
                    which: IntArray, col: IntArray, mats: SystemMatrices,
                    abs_k: sp.csr_matrix | None) -> NDArray[np.bool_]:
    """:func:`_rigid_mask` of the suspects; the verdicts on the pairs of a block that are
    the same at every speed (:attr:`Block.pairs`) are kept in the block."""
    rigid = np.zeros(lam.size, dtype=bool)
    known = np.array([blocks[k].pairs is not None and int(c) in blocks[k].rigid_known
                      for k, c in zip(which, col, strict=True)], dtype=bool)
    for j in np.flatnonzero(known):
        rigid[j] = blocks[which[j]].rigid_known[int(col[j])]
    todo = np.flatnonzero(~known)
    if todo.size:
        X = _lift(blocks, spectra, which[todo], col[todo], mats.M.shape[0])
        rigid[todo] = _rigid_mask(lam[todo], X, mats, abs_k)
        for j in todo:
            if blocks[which[j]].pairs is not None:
                blocks[which[j]].rigid_known[int(col[j])] = bool(rigid[j])
    return rigid


def _lift(blocks: list[Block], spectra: dict[int, Spectrum], which: IntArray,
          col: IntArray, n: int) -> ComplexArray:
    """Ritz vectors on the free DOFs from their blocks' coordinates."""
    X = np.zeros((n, which.size), dtype=complex)
    for k in np.unique(which):
        mine = np.flatnonzero(which == k)
        X[np.ix_(blocks[k].dofs, mine)] = blocks[k].V @ spectra[int(k)].vectors(col[mine])
    return X


def _rigid_mask(lam: ComplexArray, X: ComplexArray, mats: SystemMatrices,
                abs_k: sp.csr_matrix | None) -> NDArray[np.bool_]:
    """The rigid-body test of :func:`~rotorsim.analyses.linear.modal.modal` (elastic energy
    at the rounding level of ``K x``), with ``|K|`` formed once."""
    abs_k = abs(mats.K) if abs_k is None else abs_k
    size = np.abs(X)
    rounding = RIGID_ROUNDING * np.finfo(float).eps * np.einsum("ij,ij->j", size,
                                                                abs_k @ size)
    kinetic = np.real(np.einsum("ij,ij->j", X.conj(), mats.M @ X))
    return np.asarray(np.abs(lam) <= np.sqrt(rounding / kinetic))
