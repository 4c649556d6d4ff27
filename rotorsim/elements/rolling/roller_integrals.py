"""Per-roller line integrals and their assembly into the bearing force and tangent.

A roller ``j`` at ``psi_j`` with the centre approach ``V_j`` and tilt ``L omega_j`` has the
deflection ``delta(xi) = V_j + xi L omega_j - c(xi)`` along its length; the bearing needs
the integrals of :class:`LineIntegrals` (seed 000 eqs 7-9, 22-23). With
``g(xi) = d delta / d(x, y, z, rx, ry) = (ca cos psi, ca sin psi, sa, arm sin psi,
-arm cos psi)``, ``arm = r_p sin a0 - xi L`` (seed 000 eq 10), a per-roller quadratic form
``int w(xi) g g^T dxi`` needs only the weights ``int w arm^p dxi`` (``p = 0, 1, 2``):
:func:`assemble_tangent` sums them over the rollers (seed 000 Appendix A2). The rigid-ring
model (:mod:`~rotorsim.elements.rolling.roller`) and the centrifugal model
(:mod:`~rotorsim.elements.rolling.roller_centrifugal`) share these helpers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from rotorsim.elements.rolling.state import FloatArray


class LineIntegrals(NamedTuple):
    """Integrals along each roller, arrays ``(S, N)``; ``delta^+`` the positive deflection.

    ``energy = int delta^(n+1)/(n+1)``, ``load = int delta^n``, ``load_moment =
    int xi delta^n``, ``tangent0..2 = int xi^p delta^(n-1)`` (all over ``dxi``), ``peak``
    the largest deflection along the roller.
    """

    energy: FloatArray
    load: FloatArray
    load_moment: FloatArray
    tangent0: FloatArray
    tangent1: FloatArray
    tangent2: FloatArray
    peak: FloatArray


@dataclass(frozen=True, eq=False)
class RollerLoads:
    """Per-roller load distribution, arrays ``(S, N)`` (``slice_load``: ``(S, N, K)``).

    Attributes
    ----------
    load : Contact load ``Q_j`` [N] (seed 000 eq 7b).
    eccentricity : Load eccentricity ``e_j`` [m] from the roller centre along ``t_j``
        (seed 000 eq 9); 0 for unloaded rollers.
    contact_limits : ``(S, N, 2)`` dimensionless ends ``xi_1, xi_2`` of the loaded zone
        (seed 000 eq 8; for slices the outer edges of the loaded slices); NaN if unloaded.
    slice_load : Load of each slice [N] (``model="slices"``), else ``None``.
    """

    load: FloatArray
    eccentricity: FloatArray
    contact_limits: FloatArray
    slice_load: FloatArray | None = None


def tilt_limits(v: FloatArray, lw: FloatArray) -> FloatArray:
    """Loaded zone ``(xi_1, xi_2)`` of straight rollers (seed 000 eq 8), NaN if unloaded."""
    with np.errstate(divide="ignore", invalid="ignore"):
        xi0 = np.where(lw != 0.0, -v / np.where(lw != 0.0, lw, 1.0), np.nan)
    lo = np.where(lw > 0.0, np.maximum(xi0, -0.5), -0.5)
    hi = np.where(lw < 0.0, np.minimum(xi0, 0.5), 0.5)
    loaded = (v + 0.5 * np.abs(lw)) > 0.0
    return np.where(loaded[..., None], np.stack([lo, hi], axis=-1), np.nan)


def assemble_tangent(c: FloatArray, s: FloatArray, w0: FloatArray, w1: FloatArray,
                      w2: FloatArray, ca: float, sa: float) -> FloatArray:
    """``sum_j int delta^(n-1) g g^T`` from the weights of ``1, arm, arm^2`` (S, N).

    ``g = (ca u, sa, arm J u)`` with ``u = (cos psi, sin psi)``, ``J u = (sin, -cos)`` and
    ``arm = r_p sin a0 - xi L``; ``w0, w1, w2`` are the integrals of
    ``delta^(n-1) arm^p``.
    """
    cc, cs, ss = c * c, c * s, s * s
    m0 = [(w * cc).sum(1) for w in (w0, w1, w2)]  # sum w cos^2
    m1 = [(w * cs).sum(1) for w in (w0, w1, w2)]  # sum w cos sin
    m2 = [(w * ss).sum(1) for w in (w0, w1, w2)]  # sum w sin^2
    v0 = [(w * c).sum(1) for w in (w0, w1)]
    v1 = [(w * s).sum(1) for w in (w0, w1)]
    k = np.empty((c.shape[0], 5, 5))
    k[:, 0, 0], k[:, 0, 1], k[:, 1, 1] = ca * ca * m0[0], ca * ca * m1[0], ca * ca * m2[0]
    k[:, 0, 2], k[:, 1, 2], k[:, 2, 2] = ca * sa * v0[0], ca * sa * v1[0], sa * sa * w0.sum(1)
    # translation-rotation block: ca * M2(w1) J^T, J^T = [[0, -1], [1, 0]]
    k[:, 0, 3], k[:, 0, 4] = ca * m1[1], -ca * m0[1]
    k[:, 1, 3], k[:, 1, 4] = ca * m2[1], -ca * m1[1]
    # axial-rotation block: sa * (J m1(w1))^T = sa * (sum w1 sin, -sum w1 cos)
    k[:, 2, 3], k[:, 2, 4] = sa * v1[1], -sa * v0[1]
    # rotation block: J M2(w2) J^T
    k[:, 3, 3], k[:, 3, 4], k[:, 4, 4] = m2[2], -m1[2], m0[2]
    lower = np.tril_indices(5, -1)
    k[:, lower[0], lower[1]] = k[:, lower[1], lower[0]]
    return k


def unit_load_directions(c: FloatArray, s: FloatArray, unit_arm: FloatArray, ca: float,
                         sa: float) -> FloatArray:
    """Unit-load directions ``g_j = dF/dQ_j`` (S, Z, 5) of the rollers (seed 000 eq 10).

    ``(ca cos psi, ca sin psi, sa, a_j sin psi, -a_j cos psi)`` with the moment arm
    ``a_j = r_p sin a0 - e_j`` [m] (``unit_arm``, (S, Z)).
    """
    direction = np.empty((*c.shape, 5))
    np.multiply(c, ca, out=direction[..., 0])
    np.multiply(s, ca, out=direction[..., 1])
    direction[..., 2] = sa
    np.multiply(unit_arm, s, out=direction[..., 3])
    np.multiply(unit_arm, -c, out=direction[..., 4])
    return direction
