"""Batched output of a rolling-bearing model at given relative displacements."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

RELATIVE_DOFS = ("x", "y", "z", "rx", "ry")
"""The 5 relative DOFs of a bearing, ``delta = u_inner - u_outer`` (DESIGN section 3)."""


@dataclass(frozen=True, eq=False)
class BearingState:
    """Forces, tangent and per-element quantities for ``S`` samples of ``N`` elements.

    Attributes
    ----------
    force : array (S, 5)
        Restoring force of the bearing on the inner ring's DOFs, ``F = dU/d delta``
        [N, N m]: at static equilibrium it equals the external load applied to the inner
        ring (seed 000 eqs 4-5 and 10-11).
    stiffness : array (S, 5, 5)
        ``dF/d delta`` (exact analytic tangent; the Hessian of ``energy``).
    energy : array (S,)
        Elastic strain energy ``U`` of all contacts [J] (seed 000 eqs 14-15, 21-22).
    element_load : array (S, N)
        Normal contact load ``Q_j`` of each rolling element [N] (rollers: summed over the
        length).
    contact_angle : array (S, N)
        Loaded contact angle ``alpha_j`` [rad].
    deflection : array (S, N)
        Contact deflection ``delta_j`` [m] (rollers: the largest along the length), 0 when
        unloaded.
    contact_direction : array (S, N, 5), optional
        Unit-load direction ``g_j = dF/dQ_j`` of each element in the 5 relative DOFs [-, m]
        (force per unit contact load): ``force = sum_j Q_j g_j`` exactly. Balls:
        ``(cos a cos psi, cos a sin psi, sin a, r sin a sin psi, -r sin a cos psi)``
        (seed 000 eq 4); rollers: ``(cos a0 cos psi, cos a0 sin psi, sin a0,
        (r_p sin a0 - e_j) sin psi, -(r_p sin a0 - e_j) cos psi)`` (seed 000 eq 10).
        ``None`` when a model does not provide it.
    element_stiffness : array (S, N), optional
        Contact stiffness of each element [N/m]: balls ``dQ_j/d delta_j =
        n Kn delta_j^(n-1)``; rollers ``dQ_j/dV_j = n Kn int delta^(n-1) dxi``, the
        derivative of the roller load with respect to a uniform approach ``V_j``. 0 when
        unloaded; ``None`` when not provided.
    outer_load : array (S, N), optional
        Load of the outer-ring contact [N] when it differs from the inner one (rolling
        elements with their centrifugal force,
        :class:`~rotorsim.elements.rolling.centrifugal.CentrifugalBearing`); ``None`` when
        both contacts carry ``element_load``.
    outer_contact_angle : array (S, N), optional
        Contact angle of the outer-ring contact [rad] (balls with centrifugal force);
        ``None`` when equal to ``contact_angle``.
    internal : array (S, N, 2), optional
        Converged internal DOFs of the rolling elements (centrifugal models: the position
        of each element between the rings), to warm-start the next evaluation; ``None``
        for models without internal DOFs.
    iterations : int, optional
        Newton iterations spent on the internal DOFs (the most any element needed).
    """

    force: FloatArray
    stiffness: FloatArray
    energy: FloatArray
    element_load: FloatArray
    contact_angle: FloatArray
    deflection: FloatArray
    contact_direction: FloatArray | None = None
    element_stiffness: FloatArray | None = None
    outer_load: FloatArray | None = None
    outer_contact_angle: FloatArray | None = None
    internal: FloatArray | None = None
    iterations: int | None = None

    @property
    def loaded(self) -> NDArray[np.bool_]:
        """Elements in contact, shape ``(S, N)``."""
        return np.asarray(self.element_load > 0.0)

    @property
    def n_samples(self) -> int:
        return int(self.force.shape[0])
