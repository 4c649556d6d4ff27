"""Roller-to-bearing transformation of the flexible-ring bearing and its batched output.

Seed 001 places node A at the inner ring and describes the outer ring relative to it
(``y_rel``, eq 1); rotorsim's bearings act on ``delta = u_inner - u_outer`` (DESIGN
section 3), i.e. ``y_rel = -delta``. With roller ``j`` at ``psi`` the local DOFs of eq 3,
``z = S_j y_rel``, are therefore::

    u_r     = -(x cos psi + y sin psi)
    gamma_n = rx sin psi - ry cos psi

so ``z = T_j delta`` with ``T_j = -S_j`` (eq 4, restricted to ``x, y, z, rx, ry``). The
bearing potential is ``U(delta) = sum_j Pi*_j(T_j delta)``, so the restoring force on the
inner ring and its tangent are (eqs 6-7, with ``P_local = -dPi*/dz``)::

    F = dU/d delta = sum_j T_j^T dPi*_j/dz = -sum_j T_j^T P_local,j
    K = sum_j T_j^T K_local,j T_j

At a static equilibrium ``F`` equals the load applied to the inner ring.

References
----------
Seed 001 eqs 1-7.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorsim.elements.rolling.condensation import InnerNewtonStats
from rotorsim.elements.rolling.state import BearingState, FloatArray


def local_transform(psi: FloatArray, tilt: bool) -> FloatArray:
    """``T_j`` (S, N, e, 5) with ``e = 2`` (``u_r``, ``gamma_n``) or 1 without tilt.

    Examples
    --------
    >>> local_transform(np.zeros((1, 1)), True)[0, 0].tolist()
    [[-1.0, -0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, -1.0]]
    """
    c, s = np.cos(psi), np.sin(psi)
    t = np.zeros((*psi.shape, 2 if tilt else 1, 5))
    t[..., 0, 0], t[..., 0, 1] = -c, -s
    if tilt:
        t[..., 1, 3], t[..., 1, 4] = s, -c
    return t


def assemble(psi: FloatArray, local_grad: FloatArray, local_hess: FloatArray
             ) -> tuple[FloatArray, FloatArray]:
    """Bearing force (S, 5) and tangent (S, 5, 5) from the condensed rollers (eqs 6-7).

    ``F = sum_j T_j^T g_j`` and ``K = sum_j T_j^T H_j T_j`` written out for the sparse
    ``T_j`` of :func:`local_transform`.

    Parameters
    ----------
    psi : array (S, N)
        Roller angles [rad].
    local_grad : array (e, S, N)
        ``dPi*/dz`` of every roller (``e = 2``: ``u_r``, ``gamma_n``; 1 without tilt).
    local_hess : array (e, e, S, N)
        ``d^2 Pi*/dz^2`` (``K_local``, eq 26).

    Examples
    --------
    >>> f, k = assemble(np.zeros((1, 1)), -np.ones((2, 1, 1)), np.ones((2, 2, 1, 1)))
    >>> (f[0] + 0.0).tolist(), (k[0, 0] + 0.0).tolist()
    ([1.0, 0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0, 1.0])
    """
    c, s = np.cos(psi), np.sin(psi)
    cc, cs, ss = c * c, c * s, s * s
    n_s = psi.shape[0]
    force = np.zeros((n_s, 5))
    k = np.zeros((n_s, 5, 5))
    g_u, h_uu = local_grad[0], local_hess[0, 0]
    force[:, 0], force[:, 1] = -(g_u * c).sum(axis=1), -(g_u * s).sum(axis=1)
    k[:, 0, 0], k[:, 0, 1], k[:, 1, 1] = ((h_uu * w).sum(axis=1) for w in (cc, cs, ss))
    if local_grad.shape[0] == 2:
        g_g, h_gg, h_ug = local_grad[1], local_hess[1, 1], local_hess[0, 1]
        force[:, 3], force[:, 4] = (g_g * s).sum(axis=1), -(g_g * c).sum(axis=1)
        k[:, 3, 3], k[:, 3, 4], k[:, 4, 4] = ((h_gg * w).sum(axis=1) for w in (ss, -cs, cc))
        # T_u = -(c, s) on (x, y), T_gamma = (s, -c) on (rx, ry)
        k[:, 0, 3], k[:, 0, 4] = -(h_ug * cs).sum(axis=1), (h_ug * cc).sum(axis=1)
        k[:, 1, 3], k[:, 1, 4] = -(h_ug * ss).sum(axis=1), (h_ug * cs).sum(axis=1)
    lower = np.tril_indices(5, -1)
    k[:, lower[0], lower[1]] = k[:, lower[1], lower[0]]
    return force, k


@dataclass(frozen=True, eq=False)
class FlexibleRingState(BearingState):
    """:class:`~rotorsim.elements.rolling.state.BearingState` of the flexible-ring bearing.

    The inherited fields hold: ``force``, ``stiffness`` (exact condensed tangent),
    ``energy`` (the condensed potential ``sum_j Pi*_j`` [J], centrifugal part measured from
    ``v_r = 0``), ``element_load`` = inner-contact load ``Q_i`` [N] (eq 21a),
    ``outer_load`` = ``Q_e``, ``deflection`` = largest inner slice compression [m],
    ``contact_angle`` = 0, ``internal`` (S, N, 4) = ``[v_r, phi, w_i, w_e]`` (eq 12) and
    ``iterations`` = inner Newton iterations of the slowest roller.

    Attributes
    ----------
    ring_deflection : array (S, N, 2)
        ``[w_i, w_e]`` [m]: inner ring inwards, outer ring outwards.
    slice_load : array (S, N, K)
        Inner-contact load of each slice ``C h_k delta_ik^n`` [N].
    outer_slice_load : array (S, N, K)
        Outer-contact slice loads [N].
    local_force : array (S, N, e)
        ``P_local = [Q_e, M_e]`` of each roller (eq 25) [N, N m] (``[Q_e]`` without tilt).
    local_stiffness : array (S, N, e, e)
        ``K_local`` of each roller (eq 26).
    inner : InnerNewtonStats
        Cost and failures of the inner Newton solve.
    """

    ring_deflection: FloatArray | None = None
    slice_load: FloatArray | None = None
    outer_slice_load: FloatArray | None = None
    local_force: FloatArray | None = None
    local_stiffness: FloatArray | None = None
    inner: InnerNewtonStats | None = None
