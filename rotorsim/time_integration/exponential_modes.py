"""The exact linear part of an exponential collocation step: modes of the shifted linear
rotor and the weights of one step size (the stepper is :mod:`~.exponential`).

A rotor at constant speed with local nonlinear elements reads, in first-order form
``y = (q, v)``,

    y' = A y + [0; M^-1 (f(t) + P rho(P^T q, P^T v, t))],
    A = [[0, I], [-M^-1 (K + P K0 P^T), -M^-1 (D + P C0 P^T)]],
    rho = K0 q_b + C0 v_b - r(q_b, v_b, t),

with ``D = C + W G``, ``P`` the columns of the ``k`` nonlinear DOFs and ``K0``, ``C0`` the
tangents of the restoring force ``r`` at the start (the splitting is exact for any ``K0``,
``C0``; taking the tangents leaves only the nonlinear remainder in ``rho``). ``A`` is
diagonalised once, ``A = V diag(lambda) V^-1``, so for the modal coordinates
``z = V^-1 y`` the variation-of-constants formula over a step of size ``h`` is diagonal:

    z(t_n + x h) = e^{lambda x h} z_n + int_0^{x h} e^{lambda (x h - s)} b(t_n + s) ds.

The constant load and the unbalance ``Re(u e^{i W t})`` are integrated exactly
(``phi_1``); ``rho`` is replaced by its interpolation polynomial through the stage values,
whose integrals are the ``phi_k`` functions (Hochbruck & Ostermann 2010, section 2.3).

References
----------
M. Hochbruck, A. Ostermann, *Exponential integrators*, Acta Numerica 19 (2010) 209-286,
sections 2.1-2.3 (variation of constants, the ``phi_k`` functions and their recurrence
``phi_{k+1}(z) = (phi_k(z) - 1/k!) / z``, exponential collocation).
"""

from __future__ import annotations

import cmath
import hashlib
import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import scipy.linalg as sl

from rotorsim.errors import ConvergenceError
from rotorsim.solvers.dense_groups import coupled_groups
from rotorsim.time_integration.base import FloatArray, IntArray
from rotorsim.time_integration.phi_functions import cexp as cexp
from rotorsim.time_integration.phi_functions import phi_functions as phi_functions

ComplexArray = np.ndarray
RECONSTRUCTION_LIMIT = 1e-8
"""Largest relative error of ``V (V^-1 x)`` accepted for the eigenbasis (an ill-conditioned
basis, e.g. a nearly defective eigenvalue, is refused)."""
RIGID_SHIFT = 1e-2
"""Stiffness added (and subtracted again in ``rho``) on nonlinear DOFs whose start tangent
is zero, as a fraction of the linear stiffness's diagonal there: it turns the rigid modes
of a rotor carried only by nonlinear elements (defective double zero eigenvalues) into
slow oscillations, which the eigenbasis can represent."""


class IllConditionedModes(ConvergenceError):
    """The eigenbasis of the linear part cannot represent it (a nearly defective
    eigenvalue); raised at the start of a run, before any step."""


_FACTORIALS = np.array([float(math.factorial(m)) for m in range(8)])
"""``m!`` for the monomial weights of :class:`StepWeights` (``stages <= 6``)."""


def lagrange_coefficients(nodes: FloatArray) -> FloatArray:
    """Monomial coefficients ``L[j, m]`` of the Lagrange basis ``l_j(x) = sum_m L[j, m]
    x^m`` through ``nodes`` (p,)."""
    p = nodes.size
    vander = np.vander(nodes, p, increasing=True)  # vander[i, m] = x_i^m
    return np.asarray(np.linalg.inv(vander).T)


def lobatto_nodes(s: int) -> FloatArray:
    """The ``s + 1`` Gauss-Lobatto nodes on [0, 1].

    Examples
    --------
    >>> [round(float(x), 6) for x in lobatto_nodes(2)]
    [0.0, 0.5, 1.0]
    """
    inner = np.polynomial.legendre.Legendre.basis(s).deriv().roots()
    return np.concatenate([[0.0], np.sort((inner.real + 1.0) / 2.0), [1.0]])


class HarmonicLoad:
    """``f(t) = constant + Re(amplitude e^{i frequency t})`` [N]: gravity, point loads and
    an unbalance at constant speed. Its ``repr`` is a digest of the numbers (it enters the
    identity of a run, :func:`~rotorsim.time_integration.integrate.run_config`).

    Examples
    --------
    >>> f = HarmonicLoad(np.zeros(2), np.array([1.0, -1j]), 10.0)
    >>> [round(float(x), 12) for x in f(0.0)]
    [1.0, 0.0]
    """

    __slots__ = ("amplitude", "constant", "frequency")

    def __init__(self, constant: FloatArray, amplitude: ComplexArray, frequency: float
                 ) -> None:
        self.constant = np.asarray(constant, dtype=float)
        self.amplitude = np.asarray(amplitude, dtype=complex)
        self.frequency = float(frequency)

    def __call__(self, t: float) -> FloatArray:
        return np.asarray(self.constant + (self.amplitude * cmath.exp(1j * self.frequency * t)
                                           ).real)

    def __repr__(self) -> str:
        h = hashlib.blake2b(digest_size=8)
        for x in (self.constant, self.amplitude, np.array([self.frequency])):
            h.update(x.tobytes())
        return f"HarmonicLoad({h.hexdigest()})"


@dataclass(frozen=True, eq=False)
class LinearModes:
    """The eigenbasis of the shifted linear rotor (module docstring) and the projections
    a step needs.

    Attributes
    ----------
    lam : complex array (N,)
        Kept eigenvalues of ``A`` [1/s] (the real ones and those with a positive
        imaginary part: ``N`` about ``n``).
    V : complex array (2 n, N)
        Their eigenvectors, doubled for the pairs (``y = Re(V z)``).
    blocks : tuple
        Per uncoupled DOF group, what gives ``z`` of a state (LU factors of its
        eigenvectors, the kept modes).
    dofs : int array (k,)
        Nonlinear DOFs.
    K0, C0 : arrays (k, k)
        The shift of the linear part on them.
    Bp : complex array (N, k)
        Modal load of a unit force on each nonlinear DOF, ``V^-1 [0; M^-1 P]``.
    b_const, b_plus, b_minus : complex arrays (N,)
        Modal loads of the constant load and of the two halves ``u/2 e^{iWt}``,
        ``conj(u)/2 e^{-iWt}`` of the harmonic one.
    frequency : float
        ``W`` of the harmonic load [rad/s].
    minv : array (n, n)
        ``M^-1``.
    """

    lam: ComplexArray
    V: ComplexArray
    blocks: tuple[Any, ...]
    dofs: IntArray
    K0: FloatArray
    C0: FloatArray
    Bp: ComplexArray
    b_const: ComplexArray
    b_plus: ComplexArray
    b_minus: ComplexArray
    frequency: float
    minv: FloatArray

    @property
    def n(self) -> int:
        return self.V.shape[0] // 2

    @cached_property
    def shifts(self) -> ComplexArray:
        """``lambda``, ``lambda - i W`` and ``lambda + i W`` (3, N): the arguments of the
        ``phi`` functions of the modes and of the two halves of the harmonic load."""
        return np.stack([self.lam, self.lam - 1j * self.frequency,
                         self.lam + 1j * self.frequency])

    @classmethod
    def build(cls, M: Any, K: Any, D: Any, dofs: IntArray, K0: FloatArray, C0: FloatArray,
              load: HarmonicLoad, where: str) -> LinearModes:
        """Diagonalise the shifted linear part; dense ``M``, ``K``, ``D`` (n, n).

        Uncoupled groups of DOFs (e.g. torsion, which no bearing tangent couples to the
        bending) are diagonalised separately (cheaper: the cost is cubic). Only one mode
        of each complex-conjugate pair is kept, with its eigenvector doubled: a real state
        has conjugate coordinates on the pair, so ``y = Re(V z)`` over the kept ones.

        Raises
        ------
        IllConditionedModes
            When the eigenbasis cannot represent the linear part to ``RECONSTRUCTION_LIMIT``
            (the caller then uses another stepper).
        """
        M, K, D = (np.asarray(X, dtype=float) for X in (M, K, D))
        n = M.shape[0]
        K0 = np.array(K0, dtype=float)
        diag = np.diag(K0).copy()
        soft = np.flatnonzero(diag <= 1e-9 * max(float(np.max(np.abs(diag), initial=0.0)),
                                                 1e-300))
        K0[soft, soft] += RIGID_SHIFT * np.abs(np.diag(K)[dofs[soft]])
        Ks, Ds = K.copy(), D.copy()
        Ks[np.ix_(dofs, dofs)] += K0
        Ds[np.ix_(dofs, dofs)] += C0
        minv = np.zeros((n, n))
        forces = np.zeros((n, dofs.size + 3), dtype=complex)
        forces[dofs, np.arange(dofs.size)] = 1.0
        forces[:, dofs.size:] = np.column_stack(
            [load.constant, 0.5 * load.amplitude, 0.5 * np.conj(load.amplitude)])
        parts = [_Block.build(idx, M, Ks, Ds, minv, forces, where)
                 for idx in _groups(M, Ks, Ds)]
        lam = np.concatenate([p.lam for p in parts])
        V = np.zeros((2 * n, lam.size), dtype=complex)
        at = 0
        for part in parts:
            V[np.ix_(part.rows, np.arange(at, at + part.lam.size))] = part.vectors
            at += part.lam.size
        modal = np.concatenate([p.loads for p in parts])
        k = dofs.size
        return cls(lam, V, tuple(p.solver for p in parts), np.asarray(dofs, dtype=np.int64),
                   K0, np.asarray(C0), modal[:, :k], modal[:, k], modal[:, k + 1],
                   modal[:, k + 2], float(load.frequency), minv)

    def modal(self, q: FloatArray, v: FloatArray) -> ComplexArray:
        """Kept coordinates of ``z = V^-1 (q, v)``."""
        y = np.concatenate([q, v])
        return np.concatenate([b.solve(y) for b in self.blocks])


def _groups(M: FloatArray, K: FloatArray, D: FloatArray) -> list[IntArray]:
    """DOF groups that no matrix couples (connected components of the pattern)."""
    return coupled_groups((M != 0) | (K != 0) | (D != 0))


@dataclass(frozen=True, eq=False)
class _Solver:
    """``z`` of one group from the state: rows of ``y`` (2m,), LU of its eigenvectors,
    the kept modes."""

    rows: IntArray
    lu: Any
    keep: IntArray
    unscale: FloatArray
    """Per row of ``y``: 1 for the displacements, ``1 / s`` for the velocities."""

    def solve(self, y: FloatArray) -> ComplexArray:
        return np.asarray(sl.lu_solve(self.lu, (y[self.rows] * self.unscale).astype(complex),
                                      check_finite=False)[self.keep])


@dataclass(frozen=True, eq=False)
class _Block:
    """The kept modes of one DOF group: eigenvalues, eigenvectors on its rows, modal loads
    of the columns of ``forces``."""

    rows: IntArray
    lam: ComplexArray
    vectors: ComplexArray
    loads: ComplexArray
    solver: _Solver

    @classmethod
    def build(cls, idx: IntArray, M: FloatArray, Ks: FloatArray, Ds: FloatArray,
              minv: FloatArray, forces: ComplexArray, where: str) -> _Block:
        """Diagonalise the group ``idx``; fills its block of ``minv`` (``M`` is block
        diagonal over the groups)."""
        n, m = M.shape[0], idx.size
        sub = np.ix_(idx, idx)
        mi = np.linalg.inv(M[sub])
        minv[sub] = mi
        # diagonalised in y_s = (q, v / s), s from :func:`velocity_scale` (its docstring)
        s = velocity_scale(np.diag(Ks)[idx], np.diag(M)[idx])
        A = np.zeros((2 * m, 2 * m))
        A[:m, m:] = s * np.eye(m)
        A[m:, :m] = (mi @ Ks[sub]) * (-1.0 / s)
        A[m:, m:] = -mi @ Ds[sub]
        lam, V = np.linalg.eig(A)
        lu = sl.lu_factor(V, check_finite=False)
        x = np.cos(np.arange(2 * m) + 0.5)
        back = V @ sl.lu_solve(lu, x, check_finite=False)
        if not (np.all(np.isfinite(back)) and
                float(np.max(np.abs(back - x))) <= RECONSTRUCTION_LIMIT):
            raise IllConditionedModes("eigenbasis of the linear part is ill-conditioned",
                                      where)
        if int(np.count_nonzero(lam.imag > 0)) != int(np.count_nonzero(lam.imag < 0)):
            raise IllConditionedModes("eigenvalues of the linear part are not in "
                                      "conjugate pairs", where)
        keep = np.flatnonzero(lam.imag >= 0.0)
        rhs = np.zeros((2 * m, forces.shape[1]), dtype=complex)
        rhs[m:] = (mi @ forces[idx]) * (1.0 / s)
        loads = sl.lu_solve(lu, rhs, check_finite=False)[keep]
        unscale = np.concatenate([np.ones(m), np.full(m, 1.0 / s)])
        # back to y = (q, v): the velocity rows times s (a power of two: exact)
        vectors = V[:, keep] * (np.where(lam.imag[keep] > 0.0, 2.0, 1.0)[None, :] /
                                unscale[:, None])
        rows = np.concatenate([idx, n + idx])
        return cls(rows, lam[keep], vectors, loads, _Solver(rows, lu, keep, unscale))


def velocity_scale(k_diag: FloatArray, m_diag: FloatArray) -> float:
    """The power of two nearest the geometric mean of ``sqrt(K_jj / M_jj)`` over the DOFs
    where both are positive [rad/s] (1 when there are none).

    The eigenvectors of ``A`` in ``y = (q, v)`` have velocity parts ``lambda`` times their
    displacement parts, ``|lambda|`` spanning 2e2 to 5e5 rad/s on a small FE rotor: the
    matrix of eigenvectors then has a condition number near 5e7 from this row scaling
    alone, and its reconstruction error (``cond * eps``) sits at
    :data:`RECONSTRUCTION_LIMIT`, passed or refused depending on the BLAS. In ``(q, v / s)``
    with ``s`` inside the spectrum it falls to about 5e3 on the benchmark rotors (measured
    2e3-8e3 for any ``s`` from 1e4 to 1e5 rad/s); a power of two makes the scaling back
    exact."""
    ok = (k_diag > 0.0) & (m_diag > 0.0)
    if not ok.any():
        return 1.0
    mean_log = 0.5 * float(np.mean(np.log2(k_diag[ok] / m_diag[ok])))
    return float(2.0 ** round(mean_log))


@dataclass(frozen=True, eq=False)
class StepWeights:
    """Weights of a step of size ``h`` at the fractions ``x`` (p,) of the step, for the
    interpolation of ``rho`` through the nodes ``c`` (s + 1,) starting at 0.

    Attributes
    ----------
    E : complex (p, N)
        ``e^{lambda x h}``.
    const, plus, minus : complex (p, N)
        Exact integrals of the constant load and of ``e^{+-iW (t_n + s)}`` per unit
        ``e^{+-iW t_n}``, times the modal loads.
    W : complex (p, s + 1, N)
        ``int_0^{x h} e^{lambda (x h - s)} l_j(s / h) ds`` of the Lagrange basis ``l_j``.
    mono : complex (p, m, N)
        The same integrals of the monomials ``(s / h)^m`` (``W = L mono``: the weights of
        another basis at the same fractions cost one product).
    """

    E: ComplexArray
    const: ComplexArray
    plus: ComplexArray
    minus: ComplexArray
    W: ComplexArray
    mono: ComplexArray

    @classmethod
    def of(cls, modes: LinearModes, h: float, x: FloatArray, L: FloatArray,
           monomials: int = 0) -> StepWeights:
        """Weights at the fractions ``x`` for the basis coefficients ``L`` (p_basis, m);
        ``mono`` holds ``max(m, monomials)`` monomials (for :meth:`select` with a basis of
        a higher degree)."""
        lam, w = modes.lam, modes.frequency
        degree = max(L.shape[1], monomials)
        x = np.asarray(x, dtype=float)
        tau = x[:, None] * h  # (p, 1)
        p, N = tau.size, lam.size
        # with phi_1 of (lam -+ iW) tau, the two halves of the harmonic load (one call)
        every = phi_functions((modes.shifts[:, None, :] * tau[None]).ravel(), degree)
        every = every.reshape(degree + 1, 3, p, N)
        phis, shifted = every[:, 0], every[1, 1:]
        E = phis[0]
        const = tau * phis[1] * modes.b_const[None, :]
        # e^{iW tau} of the p fractions (a few numbers: cmath is cheaper than an array call)
        turn = np.array([cmath.exp(1j * w * t) for t in tau[:, 0].tolist()])[:, None]
        plus = turn * tau * shifted[0] * modes.b_plus[None, :]
        minus = np.conj(turn) * tau * shifted[1] * modes.b_minus[None, :]
        # int_0^tau e^{lam (tau - s)} (s/h)^m ds = m! tau^{m+1} h^-m phi_{m+1}(lam tau)
        # = m! h x^{m+1} phi_{m+1}(lam tau)
        m = np.arange(degree)
        coef = h * _FACTORIALS[:degree] * x[:, None] ** (m + 1)  # (p, m)
        mono = coef[:, :, None] * phis[1:].transpose(1, 0, 2)  # (p, m, N)
        W = np.matmul(L[None, :, :], mono[:, :L.shape[1]])  # (p, j, N)
        return cls(E, const, plus, minus, W, mono)

    def select(self, rows: slice, L: FloatArray) -> StepWeights:
        """The weights of the fractions ``rows`` for another basis ``L`` (p_basis, m),
        from the monomials already integrated (one call of the ``phi`` functions for the
        fractions of several uses: each call costs tens of microseconds at any size)."""
        mono = self.mono[rows, :L.shape[1]]
        return StepWeights(self.E[rows], self.const[rows], self.plus[rows], self.minus[rows],
                           np.matmul(L[None, :, :], mono), mono)
