"""Potential of one roller clamped between two flexible ring segments (seed 001 eqs 8-21).

Per roller the DOFs are (internal first, seed 001 eq 12 and eq 3)::

    y = [v_r, phi, w_i, w_e]      roller radial displacement (outwards), roller tilt about
                                  the local tangent n, radial deflection of the inner ring
                                  (inwards) and of the outer ring (outwards)
    z = [u_r, gamma_n]            radial displacement and tilt of the outer ring relative
                                  to the inner ring at the roller (eq 3)

Slice ``k`` (width ``h_k``, centre ``s_k``, profile drop ``c_k = R_b - b_k``) is compressed
by (eqs 13, 15)::

    delta_ik = -g/4 - v_r - w_i - c_k - phi s_k
    delta_ek = -g/4 - u_r + v_r - w_e - c_k + (phi - gamma_n) s_k

with the diametral clearance ``g`` (negative: preload). The roller potential (eq 19) is::

    Pi = U_i + U_e + T_i + B_i + T_e + B_e - V

* ``U_a = C/(n+1) sum_k h_k <delta_ak>^(n+1)`` (eq 17, Hertz line law ``q = C delta^n``);
* ``T_a = E A_a theta w_a^2 / (2 R_a)`` (eq 9, ring tension, ``theta = 2 pi / N``);
* ``B_a = E I_a theta w_a^2 / (2 R_a (R_a -+ w_a)^2)`` (eq 10, ring bending; ``-`` for the
  inner ring, ``+`` for the outer one);
* ``V = m omega_c^2 ((R_p + v_r)^2 - R_p^2) / 2`` (eq 18, measured from ``v_r = 0``: the
  constant ``m omega_c^2 R_p^2 / 2`` is dropped).

Each contact's deflections are linear in the DOFs, ``d delta_ak = (A_a + s_k B_a) . d(y, z)``,
so its gradient is ``Q_a A_a + M_a B_a`` and its Hessian
``K0_a A A^T + K1_a (A B^T + B A^T) + K2_a B B^T`` with the slice sums
``Q_a, M_a = sum C h delta^n (1, s)`` (eqs 21a-b) and
``K0_a, K1_a, K2_a = n sum C h delta^(n-1) (1, s, s^2)``. The ring terms give
``N_a = dT/dw + dB/dw`` (eq 21c) and the centrifugal force ``F_c = m omega_c^2 (R_p + v_r)``
(eq 21d). All are evaluated for ``M`` rollers at once, and projected on the active DOFs
(without tilt: no ``phi``, ``gamma_n``; rigid rings: no ``w_i``, ``w_e``) by two small
matrix products.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np

from rotorsim.elements.rolling.condensation import LocalProblem
from rotorsim.elements.rolling.flexible_ring.geometry import FloatArray, RollerSlices

ROLLER_DOFS = ("v_r", "phi", "w_i", "w_e")
"""Internal DOFs of a roller (seed 001 eq 12), in the order of ``internal`` arrays."""
LOCAL_DOFS = ("u_r", "gamma_n")
"""External (master) DOFs of a roller (seed 001 eq 3)."""

# d delta / d(v, phi, w_i, w_e, u_r, gamma) = A + s B for the inner and outer contact
_A_I = np.array([-1.0, 0.0, -1.0, 0.0, 0.0, 0.0])
_B_I = np.array([0.0, -1.0, 0.0, 0.0, 0.0, 0.0])
_A_E = np.array([1.0, 0.0, 0.0, -1.0, -1.0, 0.0])
_B_E = np.array([0.0, 1.0, 0.0, 0.0, 0.0, -1.0])
_UNIT = np.eye(6)


class ContactDetail(NamedTuple):
    """Contact output of ``M`` rollers: slice loads ``h_k C delta^n`` [N] (M, K) and peak
    slice deflections [m] (M,) of the inner and outer contact."""

    inner_slice_load: FloatArray
    outer_slice_load: FloatArray
    inner_peak: FloatArray
    outer_peak: FloatArray


def _power(x: FloatArray, exponent: float) -> FloatArray:
    """``x^p`` for ``x >= 0``; ``x^(1/9)`` as ``cbrt(cbrt(x))`` (twice as fast)."""
    if abs(exponent - 1.0 / 9.0) < 1e-12:
        out = np.cbrt(x)
        return np.cbrt(out, out=out)
    if exponent == 0.0:
        return (x > 0.0).astype(float)
    return np.asarray(x**exponent)


@dataclass(frozen=True, eq=False)
class RollerPotential:
    """The roller potential of seed 001 eq 19 and its derivatives (module docstring).

    Parameters
    ----------
    contact_constant : float
        ``C`` [N/m^(1+n)] of both line contacts (eq 16).
    exponent : float
        ``n``.
    clearance : float
        Diametral clearance ``g`` [m].
    slices : RollerSlices
    pitch_radius : float
        ``R_p`` [m].
    inner_ring, outer_ring : tuple of 3 floats
        ``(E A theta / R_m, E I theta, R_m)`` of each ring segment [N/m, N m^2, m].
    internal : tuple of int
        Active internal DOFs (indices into :data:`ROLLER_DOFS`).
    external : tuple of int
        Active external DOFs (indices into :data:`LOCAL_DOFS`).
    """

    contact_constant: float
    exponent: float
    clearance: float
    slices: RollerSlices
    pitch_radius: float
    inner_ring: tuple[float, float, float]
    outer_ring: tuple[float, float, float]
    internal: tuple[int, ...]
    external: tuple[int, ...]

    @cached_property
    def active(self) -> list[int]:
        """Active DOFs among ``(v, phi, w_i, w_e, u_r, gamma)``, internal first."""
        return [*self.internal, *(4 + k for k in self.external)]

    @cached_property
    def _grad_basis(self) -> FloatArray:
        """(a, 7): the gradient is this times ``[Q_i, M_i, Q_e, M_e, N_i, N_e, -F_c]``."""
        rows = np.stack([_A_I, _B_I, _A_E, _B_E, _UNIT[2], _UNIT[3], _UNIT[0]])
        return np.ascontiguousarray(rows[:, self.active].T)

    @cached_property
    def _hess_basis(self) -> FloatArray:
        """(a*a, 9): the Hessian is this times ``[K0_i, K1_i, K2_i, K0_e, K1_e, K2_e, k_wi,
        k_we, -m omega_c^2]``."""
        def sym(a: FloatArray, b: FloatArray) -> FloatArray:
            return np.outer(a, b) + np.outer(b, a)

        mats = [np.outer(_A_I, _A_I), sym(_A_I, _B_I), np.outer(_B_I, _B_I),
                np.outer(_A_E, _A_E), sym(_A_E, _B_E), np.outer(_B_E, _B_E),
                np.outer(_UNIT[2], _UNIT[2]), np.outer(_UNIT[3], _UNIT[3]),
                np.outer(_UNIT[0], _UNIT[0])]
        idx = np.ix_(self.active, self.active)
        return np.ascontiguousarray(np.stack([m[idx].reshape(-1) for m in mats]).T)

    @cached_property
    def _weights(self) -> FloatArray:
        """(6, K): slice weights of ``K0, K1, K2`` (on ``delta^(n-1)``), of ``Q, M`` (on
        ``delta^n``) and of the energy (on ``delta^(n+1)``)."""
        ch = self.contact_constant * self.slices.widths
        s = self.slices.positions
        n = self.exponent
        return np.stack([n * ch, n * ch * s, n * ch * s * s, ch, ch * s, ch / (n + 1.0)])

    @cached_property
    def _slice_basis(self) -> FloatArray:
        sl = self.slices
        return np.stack([np.ones(sl.count), sl.positions, -0.25 * self.clearance - sl.drops])

    def deflections(self, y: FloatArray, z: FloatArray) -> FloatArray:
        """Slice compressions (2, M, K) [m] of the inner [0] and outer [1] contact (eq 15)
        for full internal DOFs ``y`` (4, M) and local DOFs ``z`` (2, M)."""
        v, phi, w_i, w_e = y
        coef = np.empty((2, y.shape[1], 3))
        coef[0, :, 0], coef[1, :, 0] = -(v + w_i), v - w_e - z[0]
        coef[0, :, 1], coef[1, :, 1] = -phi, phi - z[1]
        coef[..., 2] = 1.0
        return coef @ self._slice_basis  # centre + slope s_k + (-g/4 - c_k)

    def _slice_sums(self, y: FloatArray, z: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Slice sums of both contacts (6, 2, M): ``K0, K1, K2, Q, M, U`` (module
        docstring), and the peak inner compression (M,); in blocks of about 16k contacts so
        that the temporaries stay in cache."""
        n_sys = y.shape[1]
        w = self._weights
        sums, peak = np.empty((6, 2, n_sys)), np.empty(n_sys)
        size = max(1, 8192 // self.slices.count)
        for lo in range(0, n_sys, size):
            blk = slice(lo, lo + size)
            pos = self.deflections(y[:, blk], z[:, blk])
            np.maximum(pos, 0.0, out=pos)
            t = _power(pos, self.exponent - 1.0)
            b = pos.shape[1]
            sums[0:3, :, blk] = (w[0:3] @ t.reshape(2 * b, -1).T).reshape(3, 2, b)
            t *= pos
            sums[3:5, :, blk] = (w[3:5] @ t.reshape(2 * b, -1).T).reshape(2, 2, b)
            t *= pos
            sums[5, :, blk] = (w[5] @ t.reshape(2 * b, -1).T).reshape(2, b)
            peak[blk] = pos[0].max(axis=1)
        return sums, peak

    def evaluate(self, y: FloatArray, z: FloatArray, m_omega2: FloatArray) -> LocalProblem:
        """``Pi``, its gradient and Hessian in the active DOFs for ``M`` rollers.

        Parameters
        ----------
        y : array (4, M)
            Internal DOFs ``[v_r, phi, w_i, w_e]`` [m, rad, m, m] (inactive ones 0).
        z : array (2, M)
            ``[u_r, gamma_n]`` [m, rad].
        m_omega2 : array (M,)
            ``m omega_c^2`` [N/m] (roller mass times the squared cage speed).

        Returns
        -------
        LocalProblem
            ``grad`` (a, M) and ``hess`` (a, a, M) over the active DOFs ``a``; ``scale``
            the roller's ``Q_i + Q_e + F_c`` [N]; ``aux`` (3, M) ``[Q_i, Q_e, peak inner
            slice compression]``.
        """
        n_sys = y.shape[1]
        sums, peak = self._slice_sums(y, z)
        ring_e, n_i, n_e, k_i, k_e = self._rings(y[2], y[3])
        v = y[0]
        f_c = m_omega2 * (self.pitch_radius + v)
        gcoef = np.empty((7, n_sys))
        gcoef[0:2], gcoef[2:4] = sums[3:5, 0], sums[3:5, 1]
        gcoef[4], gcoef[5], gcoef[6] = n_i, n_e, -f_c
        hcoef = np.empty((9, n_sys))
        hcoef[0:3], hcoef[3:6] = sums[0:3, 0], sums[0:3, 1]
        hcoef[6], hcoef[7], hcoef[8] = k_i, k_e, -m_omega2
        n_act = len(self.active)
        aux = np.empty((3, n_sys))
        aux[0], aux[1], aux[2] = sums[3, 0], sums[3, 1], peak
        energy = sums[5].sum(axis=0) + ring_e - m_omega2 * (self.pitch_radius * v + 0.5 * v * v)
        return LocalProblem(energy, self._grad_basis @ gcoef,
                            (self._hess_basis @ hcoef).reshape(n_act, n_act, n_sys),
                            aux[0] + aux[1] + np.abs(f_c), aux)

    def _rings(self, w_i: FloatArray, w_e: FloatArray) -> tuple[FloatArray, ...]:
        """Ring energy ``T + B`` (eqs 9-10), forces ``N_i, N_e`` (eq 21c), stiffnesses."""
        energy = np.zeros_like(w_i)
        force, stiffness = [], []
        for (kt, ei, r), w, sign in ((self.inner_ring, w_i, -1.0), (self.outer_ring, w_e, 1.0)):
            inv = 1.0 / (r + sign * w)  # 1 / (R -+ w): the bent segment's radius
            inv2 = inv * inv
            energy += 0.5 * w * w * (kt + (ei / r) * inv2)
            force.append(w * (kt + ei * inv2 * inv))
            stiffness.append(kt + ei * (r - 2.0 * sign * w) * inv2 * inv2)
        return energy, force[0], force[1], stiffness[0], stiffness[1]

    def contacts(self, y: FloatArray, z: FloatArray) -> ContactDetail:
        """Slice loads and peak deflections of ``M`` rollers (post-processing; ``y`` (4, M),
        ``z`` (2, M))."""
        d = self.deflections(y, z)
        pos = np.maximum(d, 0.0)
        loads = self.contact_constant * self.slices.widths * pos**self.exponent
        return ContactDetail(loads[0], loads[1], pos[0].max(axis=1), pos[1].max(axis=1))
