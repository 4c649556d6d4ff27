"""Input checks of :class:`~rotorsim.elements.rolling.flexible_ring.bearing.
FlexibleRingRollerBearing`, and its ring sections resolved from the bore and housing radii
(seed 001 Fig. 3a).

Every message names the bearing (``FlexibleRingRollerBearing 'tag'``) and the parameter.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorsim.elements.rolling.flexible_ring.geometry import RingSection, line_contact_constant
from rotorsim.elements.rolling.geometry import interference_problem
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    StraightProfile,
)
from rotorsim.errors import ModelError

if TYPE_CHECKING:
    from rotorsim.elements.rolling.flexible_ring.bearing import FlexibleRingRollerBearing

CAGE_LAWS = ("rotating", "fixed")
"""Roller placement: cage turning at ``kappa phi`` or rollers held at ``psi0 + 2 pi j/N``."""


def number(value: Any, name: str, where: str, *, positive: bool = False) -> float:
    """``value`` as a float; :class:`ModelError` naming ``name`` unless it is a finite (and
    with ``positive``, positive) real number."""
    ok = not isinstance(value, bool) and isinstance(value, int | float | np.floating) \
        and math.isfinite(value) and (value > 0.0 or not positive)
    if not ok:
        kind = "a positive finite" if positive else "a finite"
        raise ModelError(f"{name} must be {kind} number, got {value!r}", where)
    return float(value)


def check_parameters(b: FlexibleRingRollerBearing) -> None:
    """Check every parameter of ``b`` (the slicing, the rings and the inner Newton options
    through the properties that resolve them).

    Raises
    ------
    ModelError
        For a value out of range.
    TypeError
        For an unknown cage law or profile type.
    """
    where = b.label
    if isinstance(b.n_rollers, bool) or not isinstance(b.n_rollers, int | np.integer) \
            or b.n_rollers < 1:
        raise ModelError(f"n_rollers must be an integer >= 1, got {b.n_rollers!r}", where)
    r_p = number(b.pitch_radius, "pitch_radius", where, positive=True)
    r_b = number(b.roller_radius, "roller_radius", where, positive=True)
    number(b.effective_length, "effective_length", where, positive=True)
    if r_b >= r_p:
        raise ModelError(f"roller_radius {r_b} m must be smaller than pitch_radius {r_p} m",
                         where)
    g = number(b.diametral_clearance, "diametral_clearance", where)
    if abs(g) >= r_b:
        raise ModelError(f"diametral_clearance {g} m exceeds the roller radius: check the "
                         "units (metres)", where)
    problem = interference_problem(0.5 * g, 2.0 * r_b, "roller")
    if problem is not None:
        raise ModelError(problem, where)
    for name in ("E", "rho"):
        number(getattr(b, name), name, where, positive=True)
    for name in ("ring_modulus", "roller_mass", "contact_constant", "cage_ratio"):
        if getattr(b, name) is not None:
            number(getattr(b, name), name, where, positive=name != "cage_ratio")
    if number(b.exponent, "exponent", where) < 1.0:
        raise ModelError(f"exponent must be >= 1, got {b.exponent!r}", where)
    for name in ("psi0", "speed"):
        number(getattr(b, name), name, where)
    if b.cage not in CAGE_LAWS:
        raise TypeError(f"{where}: unknown cage {b.cage!r}; valid: {CAGE_LAWS}")
    if not isinstance(b.profile, StraightProfile | CircularCrown | LogarithmicProfile):
        raise TypeError(f"{where}: profile must be a StraightProfile, CircularCrown or "
                        f"LogarithmicProfile, got {type(b.profile).__name__}")
    b.slices  # noqa: B018 - validates the slicing
    b.sections  # noqa: B018 - validates the rings
    b.newton  # noqa: B018 - validates tol and max_iter
    line_contact_constant(b.E, b.nu, b.effective_length, b.exponent)


def ring_sections(b: FlexibleRingRollerBearing
                  ) -> tuple[RingSection | None, RingSection | None]:
    """Inner and outer ring sections of ``b``: given, or rectangular from ``shaft_radius``,
    ``housing_radius`` and ``ring_width`` (``None`` for rigid rings without geometry)."""
    where = b.label
    inner_race = b.pitch_radius - b.roller_radius
    outer_race = b.pitch_radius + b.roller_radius
    out: list[RingSection | None] = []
    for side, given, radius, race in (
            ("inner", b.inner_ring, b.shaft_radius, inner_race),
            ("outer", b.outer_ring, b.housing_radius, outer_race)):
        name = "shaft_radius" if side == "inner" else "housing_radius"
        if given is not None and radius is not None:
            raise ModelError(f"give {side}_ring or {name}, not both", where)
        if radius is not None:
            r = number(radius, name, where, positive=True)
            if side == "inner" and r >= race:
                raise ModelError(f"shaft_radius R_s = {r} m must be smaller than the inner "
                                 f"raceway radius R_p - R_b = {race:.6g} m", where)
            if side == "outer" and r <= race:
                raise ModelError(f"housing_radius R_h = {r} m must exceed the outer "
                                 f"raceway radius R_p + R_b = {race:.6g} m", where)
            if b.ring_width is None:
                raise ModelError(f"ring_width b is needed with {name}", where)
            lo, hi = (r, race) if side == "inner" else (race, r)
            given = RingSection.rectangular(lo, hi, b.ring_width, where)
        if given is None and not b.rigid_rings:
            raise ModelError(f"the {side} ring needs {name} and ring_width, or "
                             f"{side}_ring=RingSection(...) (or rigid_rings=True)", where)
        if given is not None:
            given.validate(f"{where} {side}_ring")
        out.append(given)
    return out[0], out[1]
