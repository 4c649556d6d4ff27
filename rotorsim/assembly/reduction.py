"""Craig-Bampton reduction of the linear part, keeping the nonlinear DOFs physical.

A rotor on rolling bearings is linear everywhere but at the bearing DOFs ``b``. With the
other (interior) DOFs ``i``, the Craig-Bampton basis

    q = T [q_b; eta; s],   T = [[I, 0, 0], [Psi, Phi, S]],

keeps the boundary DOFs ``q_b`` as unknowns (so the bearings see physical displacements),
represents the interior by the static constraint modes ``Psi = -K_ii^-1 K_ib`` (the interior
following a unit motion of one boundary DOF), the lowest ``num_modes`` fixed-interface normal
modes ``Phi`` (``K_ii phi = w^2 M_ii phi``, boundary held) and, optionally, the interior
static responses ``S = K_ii^-1 f_i`` to given load shapes (gravity, unbalance), which make
the static deflection under those loads exact. The reduced matrices are ``T^T A T``.

Accuracy is reported, not assumed: :func:`accuracy` compares the lowest natural frequencies
of the full and the reduced system with the boundary supported by a given stiffness (e.g.
the bearings' nominal tangent).

Reference: R. R. Craig, M. C. C. Bampton, AIAA J. 6 (1968) 1313-1319.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from numpy.typing import ArrayLike, NDArray

from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import factorize

IntArray = NDArray[np.int64]
DENSE_EIGEN = 400
"""Interior sizes up to this use a dense symmetric eigensolver."""


@dataclass(frozen=True, eq=False)
class ReducedBasis:
    """A Craig-Bampton basis (module docstring).

    Attributes
    ----------
    T : array (n, m)
        Basis on the free DOFs: ``q = T x``; the first ``boundary.size`` entries of ``x``
        are the boundary DOFs themselves.
    boundary : int array (b,)
        Free DOFs kept physical, in the order of ``x``.
    frequencies : array (num_modes,)
        Natural frequencies of the fixed-interface modes [rad/s].
    n_static : int
        Number of static load vectors in the basis.
    """

    T: FloatArray
    boundary: IntArray
    frequencies: FloatArray
    n_static: int

    @property
    def size(self) -> int:
        """Number of reduced unknowns ``m``."""
        return int(self.T.shape[1])

    def reduce(self, A: sp.spmatrix | FloatArray) -> FloatArray:
        """``T^T A T`` (dense, m x m)."""
        return np.asarray(self.T.T @ (A @ self.T))

    def project(self, q: ArrayLike) -> FloatArray:
        """Least-squares reduced coordinates of free-DOF vectors ``q`` (n,) or (n, k)
        (LAPACK's complete orthogonal factorisation, ``gelsy``: a third of the SVD's cost
        at 126 x 32, the same minimum-norm solution)."""
        return np.asarray(sl.lstsq(self.T, np.asarray(q, dtype=float), lapack_driver="gelsy",
                                   check_finite=False)[0])


def craig_bampton(system: RotorSystem, boundary: ArrayLike, num_modes: int, *,
                  static_loads: Sequence[ArrayLike] = (), speed: float = 0.0,
                  modes: tuple[FloatArray, FloatArray] | None = None,
                  interior: tuple[Any, Any, Any] | None = None,
                  parts: ConstraintParts | None = None) -> ReducedBasis:
    """Build the Craig-Bampton basis of ``system`` (module docstring).

    Parameters
    ----------
    system : RotorSystem
        The assembled model (its linear matrices at ``speed``).
    boundary : sequence of int
        Free DOFs kept physical (the nonlinear elements' DOFs, ``system.nonlinear.dofs``).
    num_modes : int
        Number of fixed-interface normal modes (>= 0); raised to keep the last cluster of
        equal frequencies whole (:func:`fixed_interface_modes`).
    static_loads : sequence of arrays (n_free,)
        Load shapes whose interior static response is added to the basis.
    speed : float
        Speed at which speed-dependent linear bearings are evaluated [rad/s].
    modes : (frequencies, shapes), optional
        The fixed-interface modes, already computed by :func:`fixed_interface_modes` on
        this boundary (``num_modes`` is then ignored).
    interior : (K_ii, M_ii, factorisation of K_ii), optional
        The interior blocks of the matrices at ``speed`` on this boundary and the LU of
        ``K_ii`` (:func:`~rotorsim.solvers.linear.factorize`), already computed by the
        caller: not extracted and factorised again.
    parts : ConstraintParts, optional
        The constraint modes and interior static responses of this boundary, loads and
        speed (:func:`constraint_parts`), shared by bases of several mode counts
        (``static_loads`` and ``interior`` are then not used).

    Raises
    ------
    ModelError
        Bad boundary or mode count, or an interior that moves freely with the boundary held
        (add its DOFs to the boundary).
    """
    if parts is None:
        parts = constraint_parts(system, boundary, static_loads=static_loads, speed=speed,
                                 interior=interior)
    b, inner = parts.boundary, parts.inner
    if not 0 <= int(num_modes) <= inner.size:
        raise ModelError(f"num_modes must lie in 0..{inner.size} (interior DOFs), got {num_modes}",
                         "craig_bampton")
    freqs, phi = fixed_interface_modes(parts.K_ii, parts.M_ii, int(num_modes)) \
        if modes is None else modes
    statics = _independent(list(parts.statics), phi, parts.M_ii)
    T = np.zeros((system.n_free, b.size + phi.shape[1] + statics.shape[1]))
    T[b, np.arange(b.size)] = 1.0
    T[inner] = np.hstack([parts.psi, phi, statics])
    return ReducedBasis(T, b, freqs, int(statics.shape[1]))


@dataclass(frozen=True, eq=False)
class ConstraintParts:
    """What every Craig-Bampton basis of one boundary shares whatever its mode count: the
    boundary and interior DOFs, the interior blocks ``K_ii``, ``M_ii``, the constraint
    modes ``Psi`` (n_i, b) and the interior static responses to the load shapes."""

    boundary: IntArray
    inner: IntArray
    K_ii: Any
    M_ii: Any
    psi: FloatArray
    statics: tuple[FloatArray, ...]


def constraint_parts(system: RotorSystem, boundary: ArrayLike, *,
                     static_loads: Sequence[ArrayLike] = (), speed: float = 0.0,
                     interior: tuple[Any, Any, Any] | None = None,
                     stiffness: Any = None) -> ConstraintParts:
    """The shared parts of :func:`craig_bampton` (same arguments), computed once;
    ``stiffness``: the system's stiffness at ``speed`` (n_free, n_free) when the caller
    holds it, dense or sparse (with ``interior``, nothing is then taken from ``system``'s
    matrices again).

    Raises
    ------
    ModelError
        Bad boundary, or an interior that moves freely with the boundary held.
    """
    n = system.n_free
    b = np.unique(np.asarray(boundary, dtype=np.int64))
    if b.size == 0 or b.min() < 0 or b.max() >= n:
        raise ModelError(f"boundary DOFs must be free-DOF indices in 0..{n - 1}",
                         "craig_bampton")
    inner = np.setdiff1d(np.arange(n), b)
    mats = None if stiffness is not None and interior is not None else system.matrices(speed)
    K = mats.K if mats is not None and stiffness is None else stiffness
    K_i: Any = sp.csr_matrix(K)[inner] if sp.issparse(K) else np.asarray(K)[inner]
    K_ib = K_i[:, b].toarray() if sp.issparse(K_i) else K_i[:, b]
    if interior is not None:
        K_ii, M_ii, lu = interior
    else:
        assert mats is not None
        K_ii, M_ii = sp.csr_matrix(K_i[:, inner]), sp.csr_matrix(mats.M)[inner][:, inner]
        try:
            lu = factorize(K_ii, where="craig_bampton: interior stiffness")
        except ConvergenceError:
            raise ModelError("the interior is not held by the boundary (K_ii is singular): "
                             "a part of the rotor moves freely when the bearing DOFs are "
                             "held; add DOFs of that part to the boundary",
                             "craig_bampton") from None
    psi = -np.asarray(lu.solve(K_ib)).reshape(inner.size, b.size)
    statics = tuple(np.asarray(lu.solve(np.asarray(f, dtype=float)[inner])).reshape(-1)
                    for f in static_loads)
    return ConstraintParts(b, inner, K_ii, M_ii, psi, statics)


CLUSTER_RTOL = 1e-6
"""Modes whose natural frequencies differ by less than this (relative) form one cluster."""


def fixed_interface_modes(K_ii: sp.spmatrix, M_ii: sp.spmatrix, k: int
                          ) -> tuple[FloatArray, FloatArray]:
    """Lowest ``k`` modes of ``K_ii phi = w^2 M_ii phi``, mass-normalised, with the last
    cluster of (near-)equal frequencies kept whole.

    An axisymmetric rotor has pairs of modes of equal frequency (x and y bending). Cutting
    inside such a pair would keep an arbitrary direction of its eigenspace, which differs
    between LAPACK builds and makes the reduced model depend on the machine. The count is
    therefore raised until the next mode is more than :data:`CLUSTER_RTOL` above the last
    one kept (or all modes are kept).

    Returns
    -------
    frequencies : array (m,)
        Natural frequencies [rad/s], ascending, ``m >= k``.
    modes : array (n_i, m)
        Mass-normalised mode shapes.
    """
    n = K_ii.shape[0]
    if k == 0:
        return np.zeros(0), np.zeros((n, 0))
    want = min(k + 2, n)
    while True:
        lam, vec = _lowest_modes(K_ii, M_ii, want)
        w = np.sqrt(np.maximum(lam, 0.0))
        last = w[k - 1]
        keep = k + int(np.count_nonzero(w[k:] <= last * (1.0 + CLUSTER_RTOL) + 1e-12))
        if keep < want or want == n:
            return w[:keep], vec[:, :keep]
        want = min(2 * want, n)


def _lowest_modes(K_ii: sp.spmatrix, M_ii: sp.spmatrix, k: int
                  ) -> tuple[FloatArray, FloatArray]:
    """Lowest ``k`` eigenpairs ``(w^2, phi)``, ascending (dense LAPACK or shift-invert)."""
    if K_ii.shape[0] <= DENSE_EIGEN or k >= K_ii.shape[0] - 1:
        return sl.eigh(sp.csr_matrix(K_ii).toarray(), sp.csr_matrix(M_ii).toarray(),
                       subset_by_index=(0, k - 1))
    K, M, n = sp.csc_matrix(K_ii), sp.csc_matrix(M_ii), K_ii.shape[0]
    try:
        lam, vec = spl.eigsh(K, k=k, M=M, sigma=0.0, which="LM", v0=np.ones(n))
    except spl.ArpackError:
        # "no shifts could be applied" (error 3) with repeated eigenvalues under some BLAS
        # kernels (measured: OPENBLAS_CORETYPE=Sandybridge): more Lanczos vectors
        lam, vec = spl.eigsh(K, k=k, M=M, sigma=0.0, which="LM", v0=np.ones(n),
                             ncv=min(n - 1, max(4 * k + 1, 40)))
    order = np.argsort(lam)
    return _complete(K_ii, M_ii, lam[order], vec[:, order])


SUBSPACE_ITERATIONS = 60
"""Most block shift-invert iterations of the completeness check of :func:`_complete`."""
CHECK_ITERATIONS = 4
"""Iterations after which the check stops when no Ritz value lies below ARPACK's highest
eigenvalue (a missed eigenvalue below it shows up within a few iterations: its Ritz value
converges at the ratio of it to the eigenvalues outside the block, squared)."""


def _complete(K_ii: sp.spmatrix, M_ii: sp.spmatrix, lam: FloatArray, vec: FloatArray
              ) -> tuple[FloatArray, FloatArray]:
    """ARPACK's ``k`` lowest eigenpairs, checked for missed copies of repeated eigenvalues.

    Lanczos from one start vector can miss copies of an eigenvalue of multiplicity above
    two (a rotor of equal spans between several bearings has them; with the symmetric start
    vector of ones it finds one direction per symmetric pattern). A block shift-invert
    subspace iteration (Bathe, *Finite Element Procedures*, section 11.6) from ARPACK's
    vectors plus ``k`` deterministic pseudo-random ones reveals them: when its ``k`` lowest
    Ritz values agree with ARPACK's, ARPACK's pairs are returned unchanged; otherwise the
    converged Ritz pairs are.
    """
    k, n = lam.size, K_ii.shape[0]
    p = min(2 * k, n)
    lu = factorize(sp.csc_matrix(K_ii), where="craig_bampton: subspace iteration")
    rng = np.random.default_rng(0)
    X = np.hstack([vec, rng.standard_normal((n, p - k))])
    ritz = lam
    for i in range(SUBSPACE_ITERATIONS):
        Y = np.asarray(lu.solve(M_ii @ X)).reshape(n, p)
        Kr, Mr = Y.T @ (K_ii @ Y), Y.T @ (M_ii @ Y)
        new, Q = sl.eigh((Kr + Kr.T) / 2, (Mr + Mr.T) / 2)
        X = Y @ Q
        done = np.allclose(new[:k], ritz[:k], rtol=1e-10, atol=0.0)
        ritz = new
        if done or (i + 1 >= CHECK_ITERATIONS and ritz[k - 1] >= lam[-1] * (1.0 - 1e-8)):
            break  # converged, or no Ritz value has come below ARPACK's highest
    if np.allclose(ritz[:k], lam, rtol=1e-8, atol=0.0):
        return lam, vec
    return ritz[:k], X[:, :k]


def _independent(vectors: list[FloatArray], phi: FloatArray, M: sp.csr_matrix) -> FloatArray:
    """``vectors`` M-orthogonalised against ``phi`` and each other; dependent ones dropped.

    The projection on the modes is one block product per pass (``phi`` and ``M phi``
    formed once), taken twice: classical Gram-Schmidt repeated once is as accurate as the
    modified one (Giraud, Langou, Rozloznik, Comput. Math. Appl. 50 (2005) 1069, "twice is
    enough"), at two matrix products instead of two sparse products per mode and vector.
    """
    Mphi = np.asarray(M @ phi).reshape(phi.shape)
    d = np.einsum("ij,ij->j", phi, Mphi)  # u^T M u of each mode
    out: list[FloatArray] = []
    for v in vectors:
        w = np.array(v, dtype=float)
        for _ in range(2):
            if phi.shape[1]:
                w -= phi @ ((Mphi.T @ w) / d)
            for u in out:
                w -= (u @ (M @ w)) / (u @ (M @ u)) * u
        norm = float(np.sqrt(max(w @ (M @ w), 0.0)))
        if norm > 1e-8 * float(np.sqrt(max(v @ (M @ v), 1e-300))):
            w /= norm
            out.append(w)
    return np.column_stack(out) if out else np.zeros((M.shape[0], 0))


def accuracy(system: RotorSystem, basis: ReducedBasis, support: sp.spmatrix,
             n_check: int = 6, speed: float = 0.0) -> dict[str, object]:
    """Lowest natural frequencies of the full and reduced undamped systems with the
    boundary supported by ``support`` (n_free x n_free, e.g. the bearings' nominal
    tangent) and their largest relative difference over the ``n_check`` lowest elastic
    modes (rigid-body modes, below 1e-4 of the highest frequency computed, are skipped:
    both systems have them exactly)."""
    mats = system.matrices(speed)
    K = sp.csr_matrix(mats.K) + sp.csr_matrix(support)
    M = sp.csr_matrix(mats.M)
    Kr, Mr = basis.reduce(K), basis.reduce(M)
    k = min(n_check + 6, basis.size - 1)
    reduced = np.sqrt(np.maximum(sl.eigh(Kr, Mr, eigvals_only=True,
                                         subset_by_index=(0, k - 1)), 0.0))
    if K.shape[0] <= DENSE_EIGEN:
        full = np.sqrt(np.maximum(sl.eigh(K.toarray(), M.toarray(), eigvals_only=True,
                                          subset_by_index=(0, k - 1)), 0.0))
    else:
        # shift below zero: a support without stiffness in some direction (ball bearings
        # with clearance) leaves rigid-body modes, and K itself singular
        lam = spl.eigsh(K.tocsc(), k=k, M=M.tocsc(), sigma=-1.0, which="LM",
                        return_eigenvectors=False, v0=np.ones(K.shape[0]))
        full = np.sqrt(np.maximum(np.sort(lam), 0.0))
    elastic = np.flatnonzero(full > 1e-4 * full.max())[:n_check]
    full, reduced = full[elastic], reduced[elastic]
    err = np.abs(reduced - full) / full
    return {"full": full, "reduced": reduced,
            "max_relative_error": float(err.max()) if err.size else 0.0,
            "reduced_size": basis.size, "full_size": int(K.shape[0])}
