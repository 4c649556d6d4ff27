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
    """

    force: FloatArray
    stiffness: FloatArray
    energy: FloatArray
    element_load: FloatArray
    contact_angle: FloatArray
    deflection: FloatArray

    @property
    def loaded(self) -> NDArray[np.bool_]:
        """Elements in contact, shape ``(S, N)``."""
        return np.asarray(self.element_load > 0.0)

    @property
    def n_samples(self) -> int:
        return int(self.force.shape[0])
