"""Ball-bearing force and exact tangent from per-ball sums (seed 000 eqs 4, 27; Appendix A1).

Every ball contributes, in the plane of its azimuth ``psi_j``, a radial/axial force
``(F_R, F_Z)`` and a symmetric 2x2 tangent ``[[P, U], [U, V]]`` with respect to the radial
and axial displacement of the inner groove curvature centre. Both are mapped to the 5
relative DOFs ``(x, y, z, rx, ry)`` by ``dR/d delta = (cos psi, sin psi, 0, 0, 0)`` and
``dZ/d delta = (0, 0, 1, r_j sin psi, -r_j cos psi)`` (seed 000 eq 2). The sums over the
balls need only the products of ``(P, U, V, F_R, F_Z)`` with ``cos^2, cos sin, sin^2, cos,
sin, 1`` of ``psi_j``: one batched matrix product (:func:`assemble`). The rigid-ring model
(:mod:`~rotorsim.elements.rolling.ball`) and the centrifugal model
(:mod:`~rotorsim.elements.rolling.ball_centrifugal`) share it.
"""

from __future__ import annotations

import numpy as np

from rotorsim.elements.rolling.state import FloatArray

# Stiffness entries (row, column) from the ball sums: (row of ``rows``, basis column,
# power of the moment arm r_j, sign); basis columns are c^2, cs, s^2, c, s, 1.
_K_ENTRIES = (
    ((0, 0), 0, 0, 0, 1.0), ((0, 1), 0, 1, 0, 1.0), ((1, 1), 0, 2, 0, 1.0),
    ((0, 2), 1, 3, 0, 1.0), ((1, 2), 1, 4, 0, 1.0),
    ((0, 3), 1, 1, 1, 1.0), ((0, 4), 1, 0, 1, -1.0),
    ((1, 3), 1, 2, 1, 1.0), ((1, 4), 1, 1, 1, -1.0),
    ((2, 2), 2, 5, 0, 1.0), ((2, 3), 2, 4, 1, 1.0), ((2, 4), 2, 3, 1, -1.0),
    ((3, 3), 2, 2, 2, 1.0), ((3, 4), 2, 1, 2, -1.0), ((4, 4), 2, 0, 2, 1.0),
)
_K_SOURCE = np.array([6 * e[1] + e[2] for e in _K_ENTRIES])
_K_UPPER = np.array([5 * e[0][0] + e[0][1] for e in _K_ENTRIES])
_K_LOWER = np.array([5 * e[0][1] + e[0][0] for e in _K_ENTRIES])
# force: Fx = sum Q cos a c, Fy = sum Q cos a s, Fz = sum Q sin a, Mx = r sum Q sin a s,
# My = -r sum Q sin a c
_F_SOURCE = np.array([6 * 3 + 3, 6 * 3 + 4, 6 * 4 + 5, 6 * 4 + 4, 6 * 4 + 3])


def ball_sums(rows: FloatArray, c: FloatArray, s: FloatArray) -> FloatArray:
    """Sums over the balls ``(S, 5, 6)`` of ``rows`` (S, 5, N) times the angle basis.

    ``rows`` holds ``(P, U, V, F_R, F_Z)`` per ball, ``c, s`` (S, N) ``cos, sin(psi_j)``;
    the basis columns are ``c^2, c s, s^2, c, s, 1``.
    """
    basis = np.empty((c.shape[0], 6, c.shape[1]))
    np.multiply(c, c, out=basis[:, 0])
    np.multiply(c, s, out=basis[:, 1])
    np.multiply(s, s, out=basis[:, 2])
    basis[:, 3] = c
    basis[:, 4] = s
    basis[:, 5] = 1.0
    return np.asarray(np.matmul(rows, basis.transpose(0, 2, 1)))


def assemble(sums: FloatArray, arm: float) -> tuple[FloatArray, FloatArray]:
    """Force (S, 5) and symmetric stiffness (S, 5, 5) from the ball sums (S, 5, 6).

    ``sums[:, i, k]`` = sum_j row_i * basis_k with rows (P, U, V, Q cos a, Q sin a) and
    basis (c^2, cs, s^2, c, s, 1), ``c, s = cos, sin(psi_j)``.
    """
    n_samples = sums.shape[0]
    flat = sums.reshape(n_samples, 30)
    k_scale = np.array([sign * arm**power for _, _, _, power, sign in _K_ENTRIES])
    f_scale = np.array([1.0, 1.0, 1.0, arm, -arm])
    values = flat[:, _K_SOURCE] * k_scale
    k = np.empty((n_samples, 25))
    k[:, _K_LOWER] = values
    k[:, _K_UPPER] = values
    return flat[:, _F_SOURCE] * f_scale, k.reshape(n_samples, 5, 5)


def directions(sin_a: FloatArray, cos_a: FloatArray, c: FloatArray, s: FloatArray,
                arm: float) -> FloatArray:
    """Unit-load directions ``g_j = dA_j/d delta`` (S, N, 5) (seed 000 eq 4).

    ``(cos a c, cos a s, sin a, r sin a s, -r sin a c)`` with ``tan a = Z_j / R_j`` (also
    for unloaded balls, where it is the direction of the groove-centre line).
    """
    g = np.empty((*c.shape, 5))
    np.multiply(cos_a, c, out=g[..., 0])
    np.multiply(cos_a, s, out=g[..., 1])
    g[..., 2] = sin_a
    arm_sin = arm * sin_a
    np.multiply(arm_sin, s, out=g[..., 3])
    np.multiply(arm_sin, c, out=g[..., 4])
    np.negative(g[..., 4], out=g[..., 4])
    return g
