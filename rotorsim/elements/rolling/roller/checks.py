"""Input checks of :class:`~rotorsim.elements.rolling.roller.bearing.RollerBearing`: clearance, load
constant and options (each raises a :class:`~rotorsim.errors.ModelError` or ``TypeError``
naming the bearing)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorsim.elements.rolling.contact.hertz_line import LINE_EXPONENT, iso_roller_constant
from rotorsim.elements.rolling.geometry import interference_problem
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    StraightProfile,
)
from rotorsim.errors import ModelError

ROLLER_MODELS = ("tilt_integral", "slices", "influence")
"""Names of the roller contact models."""

SLICE_MODELS = ("independent", "influence")
"""Slice load laws of the post-processing (:meth:`RollerBearing.slice_loads`)."""
CAGE_LAWS = ("rotating", "fixed")
"""Cage laws: ``"rotating"`` (inner ring turns, outer fixed) or ``"fixed"`` rollers."""


def finite_number(value: Any) -> bool:
    """True for a finite real number (not a bool or a string such as ``"7.5 mm"``)."""
    return (isinstance(value, int | float | np.number) and not isinstance(value, bool)
            and math.isfinite(value))


def resolve_clearance(b: Any, where: str) -> float:
    """The radial clearance ``r_L`` [m] from ``radial_clearance`` or
    ``diametral_clearance`` (consistent when both are given)."""
    radial, diametral = b.radial_clearance, b.diametral_clearance
    for name, value in (("radial_clearance", radial), ("diametral_clearance", diametral)):
        if value is not None and not finite_number(value):
            raise ModelError(f"{name} must be finite, got {value!r}", where)
    if radial is None:
        radial = 0.0 if diametral is None else 0.5 * diametral
    elif diametral is not None and not math.isclose(2.0 * radial, diametral,
                                                    rel_tol=1e-9, abs_tol=1e-15):
        raise ModelError(f"diametral_clearance {diametral} m must equal 2 x "
                         f"radial_clearance {radial} m (give one of them)", where)
    if b.roller_diameter is None:  # the plausibility bounds scale with the diameter
        return float(radial)
    if abs(radial) >= 0.5 * b.roller_diameter:
        raise ModelError(f"radial clearance {radial} m exceeds the roller radius: check "
                         "the units (metres)", where)
    problem = interference_problem(radial, b.roller_diameter, "roller")
    if problem is not None:
        raise ModelError(problem, where)
    return float(radial)


def resolve_kn(b: Any, where: str) -> float:
    """The whole-roller constant: given, or ISO/TS 16281 for the 10/9 law."""
    if b.Kn is None:
        if abs(b.exponent - LINE_EXPONENT) > 1e-12:
            raise ModelError("Kn must be given when exponent is not 10/9 (the ISO/TS 16281 "
                             "default is a 10/9 law)", where)
        return float(iso_roller_constant(b.effective_length))
    if not (finite_number(b.Kn) and b.Kn > 0.0):
        raise ModelError(f"Kn must be positive and finite, got {b.Kn!r}", where)
    return float(b.Kn)


def check_options(b: Any, where: str) -> None:
    """Model, cage law, profile, slices and ``psi0``."""
    if b.model not in ROLLER_MODELS:
        raise TypeError(f"{where}: unknown model {b.model!r}; valid: {ROLLER_MODELS}")
    if getattr(b, "slice_model", "independent") not in SLICE_MODELS:
        raise TypeError(f"{where}: unknown slice_model {b.slice_model!r}; valid: "
                        f"{SLICE_MODELS}")
    if b.cage not in CAGE_LAWS:
        raise TypeError(f"{where}: unknown cage {b.cage!r}; valid: {CAGE_LAWS}")
    if not isinstance(b.profile, StraightProfile | CircularCrown | LogarithmicProfile):
        raise TypeError(f"{where}: profile must be a StraightProfile, CircularCrown or "
                        f"LogarithmicProfile, got {type(b.profile).__name__}")
    b.profile.validate(b.effective_length, where)
    if b.model == "tilt_integral" and not b.profile.is_straight:
        raise ModelError("the tilt-integral model (seed 000 eqs 6-11) needs a straight "
                         "profile; use model='slices' for crowned or logarithmic rollers",
                         where)
    if isinstance(b.n_slices, bool) or not isinstance(b.n_slices, int | np.integer) \
            or b.n_slices < 1:
        raise ModelError(f"n_slices must be an integer >= 1, got {b.n_slices!r}", where)
    if b.model == "influence":
        if b.roller_diameter is None:
            raise ModelError("roller_diameter is needed for model='influence' (the Hertz "
                             "strip widths of the half-space slices)", where)
        pressure = getattr(b, "influence_pressure", 1.5e9)
        if not (finite_number(pressure) and pressure > 0.0):
            raise ModelError(f"influence_pressure must be positive and finite [Pa], got "
                             f"{pressure!r}", where)
    if not finite_number(b.psi0):
        raise ModelError(f"psi0 must be finite, got {b.psi0!r}", where)
