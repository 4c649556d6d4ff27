"""Slice and roller loads of a :class:`~rotorsim.elements.rolling.roller.bearing.RollerBearing`
by its ``slice_model``: independent slices or the half-space distribution.

Independent slices (seed 002 eqs 2.7, 2.12): ``q_k = (Kn/K) max(delta_k, 0)^n``.
``"influence"``: the same roller loads distributed along the roller by the half-space
influence coefficients (:func:`~.slice_influence.influence_slice_loads`, seed 002 section
2.3.3), which moves the roller's load centre (eccentricity) and its edge load. A bearing
with the contact model ``"influence"`` (:mod:`~.influence_model`) gives its own slice loads,
those of its force.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.rolling.contact.hertz_point import (
    BEARING_STEEL_E,
    BEARING_STEEL_NU,
    effective_modulus,
)
from rotorsim.elements.rolling.roller.integrals import RollerLoads, tilt_limits
from rotorsim.elements.rolling.roller.slice_influence import influence_slice_loads

FloatArray = NDArray[np.float64]

STEEL_E_STAR = effective_modulus(BEARING_STEEL_E, BEARING_STEEL_NU, BEARING_STEEL_E,
                                 BEARING_STEEL_NU)
"""``E*`` [Pa] of the slice influence (bearing steel on bearing steel)."""


def race_radii(bearing: Any) -> tuple[float, float]:
    """Reduced radii ``D (1 -+ gamma) / 2`` [m] of the inner and outer line contact,
    ``gamma = D cos a0 / d_m``."""
    d = bearing.diameter_for("the half-space slices (slice_model='influence')")
    gamma = d * math.cos(bearing.contact_angle) / bearing.pitch_diameter
    return (0.5 * d * (1.0 - gamma), 0.5 * d * (1.0 + gamma))


def slice_loads(bearing: Any, deflection: FloatArray) -> FloatArray:
    """Slice loads (S, Z, K) [N] of the slice deflections ``deflection`` (S, Z, K) [m] by
    the bearing's ``slice_model`` (module docstring)."""
    if bearing.model == "influence":  # the coupled-slice contact model's own loads
        return np.asarray(bearing.kn * bearing._line.influence.slice_loads(deflection))
    if bearing.slice_model == "influence":
        return influence_slice_loads(deflection, bearing.kn, float(bearing.exponent),
                                     bearing.effective_length, race_radii(bearing),
                                     STEEL_E_STAR)
    return np.asarray((bearing.kn / bearing.n_slices)
                      * np.maximum(deflection, 0.0) ** bearing.exponent)


def roller_loads(bearing: Any, v: FloatArray, lw: FloatArray) -> RollerLoads:
    """Per-roller load, eccentricity (seed 000 eq 9), loaded zone (eq 8) and slice loads at
    centre deflections ``v`` and tilts ``L omega`` (S, Z) [m]; with
    ``slice_model="influence"`` the eccentricity of the half-space distribution."""
    line = bearing._line
    ints = line.integrals(v, lw)
    q = bearing.kn * ints.load
    loaded = ints.load > 0.0
    length = bearing.effective_length
    ecc = np.where(loaded, length * ints.load_moment / np.where(loaded, ints.load, 1.0), 0.0)
    if bearing.model == "tilt_integral" and bearing.slice_model == "independent":
        return RollerLoads(q, ecc, tilt_limits(v, lw))
    xi, dk = line.xi, line.slice_deflection(v, lw)
    slice_load = slice_loads(bearing, dk)
    if bearing.slice_model == "influence":
        total = slice_load.sum(axis=-1)
        ecc = np.where(total > 0.0, length * (slice_load @ xi)
                       / np.where(total > 0.0, total, 1.0), 0.0)
    half = 0.5 / bearing.n_slices
    touching = slice_load > 0.0 if bearing.model == "influence" else dk > 0.0
    lo = np.where(touching, xi - half, np.inf).min(axis=-1)
    hi = np.where(touching, xi + half, -np.inf).max(axis=-1)
    limits = np.where(loaded[..., None], np.stack([lo, hi], axis=-1), np.nan)
    return RollerLoads(q, ecc, limits, slice_load)
