"""The quasi-periodic harmonic-balance residual, condensed exactly onto the nonlinear DOFs.

The equation of motion (rotor-agnostic, as :class:`~rotorsim.harmonic_balance.problem.
HBProblem`, DESIGN section 1):

    M q'' + (C + W G) q' + K q + f(q_N, q_N', theta) = p(theta),
    theta = (w1 t, w2 t) + theta_0,      W = spin + spin_ratio w1,

where the nonlinear force ``f`` acts on the DOFs ``N`` and may depend on the torus angles
(a rolling-element bearing's cage angle is ``theta2 / N_b`` when ``w2`` is its
varying-compliance frequency), and ``p`` holds combination tones of the two frequencies.

For a tone of frequency ``Omega_j = k_j . (w1, w2)`` with complex amplitude
``X_j = c_j - i s_j``, the linear part is the dynamic stiffness
``Z(Omega) = K - Omega^2 M + i Omega (C + W G)``. Eliminating the linear DOFs ``L``
tone by tone (as :mod:`rotorsim.harmonic_balance.condensation` does for one frequency)
leaves, on ``N``,

    S_j X_N,j + F_nl,j - (F_N,j - Z_NL Z_LL^-1 F_L,j) = 0,
    S_j = Z_NN - Z_NL Z_LL^-1 Z_LN,

which has exactly the solution of the full system. The nonlinear coefficients come from
the 2-D AFT (:class:`~rotorsim.harmonic_balance.quasi.aft.TorusAFT`) with its exact
Jacobian.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.banded_tones import BandedTones
from rotorsim.harmonic_balance.quasi.aft import TorusAFT
from rotorsim.solvers.linear import factorize

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
IntArray = NDArray[np.int64]

TorusForce = Callable[[FloatArray, FloatArray, FloatArray, FloatArray],
                      tuple[FloatArray, FloatArray, FloatArray | None]]
"""``force(q (S, d), v (S, d), theta1 (S,), theta2 (S,)) -> (f (S, d), df/dq (S, d, d),
df/dv (S, d, d) or None)`` on the nonlinear DOFs, batched over ``S`` torus samples."""


@dataclass(frozen=True, eq=False)
class QuasiProblem:
    """Matrices, nonlinear force and forcing of a quasi-periodic problem.

    Parameters
    ----------
    M, C, K : dense or sparse (n, n)
        Mass [kg], damping [N s/m] and stiffness [N/m].
    G : dense or sparse (n, n) or None
        Gyroscopic matrix per unit spin [N s/m per rad/s].
    nl_dofs : int array (d,)
        DOFs the nonlinear force acts on (sorted, distinct).
    force : TorusForce or None
    excitation : array (rows, n)
        Coefficients of ``p(theta)`` in the layout of the harmonic set used.
    spin, spin_ratio : float
        ``W = spin + spin_ratio w1`` [rad/s].
    """

    M: Any
    C: Any
    K: Any
    G: Any = None
    nl_dofs: IntArray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    force: TorusForce | None = None
    excitation: FloatArray | None = None
    spin: float = 0.0
    spin_ratio: float = 0.0

    @property
    def n(self) -> int:
        return int(self.M.shape[0])

    def damping(self, w1: float) -> Any:
        """``C + W G`` at ``W = spin + spin_ratio w1``."""
        if self.G is None:
            return self.C
        return self.C + (self.spin + self.spin_ratio * w1) * self.G


@dataclass(eq=False)
class CondensedTones:
    """Per-tone Schur complements ``S (rows, d, d)`` (complex; the mean's is real), loads on
    ``N`` and the factors needed to recover the linear DOFs."""

    frequencies: FloatArray
    S: ComplexArray
    load: ComplexArray
    linear: list[ComplexArray]
    """Per tone ``[Z_LL^-1 Z_LN, Z_LL^-1 F_L]`` (``(n_L, d + 1)``): ``X_L = Z_LL^-1 F_L -
    Z_LL^-1 Z_LN X_N``."""
    factors: list[Any] = field(default_factory=list)
    """Per tone the LU factors of ``Z_LL`` (empty without linear DOFs)."""


DENSE_LINEAR = 600
"""Linear parts up to this many DOFs are condensed with dense blocks and dense LU."""


@dataclass(frozen=True, eq=False)
class LinearBlocks:
    """``M, C, G, K`` split once into the blocks of the nonlinear DOFs ``N`` and the linear
    DOFs ``L``: ``NN``, ``NL``, ``LN`` dense and ``LL`` dense (up to
    :data:`DENSE_LINEAR` DOFs) or sparse. Forming ``Z = K - w^2 M + i w (C + s G)`` tone
    by tone from them avoids re-indexing sparse matrices at every tone and speed."""

    N: IntArray
    L: IntArray
    blocks: dict[str, tuple[Any, Any, Any, Any]]
    dense: bool
    band: BandedTones | None = None
    """The ``LL`` blocks in band storage when their band is narrow: the damped tones'
    ``Z_LL`` are then factorised banded (:mod:`~rotorsim.harmonic_balance.banded_tones`)."""

    @classmethod
    def of(cls, problem: QuasiProblem) -> LinearBlocks:
        N = np.asarray(problem.nl_dofs, dtype=np.int64)
        L = np.setdiff1d(np.arange(problem.n), N)
        dense = problem.n <= DENSE_LINEAR
        out = {}
        for name in ("M", "C", "G", "K"):
            A = getattr(problem, name)
            A = sp.csr_matrix((problem.n, problem.n)) if A is None else sp.csr_matrix(A)
            rows_N, rows_L = A[N], A[L]
            LL = rows_L[:, L]
            out[name] = (rows_N[:, N].toarray(), rows_N[:, L].toarray(),
                         rows_L[:, N].toarray(), LL.toarray() if dense else LL.tocsc())
        band = BandedTones.of({name: out[name][3] for name in out}) if L.size else None
        return cls(N, L, out, dense, band)

    def block(self, name: str, b: int) -> Any:
        """Block ``b`` (0 NN, 1 NL, 2 LN, 3 LL) of matrix ``name`` (zero when the problem
        has none)."""
        return self.blocks[name][b]

    def damping(self, s: float) -> tuple[Any, Any, Any, Any]:
        """The four blocks of ``D = C + s G`` at the spin ``s`` [rad/s] (formed once per
        speed; every tone uses them)."""
        return tuple(self.block("C", b) + s * self.block("G", b) for b in range(4))

    def z(self, w: float, s: float, damping: tuple[Any, ...] | None = None,
          which: tuple[int, ...] = (0, 1, 2, 3)) -> tuple[Any, ...]:
        """Blocks ``which`` of ``Z = K - w^2 M + i w D`` (0 ``Z_NN``, 1 ``Z_NL``, 2 ``Z_LN``,
        3 ``Z_LL``) at the frequency ``w`` [rad/s] and spin ``s`` (``damping``: the blocks
        of ``D`` at ``s``, from :meth:`damping`)."""
        D = self.damping(s) if damping is None else damping
        out = []
        for b in which:
            real = self.block("K", b) - (w * w) * self.block("M", b)
            if sp.issparse(real) or sp.issparse(D[b]):
                out.append(sp.csc_matrix(real + (1j * w) * D[b]))
                continue
            Z = np.empty(np.shape(real), dtype=complex)
            Z.real = real
            Z.imag = w * D[b]
            out.append(Z)
        return tuple(out)


def condense(problem: QuasiProblem, aft: TorusAFT, w1: float, w2: float,
             blocks: LinearBlocks | None = None) -> CondensedTones:
    """Schur complements and condensed loads of every tone at ``(w1, w2)`` (``blocks``:
    :class:`LinearBlocks` of ``problem``'s matrices, formed here when not given)."""
    lb = LinearBlocks.of(problem) if blocks is None else blocks
    N, L = lb.N, lb.L
    omega = np.concatenate([[0.0], aft.harmonics.frequencies(w1, w2)])
    F = _complex_excitation(problem, aft)
    spin = problem.spin + problem.spin_ratio * w1
    D = lb.damping(spin)
    damped = _damped(lb.block("C", 3))
    S = np.empty((omega.size, N.size, N.size), dtype=complex)
    load = np.empty((omega.size, N.size), dtype=complex)
    linear, factors = [], []
    for j, w in enumerate(omega):
        where = f"quasi-periodic HB, linear DOFs at tone {j} (Omega = {w:.6g} rad/s)"
        if lb.band is not None and j > 0 and damped:     # regular by construction
            ZNN, ZNL, ZLN = lb.z(float(w), spin, D, which=(0, 1, 2))
            lu: Any = lb.band.factorize(float(w), spin, where)
        else:
            ZNN, ZNL, ZLN, ZLL = lb.z(float(w), spin, D)
            if L.size == 0:
                S[j], load[j] = ZNN, F[j, N]
                linear.append(np.zeros((0, N.size + 1), dtype=complex))
                continue
            lu = factorize(ZLL, where=where, dense_threshold=DENSE_LINEAR,
                           check_condition=j == 0 or not damped)
        Y = lu.solve(np.column_stack([ZLN, F[j, L]]))
        S[j] = ZNN - ZNL @ Y[:, :-1]
        load[j] = F[j, N] - ZNL @ Y[:, -1]
        linear.append(Y)
        factors.append(lu)
    return CondensedTones(omega, S, load, linear, factors)


def _damped(C_LL: Any) -> bool:
    """The linear DOFs carry damping. ``Z_LL`` of a tone other than the mean is then
    singular only where an undamped fixed-interface mode sits exactly on the tone (a
    measure-zero event along a branch), so its LU checks only for a zero or non-finite
    pivot and skips the condition estimate (half its cost); the mean's ``K_LL``, or an
    undamped ``Z_LL`` (gyroscopic terms alone), keep the estimate."""
    return bool(C_LL.nnz if sp.issparse(C_LL) else np.any(C_LL != 0))


def speed_derivative(blocks: LinearBlocks, tones: CondensedTones, orders: FloatArray,
                     speed: float, Y: FloatArray, dF: ComplexArray) -> FloatArray:
    """``d/dW`` of the condensed linear residual at fixed ``Y (rows, d)`` when every tone
    turns with the spin, ``Omega_j = c_j W`` (``orders`` ``c_j (T + 1,)``, the mean's 0),
    the spin is ``W`` and ``M, C, G, K`` do not depend on it; ``dF (T + 1, n)`` is the
    derivative of the complex excitation. With ``dZ_j = -2 Omega_j c_j M + i c_j (C + W
    G) + i Omega_j G`` and ``g = dZ_j X_j - dF_j`` on all DOFs (``X_L`` recovered), the
    condensed derivative is ``g_N - Z_NL Z_LL^-1 g_L`` (the Schur complement's chain
    rule)."""
    N, L = blocks.N, blocks.L
    Zc = np.concatenate([Y[:1].astype(complex), Y[1::2] - 1j * Y[2::2]])
    out = np.zeros(Zc.shape, dtype=complex)
    D = blocks.damping(speed)
    M = [blocks.block("M", k) for k in range(4)]
    G = [blocks.block("G", k) for k in range(4)]
    for j in range(Zc.shape[0]):
        c, w = float(orders[j]), float(orders[j]) * speed
        # dZ = -2 w c M + i (c D + w G), applied block by block to (X_N, X_L)
        XN = Zc[j]
        XL = tones.linear[j][:, -1] - tones.linear[j][:, :-1] @ XN
        g = [M[k] @ X * (-2.0 * w * c) + 1j * (c * (D[k] @ X) + w * (G[k] @ X))
             for k, X in ((0, XN), (1, XL), (2, XN), (3, XL))]
        gN = g[0] + g[1] - dF[j, N]
        if L.size == 0:        # every DOF nonlinear (a rigid rotor): nothing condensed
            out[j] = gN
            continue
        gL = g[2] + g[3] - dF[j, L]
        (ZNL,) = blocks.z(w, speed, D, which=(1,))
        out[j] = gN - ZNL @ tones.factors[j].solve(gL)
    R = np.empty(Y.shape)
    R[0] = out[0].real
    R[1::2], R[2::2] = out[1:].real, -out[1:].imag
    return R


def residual(problem: QuasiProblem, aft: TorusAFT, tones: CondensedTones, w1: float,
             w2: float, Y: FloatArray, jacobian: bool = True
             ) -> tuple[FloatArray, FloatArray | None]:
    """Condensed residual ``(rows d,)`` and its Jacobian at nonlinear coefficients
    ``Y (rows, d)`` (ordering harmonic-major, as :meth:`TorusAFT.jacobian`; None with
    ``jacobian=False``)."""
    rows, d = Y.shape
    Zc = np.concatenate([Y[:1].astype(complex), Y[1::2] - 1j * Y[2::2]])
    lin = np.einsum("jab,jb->ja", tones.S, Zc) - tones.load
    R = np.empty((rows, d))
    R[0] = lin[0].real
    R[1::2] = lin[1:].real
    R[2::2] = -lin[1:].imag
    if not jacobian:
        if problem.force is not None:
            q = aft.to_samples(Y)
            v = aft.to_samples(aft.derivative_matrix(w1, w2) @ Y)
            f, _, _ = problem.force(q, v, *aft.angles)
            R += aft.to_coefficients(f)
        return R.ravel(), None
    blocks = np.zeros((rows, d, rows, d))
    blocks[0, :, 0, :] = tones.S[0].real
    j = np.arange(1, rows // 2 + 1)
    Sr, Si = tones.S[1:].real, tones.S[1:].imag
    blocks[2 * j - 1, :, 2 * j - 1, :] = Sr
    blocks[2 * j - 1, :, 2 * j, :] = Si
    blocks[2 * j, :, 2 * j - 1, :] = -Si
    blocks[2 * j, :, 2 * j, :] = Sr
    J = blocks.reshape(rows * d, rows * d)
    if problem.force is not None:
        q = aft.to_samples(Y)
        Dm = aft.derivative_matrix(w1, w2)
        v = aft.to_samples(Dm @ Y)
        theta1, theta2 = aft.angles
        f, dfdq, dfdv = problem.force(q, v, theta1, theta2)
        R += aft.to_coefficients(f)
        J += aft.jacobian(dfdq)
        if dfdv is not None:
            J += times_derivative(aft.jacobian(dfdv), Dm, d)
    return R.ravel(), J


def times_derivative(Jv: FloatArray, Dm: FloatArray, d: int) -> FloatArray:
    """``Jv @ kron(Dm, I_d)`` (the chain rule through the velocity coefficients ``Dm Y``)
    without the dense product: ``Dm`` has one entry per column (a tone's cosine and sine
    exchanged), so each column block of the result is one column block of ``Jv`` scaled.
    Exact: the same products, none of the zeros."""
    P, rows = Jv.shape[0], Dm.shape[0]
    blocks = Jv.reshape(P, rows, d).transpose(1, 0, 2).reshape(rows, P * d)
    out = sp.csr_matrix(Dm.T) @ blocks                      # (rows, P d)
    return np.ascontiguousarray(out.reshape(rows, P, d).transpose(1, 0, 2).reshape(P, rows * d))


def full_coefficients(problem: QuasiProblem, tones: CondensedTones, Y: FloatArray
                      ) -> FloatArray:
    """Coefficients ``(rows, n)`` of all DOFs from those of the nonlinear DOFs."""
    rows = Y.shape[0]
    N = np.asarray(problem.nl_dofs, dtype=np.int64)
    L = np.setdiff1d(np.arange(problem.n), N)
    out = np.zeros((rows, problem.n))
    out[:, N] = Y
    Zc = np.concatenate([Y[:1].astype(complex), Y[1::2] - 1j * Y[2::2]])
    for j in range(Zc.shape[0]):
        XL = tones.linear[j][:, -1] - tones.linear[j][:, :-1] @ Zc[j]
        if j == 0:
            out[0, L] = XL.real
        else:
            out[2 * j - 1, L] = XL.real
            out[2 * j, L] = -XL.imag
    return out


def _complex_excitation(problem: QuasiProblem, aft: TorusAFT) -> ComplexArray:
    rows = aft.harmonics.rows
    P = np.zeros((rows, problem.n)) if problem.excitation is None else np.asarray(
        problem.excitation, dtype=float)
    if P.shape != (rows, problem.n):
        raise ModelError(f"excitation has shape {P.shape}, expected {(rows, problem.n)} "
                         "(rows of the harmonic set, DOFs)", "QuasiProblem.excitation")
    return np.concatenate([P[:1].astype(complex), P[1::2] - 1j * P[2::2]])
