"""Ball-bearing force and exact tangent from per-ball sums (seed 000 eqs 4, 27; Appendix A1).

Every ball contributes, in the plane of its azimuth ``psi_j``, a radial/axial force
``(F_R, F_Z)`` and a symmetric 2x2 tangent ``[[P, U], [U, V]]`` with respect to the radial
and axial displacement of the inner groove curvature centre. Both are mapped to the 5
relative DOFs ``(x, y, z, rx, ry)`` by ``dR/d delta = (cos psi, sin psi, 0, 0, 0)`` and
``dZ/d delta = (0, 0, 1, r_j sin psi, -r_j cos psi)`` (seed 000 eq 2). The sums over the
balls need only the products of ``(P, U, V, F_R, F_Z)`` with ``cos^2, cos sin, sin^2, cos,
sin, 1`` of ``psi_j``: one batched matrix product (:func:`ball_sums`), mapped to force and
tangent by a second, constant one (:func:`assemble`). The rigid-ring model
(:mod:`~rotorsim.elements.rolling.ball.bearing`) and the centrifugal model
(:mod:`~rotorsim.elements.rolling.ball.centrifugal`) share it.
"""

from __future__ import annotations

import functools

import numpy as np

from rotorsim.elements.rolling.geometry import angle_basis
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
# force: Fx = sum Q cos a c, Fy = sum Q cos a s, Fz = sum Q sin a, Mx = r sum Q sin a s,
# My = -r sum Q sin a c
_F_SOURCE = (6 * 3 + 3, 6 * 3 + 4, 6 * 4 + 5, 6 * 4 + 4, 6 * 4 + 3)


def ball_sums(rows: FloatArray, c: FloatArray, s: FloatArray) -> FloatArray:
    """Sums over the balls ``(S, 5, 6)`` of ``rows`` (S, 5, N) times the angle basis.

    ``rows`` holds ``(P, U, V, F_R, F_Z)`` per ball, ``c, s`` (S, N) ``cos, sin(psi_j)``;
    the basis columns are ``c^2, c s, s^2, c, s, 1``.
    """
    return np.asarray(np.matmul(rows, np.swapaxes(angle_basis(c, s), -1, -2)))


@functools.lru_cache(maxsize=64)
def sums_transform(arm: float) -> FloatArray:
    """``(30, 30)`` matrix ``T``: ``sums.reshape(S, 30) @ T`` is ``[force | stiffness]``
    (S, 5 + 25), the force and the row-major stiffness of :func:`assemble`.

    Every column has one non-zero entry (``+-arm^p``), so the product is exact: each output
    is one rounded product, as if picked and scaled entry by entry. Cached, read-only.
    """
    t = np.zeros((30, 30))
    for i, (source, scale) in enumerate(zip(_F_SOURCE, (1.0, 1.0, 1.0, arm, -arm),
                                            strict=True)):
        t[source, i] = scale
    for (row, col), b_row, b_col, power, sign in _K_ENTRIES:
        t[6 * b_row + b_col, 5 + 5 * row + col] = sign * arm**power
        t[6 * b_row + b_col, 5 + 5 * col + row] = sign * arm**power
    t.flags.writeable = False
    return t


def assemble(sums: FloatArray, arm: float) -> tuple[FloatArray, FloatArray]:
    """Force (..., 5) and symmetric stiffness (..., 5, 5) from the ball sums (..., 5, 6).

    ``sums[..., i, k]`` = sum_j row_i * basis_k with rows (P, U, V, Q cos a, Q sin a) and
    basis (c^2, cs, s^2, c, s, 1), ``c, s = cos, sin(psi_j)``; one product with
    :func:`sums_transform`.
    """
    lead = sums.shape[:-2]
    flat = sums.reshape(-1, 30) @ sums_transform(float(arm))
    return flat[:, :5].reshape(*lead, 5), flat[:, 5:].reshape(*lead, 5, 5)


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
