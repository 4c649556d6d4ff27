"""The line load along the rollers of a :class:`~rotorsim.elements.rolling.roller.bearing.
RollerBearing`, for its contact model.

A roller with the centre approach ``V`` and tilt ``L omega`` has the deflection
``delta(xi) = V + xi L omega - c(xi)`` along its length. ``"tilt_integral"`` integrates the
line load of the straight roller in closed form between the limits of its loaded zone
(seed 000 eqs 7-9, 22-23); ``"slices"`` sums ``K`` slices at their centres ``xi_k``, with
the profile drop ``c(xi_k)`` (seed 002 eqs 2.7, 2.12-2.13); ``"influence"`` couples the
same slices by the half-space (:mod:`~rotorsim.elements.rolling.roller.influence_model`).
All give the
:class:`~rotorsim.elements.rolling.roller.integrals.LineIntegrals` the bearing needs.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from rotorsim.elements.rolling.contact.line_integrals import (
    _slice_sums,
    _tilted,
    line_moments,
    slice_weights,
    tilted_line_integrals,
)
from rotorsim.elements.rolling.roller.influence_model import InfluenceSlices
from rotorsim.elements.rolling.roller.integrals import LineIntegrals
from rotorsim.elements.rolling.roller.profile import RollerProfile, slice_centres
from rotorsim.elements.rolling.state import FloatArray


@dataclass(frozen=True, eq=False)
class RollerLineLoad:
    """Integrals of the line load ``delta^n`` along the rollers, by contact model.

    Parameters
    ----------
    model : {"tilt_integral", "slices", "influence"}
        Closed-form integrals of a straight roller, sums over ``n_slices`` independent
        slices, or slices coupled by the half-space (``influence``).
    exponent : float
        Load-deflection exponent ``n``.
    n_slices : int
        Number of slices ``K`` (slice sums, and the points of :meth:`slice_deflection`).
    profile : RollerProfile
        Roller profile; its drop relieves the slices.
    length : float
        Effective roller length ``L`` [m].
    influence : InfluenceSlices, optional
        The coupled-slice model (required by ``model="influence"``).
    """

    model: str
    exponent: float
    n_slices: int
    profile: RollerProfile
    length: float
    influence: InfluenceSlices | None = None

    @cached_property
    def xi(self) -> FloatArray:
        """Slice centres ``xi_k`` (K,)."""
        return slice_centres(int(self.n_slices))

    @cached_property
    def drop(self) -> FloatArray:
        """Profile drop ``c(xi_k)`` at the slice centres (K,) [m]."""
        return self.profile.drop(self.xi, self.length)

    @cached_property
    def weights(self) -> FloatArray:
        """Midpoint-rule weights of the slice sums (K, 3), read-only."""
        weights = slice_weights(self.xi)
        weights.flags.writeable = False
        return weights

    def integrals(self, v: FloatArray, lw: FloatArray, energy_only: bool = False
                  ) -> LineIntegrals:
        """:class:`LineIntegrals` (..., Z) of the rollers with centre deflection ``v`` and
        tilt ``lw`` (..., Z) [m]; ``energy_only``: only the energy (the rest zeros)."""
        n = float(self.exponent)
        if self.model == "tilt_integral":
            return LineIntegrals(*tilted_line_integrals(v, lw, n, energy_only))
        if self.influence is not None:
            return self.influence.integrals(self.slice_deflection(v, lw), energy_only)
        return LineIntegrals(*line_moments(self.slice_deflection(v, lw), self.xi, n,
                                           energy_only))

    def load_integrals(self, v: FloatArray, lw: FloatArray) -> tuple[FloatArray, ...]:
        """``int delta^n``, ``int xi delta^n`` and ``int xi^p delta^(n-1)`` (p = 0, 1, 2)
        (..., Z) of :meth:`integrals`, without the energy and the peak deflection."""
        n = float(self.exponent)
        if self.model == "tilt_integral":
            return _tilted(v, lw, n, True, False)[1:6]
        if self.influence is not None:
            return tuple(self.influence.integrals(self.slice_deflection(v, lw))[1:6])
        return _slice_sums(self.slice_deflection(v, lw), self.weights, n, False)[1:6]

    def slice_deflection(self, v: FloatArray, lw: FloatArray) -> FloatArray:
        """``V + xi_k L omega - c(xi_k)`` at the slice centres (..., Z, K) [m]."""
        return np.asarray(v[..., None] + lw[..., None] * self.xi - self.drop)
