"""Modes over a speed grid from one reduced basis, every mode checked in the full space.

The low modes of a rotor at all speeds of a Campbell grid span a subspace of small
dimension. :func:`reduced_modes` builds an orthonormal real basis of it and solves, at
every speed, the projected dense problem (:mod:`rotorsim.solvers.projected_eigen`):

1. the modes at the first and last speeds, from the same full shift-invert solve that
   :func:`~rotorsim.analyses.linear.modal.modal` makes, with two modes more than wanted
   (:data:`SAMPLE_MARGIN`), start the basis (their real and imaginary parts, orthonormalised
   with singular values below :data:`SVD_TOL` of the largest dropped);
2. DOFs that no matrix entry couples (lateral, axial and torsional motions of a straight
   rotor on radial bearings) form separate blocks, each with its own basis and its own
   projected problem: the dense solves, cubic in size, are then cheaper;
3. at every speed the eigenvalues of the projected problems are computed and the
   ``n_wanted`` lowest elastic ones kept; only their eigenvectors are formed, by inverse
   iteration (:class:`_Spectrum`; a block whose projected ``G`` is zero is solved once).
   Every kept pair's relative residual ``||P^-1 (lam^2 M + lam (C + W G) + K) x|| / ||x||``
   is evaluated in the full space at that speed (``P`` the shifted stiffness of the solve,
   :func:`~rotorsim.solvers.projected_eigen.shift_inverted_residuals`; with constant
   matrices from ``P^-1 M V``, ``P^-1 C V``, ``P^-1 G V`` and ``P^-1 K V`` formed once per
   basis, :func:`_reduced_residuals`). Pairs above
   ``tol`` add their preconditioned residuals to the basis and the speed is solved again;
4. a speed whose kept modes reach above the modes the samples on both sides put in the
   basis, or that is not converged after :data:`MAX_REFINEMENTS` refinements, is solved in
   full and becomes a sample.

Every returned mode therefore has a residual in the full space below ``tol``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.linear.campbell_ritz import Block, RitzPairs, ritz_pairs
from rotorsim.analyses.linear.modal import _elastic_indices, _rigid
from rotorsim.assembly.system import RotorSystem, SystemMatrices
from rotorsim.errors import ConvergenceError
from rotorsim.solvers.eigen import default_shift, quadratic_eigen
from rotorsim.solvers.linear import Factorization, factorize
from rotorsim.solvers.projected_eigen import extend_basis, shift_inverted_residuals
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
IntArray = NDArray[np.int64]

RESIDUAL_TOL = 1e-6
"""Default largest relative residual of a returned mode [-]. The modes today's full ARPACK
solve returns (``tol = 1e-11`` on the shift-inverted operator) measure 1e-11 to 2e-7 in this
norm on the 606-DOF benchmark rotor (the higher modes the larger); a Ritz pair at 1e-6 has
its eigenvalue within about 1e-10 relative of ARPACK's (measured, docs/benchmarks.md)."""
SVD_TOL = 3e-8
"""Directions of the sample modes with singular values below this fraction of the largest
are left out of the starting basis (refinement adds back what a speed needs). Measured on
the three 100-element benchmark rotors: 1e-9 kept 56-66 directions, 3e-8 keeps 52-62 with
no refinement and the same frequencies to 1e-11; 1e-6 needs refinements that add back more
than they saved."""
SAMPLE_MARGIN = 0.0
"""Sample solves ask for this fraction of the wanted modes beyond them, and at least 2 more
(measured on the three 100-element benchmark rotors: a quarter more gave 4-5 more basis
vectors and 10 % more time, for no refinement saved)."""
MAX_REFINEMENTS = 3
"""Basis refinements at one speed before it is solved in full instead."""


@dataclass(frozen=True, eq=False)
class SpeedModes:
    """Kept elastic modes at one speed: eigenvalues ``(k,)`` [rad/s], shapes on the free DOFs
    ``(n_free, k)`` and relative residuals ``(k,)`` [-] (0 for a full solve)."""

    values: ComplexArray
    vectors: ComplexArray
    residuals: FloatArray


@dataclass
class _State:
    blocks: list[Block]
    samples: dict[int, float]  # speed index -> |lam| up to which the sample holds all modes
    abs_k: sp.csr_matrix | None = None
    n_rigid: int = 0
    refinements: int = 0
    projected_solves: int = 0


def reduced_modes(system: RotorSystem, grid: FloatArray, n_wanted: int, *,
                  sigma: float | None, tol: float, sparse: bool | None, stats: Stats
                  ) -> tuple[list[SpeedModes | Exception], dict[str, float]]:
    """The ``n_wanted`` lowest elastic modes at every speed of ``grid``.

    Returns one :class:`SpeedModes` per speed (or the exception of a failed full solve) and
    counters: basis size, refinements, full solves, largest residual.
    """
    speed_dependent = bool(system.variable_bearings)
    constant = None if speed_dependent else system.matrices(0.0)

    def at(speed: float) -> SystemMatrices:
        return constant if constant is not None else system.matrices(speed)

    first = at(float(grid[0]))
    shift = default_shift(first.M, first.K) if sigma is None else float(sigma)
    lu = factorize(first.K + shift * (first.C + float(grid[0]) * first.G) + shift**2 * first.M,
                   stats=stats, where=f"campbell shift (sigma = {shift:.6g} rad/s)")
    state = _State([Block(d, np.zeros((d.size, 0))) for d in uncoupled_blocks(system)], {},
                   abs_k=None if constant is None else abs(constant.K))
    sample_wanted = n_wanted + max(2, int(np.ceil(SAMPLE_MARGIN * n_wanted)))
    ends = sorted({0, grid.size - 1})
    first_modes = {i: _sample(state, i, at(float(grid[i])), float(grid[i]), sample_wanted,
                              shift, sparse, stats, svd=True) for i in ends}
    if constant is not None:
        _project_constant(state, constant, lu)
    out: list[SpeedModes | Exception] = []
    worst = 0.0
    for i, speed in enumerate(grid):
        try:
            if i in first_modes:
                modes = first_modes[i]
            else:
                modes = _solve_speed(state, at(float(speed)), float(speed), i, n_wanted,
                                     sample_wanted, shift, lu, tol, sparse, stats,
                                     speed_dependent)
            modes = SpeedModes(modes.values[:n_wanted], modes.vectors[:, :n_wanted],
                               modes.residuals[:n_wanted])
            worst = max(worst, float(modes.residuals.max(initial=0.0)))
            out.append(modes)
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            out.append(exc)
    info = {"basis_size": float(sum(b.V.shape[1] for b in state.blocks)),
            "blocks": float(len(state.blocks)), "refinements": float(state.refinements),
            "full_solves": float(len(state.samples)),
            "projected_solves": float(state.projected_solves), "max_residual": worst}
    return out, info


def uncoupled_blocks(system: RotorSystem) -> list[IntArray]:
    """Free-DOF index sets that no entry of ``M, C, G, K`` couples (at any speed: every entry
    of a speed-dependent bearing counts as coupling), largest first."""
    from scipy.sparse.csgraph import connected_components

    pattern = system.pattern
    weight = sum(np.abs(v) for v in system.constant.values())
    weight = np.asarray(weight, dtype=float).copy()
    for group, _ in system.variable_bearings:
        pos = pattern.positions[group]
        weight[pos[pos >= 0]] = 1.0
    graph = sp.csr_matrix((weight, pattern.indices, pattern.indptr), shape=(pattern.n,) * 2)
    graph.eliminate_zeros()
    count, labels = connected_components(graph, directed=False)
    blocks = [np.flatnonzero(labels == k) for k in range(count)]
    return sorted(blocks, key=lambda b: -b.size)


def _sample(state: _State, i: int, mats: SystemMatrices, speed: float, wanted: int,
            shift: float, sparse: bool | None, stats: Stats, svd: bool = False) -> SpeedModes:
    """Full solve at speed index ``i``: its modes join the bases of the blocks."""
    values, vectors = _full_modes(mats, speed, wanted, shift, sparse, stats)
    X = vectors / np.linalg.norm(vectors, axis=0)
    for block in state.blocks:
        part = X[block.dofs]
        part = part[:, np.linalg.norm(part, axis=0) > 1e-12]
        if svd and part.size:
            U, s, _ = np.linalg.svd(np.hstack([block.V, part.real, part.imag]),
                                    full_matrices=False)
            block.V = U[:, s > SVD_TOL * s[0]]
            block.reduced, block.solved, block.pairs = {}, {}, None
            block.solved_stack = block.rigid_bound = None
            block.rigid_known = {}
        elif part.size:
            block.V = extend_basis(block.V, part)
    rigid, _ = _rigid(values, vectors, mats.M, mats.K, None)
    state.n_rigid = max(state.n_rigid, int(np.count_nonzero(rigid)))
    elastic = _elastic_indices(values, rigid)
    state.samples[i] = float(np.abs(values[elastic]).max()) if elastic.size >= wanted \
        else np.inf
    return SpeedModes(values[elastic], vectors[:, elastic], np.zeros(elastic.size))


def _full_modes(mats: SystemMatrices, speed: float, wanted: int, shift: float,
                sparse: bool | None, stats: Stats) -> tuple[ComplexArray, ComplexArray]:
    """Eigenpairs nearest ``shift`` up to ``wanted`` elastic ones (rigid ones included), found
    as :func:`~rotorsim.analyses.linear.modal.modal` finds them."""
    D = mats.C + speed * mats.G
    n = mats.M.shape[0]
    extra = 4
    while True:
        k = min(2 * wanted + extra, 2 * n)
        pairs = quadratic_eigen(mats.M, D, mats.K, k, sigma=shift, sparse=sparse, stats=stats)
        rigid, _ = _rigid(pairs.values, pairs.vectors, mats.M, mats.K, None)
        if _elastic_indices(pairs.values, rigid).size >= wanted or pairs.values.size < k \
                or k >= 2 * n:
            return pairs.values, pairs.vectors
        extra *= 2


def _project_constant(state: _State, mats: SystemMatrices, lu: Factorization) -> None:
    """Projected matrices and ``P^-1 A V`` of every block whose basis changed."""
    for block in state.blocks:
        if block.reduced and block.reduced["M"].shape[0] == block.V.shape[1]:
            continue
        _set_reduced(block, mats)
        block.solved = _solved(block, mats, lu)
        block.solved_stack = np.hstack([block.solved[key] for key in "MCGK"])


def _set_reduced(block: Block, mats: SystemMatrices) -> None:
    block.reduced = _projected(block, mats)
    block.pairs, block.rigid_bound, block.rigid_known = None, None, {}


def _projected(block: Block, mats: SystemMatrices) -> dict[str, FloatArray]:
    out = {}
    d, V = block.dofs, block.V
    for key in "MCGK":
        A = getattr(mats, key)[d][:, d]
        out[key] = np.asarray(V.T @ (A @ V))
    return out


def _solved(block: Block, mats: SystemMatrices, lu: Factorization) -> dict[str, FloatArray]:
    """``P^-1 A V`` restricted to the block's DOFs, for the basis columns not yet solved.

    ``P`` couples no two blocks (the blocks are what no matrix couples), so ``P^-1 A V`` is
    zero outside the block and a Ritz vector's residual ``P^-1 (lam^2 M + lam D + K) V y``
    is ``(P^-1 M V) y lam^2 + (P^-1 D V) y lam + (P^-1 K V) y`` on the block.
    """
    d, V = block.dofs, block.V
    done = block.solved["M"].shape[1] if block.solved else 0
    new = V[:, done:]
    c = new.shape[1]
    if c == 0:
        return block.solved
    rhs = np.zeros((mats.M.shape[0], 4 * c), order="F")
    for k, key in enumerate("MCGK"):
        rhs[d, k * c:(k + 1) * c] = getattr(mats, key)[d][:, d] @ new
    solution = np.asarray(lu.solve(rhs))[d]
    return {key: np.hstack([block.solved[key], solution[:, k * c:(k + 1) * c]])
            if block.solved else solution[:, k * c:(k + 1) * c]
            for k, key in enumerate("MCGK")}


def _solve_speed(state: _State, mats: SystemMatrices, speed: float, i: int, n_wanted: int,
                 sample_wanted: int, shift: float, lu: Factorization, tol: float,
                 sparse: bool | None, stats: Stats, speed_dependent: bool) -> SpeedModes:
    D = mats.C + speed * mats.G
    for _ in range(MAX_REFINEMENTS + 1):
        if speed_dependent:
            for block in state.blocks:
                _set_reduced(block, mats)
        else:
            _project_constant(state, mats, lu)
        ritz = ritz_pairs(state.blocks, speed, n_wanted, shift, mats, state.abs_k, state.n_rigid,
                     rigid_test=speed_dependent or state.n_rigid > 0)
        values, X = ritz.values, ritz.vectors
        state.projected_solves += 1
        if values.size < n_wanted or np.abs(values).max() > _reach(state.samples, i):
            break  # modes above those the basis is known to hold: solve in full
        if speed_dependent:
            res, Z = shift_inverted_residuals(lu, mats.M, D, mats.K, values, X)
        else:
            res, Z = _reduced_residuals(state.blocks, ritz, speed)
        stats.residual_evaluations += 1
        if np.all(res <= tol):
            return SpeedModes(values, X, res)
        state.refinements += 1
        bad = Z[:, res > tol]
        for block in state.blocks:
            part = bad[block.dofs]
            part = part[:, np.linalg.norm(part, axis=0) > 0]
            if part.size:
                block.V = extend_basis(block.V, part)
    return _sample(state, i, mats, speed, sample_wanted, shift, sparse, stats)


def _reduced_residuals(blocks: list[Block], ritz: RitzPairs, speed: float
                       ) -> tuple[FloatArray, ComplexArray]:
    """:func:`~rotorsim.solvers.projected_eigen.shift_inverted_residuals` of the Ritz pairs
    from each block's ``P^-1 A V`` (constant matrices): the same numbers, from dense
    products of the basis size instead of sparse products and a solve of the model's."""
    Z = np.zeros(ritz.vectors.shape, dtype=complex)
    for k in np.unique(ritz.block):
        mine = np.flatnonzero(ritz.block == k)
        Y, lam = ritz.coordinates[k], ritz.values[mine]
        stacked = np.vstack([Y * lam**2, Y * lam, speed * (Y * lam), Y])
        S = blocks[k].solved_stack
        Z[np.ix_(blocks[k].dofs, mine)] = S @ stacked.real + 1j * (S @ stacked.imag)
    return np.linalg.norm(Z, axis=0) / np.linalg.norm(ritz.vectors, axis=0), Z


def _reach(samples: dict[int, float], i: int) -> float:
    """|lam| up to which the nearest samples on either side of speed index ``i`` hold all
    modes."""
    below = [j for j in samples if j <= i]
    above = [j for j in samples if j >= i]
    near = ([samples[max(below)]] if below else []) + ([samples[min(above)]] if above else [])
    return min(near) if near else np.inf
