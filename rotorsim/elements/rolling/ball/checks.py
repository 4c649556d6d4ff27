"""Input checks of :class:`~rotorsim.elements.rolling.ball.bearing.BallBearing` and the
geometry they resolve: groove-centre distance ``A0``, radial clearance ``r_L``, moment arm
``r_j`` and cage ratio (seed 000 eqs 1-2; Harris & Kotzalas for the default ``r_j``).

Every message names the bearing (``BallBearing 'tag'``) and the offending parameter.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from rotorsim.elements.rolling import geometry
from rotorsim.errors import ModelError

if TYPE_CHECKING:
    from rotorsim.elements.rolling.ball.bearing import BallBearing

CAGES = ("rotating", "fixed")


class ResolvedGeometry(NamedTuple):
    """Geometry of a checked ball bearing, resolved from its parameters."""

    a0: float  # distance of the groove curvature centres, A0 [m]
    clearance: float  # radial clearance r_L [m]
    arm: float  # radius of the inner groove curvature centres r_j [m]
    kappa: float  # cage ratio
    sin0: float  # sin(alpha0)
    cos0: float  # cos(alpha0)
    axial0: float  # A0 sin(alpha0): unloaded axial groove-centre offset [m]
    radial0: float  # A0 cos(alpha0) - r_L: unloaded radial offset [m]


def resolve_geometry(bearing: BallBearing) -> ResolvedGeometry:
    """Check the parameters of ``bearing`` and resolve its geometry.

    Raises
    ------
    ModelError
        For a parameter out of range (the message names it and the bearing).
    TypeError
        For an unknown ``cage``.
    """
    b, where = bearing, bearing.label
    if (isinstance(b.n_balls, bool) or not isinstance(b.n_balls, int | np.integer)
            or b.n_balls < 1):
        raise ModelError(f"n_balls must be an integer >= 1, got {b.n_balls!r}", where)
    for key in ("pitch_diameter", "ball_diameter", "Kn", "contact_angle", "exponent",
                "psi0"):
        finite_number(getattr(b, key), key, where)
    if not 0.0 < b.ball_diameter < b.pitch_diameter:
        raise ModelError(f"ball_diameter {b.ball_diameter} m must be in (0, "
                         f"pitch_diameter {b.pitch_diameter} m)", where)
    if b.Kn <= 0:
        raise ModelError(f"Kn must be positive, got {b.Kn}", where)
    if b.exponent < 1.0:
        raise ModelError(f"exponent must be >= 1 (3/2 for balls; below 1 the contact "
                         f"stiffness is infinite at first contact), got {b.exponent}",
                         where)
    if not 0.0 <= b.contact_angle <= 0.5 * math.pi:
        raise ModelError(f"contact_angle {b.contact_angle} rad "
                         f"({math.degrees(b.contact_angle):.4g} deg) outside "
                         "[0, 90] deg (give it in radians)", where)
    if b.cage not in CAGES:
        raise TypeError(f"{where}: cage must be one of {CAGES}, got {b.cage!r}")
    a0 = _resolve_a0(b, where)
    clearance = _resolve_clearance(b, where)
    arm = _resolve_arm(b, a0, where)
    kappa = (geometry.cage_ratio(b.ball_diameter, b.pitch_diameter,
                                 b.contact_angle) if b.cage == "rotating" else 0.0)
    sin0, cos0 = math.sin(b.contact_angle), math.cos(b.contact_angle)
    return ResolvedGeometry(a0, clearance, arm, kappa, sin0, cos0, a0 * sin0,
                            a0 * cos0 - clearance)


def _resolve_a0(b: BallBearing, where: str) -> float:
    """``A0`` [m] from ``A0`` or ``(f_i + f_o - 1) d`` (consistent when both are given)."""
    if (b.f_i is None) != (b.f_o is None):
        raise ModelError("give both groove curvature factors f_i and f_o", where)
    from_f = None
    if b.f_i is not None and b.f_o is not None:
        for key in ("f_i", "f_o"):
            value = finite_number(getattr(b, key), key, where)
            if value <= 0.5:
                raise ModelError(f"{key} = {value} must be > 0.5 (groove radius larger "
                                 "than the ball radius)", where)
        from_f = (b.f_i + b.f_o - 1.0) * b.ball_diameter
    if b.A0 is None:
        if from_f is None:
            raise ModelError("give A0 or the groove curvature factors f_i and f_o", where)
        return from_f
    a0 = finite_number(b.A0, "A0", where)
    if not 0.0 < a0 < b.ball_diameter:
        raise ModelError(f"A0 = {a0} m must be in (0, ball_diameter)", where)
    if from_f is not None and not math.isclose(a0, from_f, rel_tol=1e-9):
        raise ModelError(f"A0 = {a0} m disagrees with (f_i + f_o - 1) d = {from_f} m",
                         where)
    return a0


def _resolve_clearance(b: BallBearing, where: str) -> float:
    """Radial clearance ``r_L`` [m] from the radial or the diametral clearance."""
    radial = b.radial_clearance
    diametral = b.diametral_clearance
    if radial is None:
        radial = 0.0 if diametral is None else 0.5 * finite_number(diametral,
                                                                     "diametral_clearance",
                                                                     where)
    else:
        finite_number(radial, "radial_clearance", where)
        if diametral is not None and not math.isclose(2.0 * radial, diametral,
                                                      rel_tol=1e-9, abs_tol=1e-15):
            raise ModelError(f"diametral_clearance {diametral} m must equal 2 x "
                             f"radial_clearance {radial} m (give one of them)", where)
    if abs(radial) >= 0.5 * b.ball_diameter:
        raise ModelError(f"radial clearance {radial} m exceeds the ball radius: check "
                         "the units (metres)", where)
    problem = geometry.interference_problem(radial, b.ball_diameter, "ball")
    if problem is not None:
        raise ModelError(problem, where)
    return float(radial)


def _resolve_arm(b: BallBearing, a0: float, where: str) -> float:
    """Moment arm ``r_j`` [m]: given, ``"pitch"`` (``d_m/2``, ISO/TS 16281), or
    ``d_m/2 + (f_i - 1/2) d cos(alpha0)``."""
    if isinstance(b.groove_center_radius, str):
        if b.groove_center_radius != "pitch":
            raise ModelError(f"groove_center_radius must be a length [m] or 'pitch', got "
                             f"{b.groove_center_radius!r}", where)
        return 0.5 * b.pitch_diameter
    if b.groove_center_radius is not None:
        arm = finite_number(b.groove_center_radius, "groove_center_radius", where)
        if arm <= 0:
            raise ModelError(f"groove_center_radius must be positive, got {arm}", where)
        return arm
    offset = 0.5 * a0 if b.f_i is None else (b.f_i - 0.5) * b.ball_diameter
    return 0.5 * b.pitch_diameter + offset * math.cos(b.contact_angle)


def finite_number(value: object, key: str, where: str) -> float:
    """``value`` as a finite float; :class:`ModelError` naming ``key`` otherwise."""
    if isinstance(value, str | bytes | bool):  # SI numbers only; units are read at the edges
        raise ModelError(f"{key} must be a number, got {value!r}", where)
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ModelError(f"{key} must be a number, got {value!r}", where) from None
    if not math.isfinite(number):
        raise ModelError(f"{key} must be finite, got {value!r}", where)
    return number
