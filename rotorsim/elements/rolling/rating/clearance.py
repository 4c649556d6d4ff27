"""Mounted and operating clearance: interference fits, ring temperatures, centrifugal growth.

The diametral clearance ``P_d = D_o - D_i - 2 D_w`` of a radial bearing (outer and inner
raceway diameters, rolling-element diameter) changes when the bearing is mounted and run:

    P_d,op = P_d - dD_i,fit - dD_o,fit + (a_o dT_o D_o - a_i dT_i D_i - 2 a_e dT_e D_w)
             - dD_i,rot

* **Fits** (thick-walled cylinders, Lame, plane stress; Harris & Kotzalas, *Essential
  Concepts of Bearing Technology*, 5th ed., ch. 5 "Bearing fits"). The inner ring (bore
  ``d``, raceway ``D_i``) on a shaft of bore ``d_0`` with diametral interference ``I_i``::

      p_i = I_i / (d [((D_i^2 + d^2)/(D_i^2 - d^2) + nu_r)/E_r
                      + ((d^2 + d_0^2)/(d^2 - d_0^2) - nu_s)/E_s])
      dD_i,fit = 2 p_i d^2 D_i / (E_r (D_i^2 - d^2))         (raceway expansion)

  and the outer ring (outside diameter ``D``, raceway ``D_o``) in a housing of outside
  diameter ``D_h`` with interference ``I_o``::

      p_o = I_o / (D [((D^2 + D_o^2)/(D^2 - D_o^2) - nu_r)/E_r
                      + ((D_h^2 + D^2)/(D_h^2 - D^2) + nu_h)/E_h])
      dD_o,fit = 2 p_o D^2 D_o / (E_r (D^2 - D_o^2))         (raceway contraction)

  For a solid shaft of the ring's material ``dD_i,fit = I_i d / D_i`` exactly, and for a
  rigid-walled (infinite) housing of the ring's material ``dD_o,fit = I_o D_o / D``: the
  "reduction factors" of the catalogues (SKF: ``dr = I_1 f_1 + I_2 f_2``). The ring is
  taken as a plain cylinder from its bore (outside diameter) to the raceway diameter (the
  groove and shoulders are not modelled; Harris takes the same equivalent ring).
* **Temperatures** ``dT`` above the mounting temperature, with expansion coefficients
  ``a``: free rings and rolling elements scale their diameters by ``1 + a dT`` (the
  bracket above), and the fits change with the temperatures of shaft and housing::

      I_i(dT) = I_i + d (a_s dT_s - a_i dT_i),    I_o(dT) = I_o + D (a_o dT_o - a_h dT_h)

  (a fit that opens, ``I < 0``, no longer presses).
* **Centrifugal growth of the turning inner ring** (free rotating annulus, plane stress;
  Timoshenko & Goodier, *Theory of Elasticity*, sec. 32)::

      dD_i,rot = rho W^2 (D_i/2) / (2 E_r) ((1 - nu_r) (D_i/2)^2 + (3 + nu_r) (d/2)^2)

  (an upper bound for a ring held by an interference fit, which the shaft's own growth
  partly follows).

Units: SI (m, Pa, 1/K, K, rad/s, kg/m^3). The result is the diametral clearance the contact
models take (``diametral_clearance`` of ``BallBearing`` and ``RollerBearing``);
:func:`with_operating_clearance` returns the model with it.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from rotorsim.errors import ModelError

STEEL_EXPANSION = 11.5e-6
"""Linear expansion coefficient of bearing steel [1/K] (100Cr6, 20-100 C)."""
_STEEL_E, _STEEL_NU, _STEEL_RHO = 2.08e11, 0.3, 7850.0


@dataclass(frozen=True)
class MountingConditions:
    """Fits, temperatures and speed of a mounted bearing (module docstring).

    Parameters
    ----------
    bore, outside_diameter : float
        Ring bore ``d`` and outside diameter ``D`` [m].
    shaft_interference, housing_interference : float
        Diametral interferences ``I_i``, ``I_o`` [m] at mounting temperature (negative =
        loose fit).
    shaft_bore : float
        ``d_0`` [m] of a hollow shaft (0 solid).
    housing_outside_diameter : float
        ``D_h`` [m] (``inf``: a thick housing).
    inner_temperature, outer_temperature, element_temperature : float
        Temperature rises ``dT_i, dT_o, dT_e`` [K] of the rings and rolling elements above
        the mounting temperature (``element_temperature`` default: the mean of the rings).
    shaft_temperature, housing_temperature : float, optional
        ``dT_s, dT_h`` [K] (default: those of the inner and outer ring).
    speed : float
        Speed of the inner ring [rad/s] (centrifugal growth).
    E_ring, nu_ring, E_shaft, nu_shaft, E_housing, nu_housing : float
        Elastic constants [Pa, -] (default bearing steel 208 GPa, 0.3).
    expansion_ring, expansion_element, expansion_shaft, expansion_housing : float
        Linear expansion coefficients [1/K] (default bearing steel).
    density_ring : float
        [kg/m^3].
    """

    bore: float
    outside_diameter: float
    shaft_interference: float = 0.0
    housing_interference: float = 0.0
    shaft_bore: float = 0.0
    housing_outside_diameter: float = math.inf
    inner_temperature: float = 0.0
    outer_temperature: float = 0.0
    element_temperature: float | None = None
    shaft_temperature: float | None = None
    housing_temperature: float | None = None
    speed: float = 0.0
    E_ring: float = _STEEL_E
    nu_ring: float = _STEEL_NU
    E_shaft: float = _STEEL_E
    nu_shaft: float = _STEEL_NU
    E_housing: float = _STEEL_E
    nu_housing: float = _STEEL_NU
    expansion_ring: float = STEEL_EXPANSION
    expansion_element: float = STEEL_EXPANSION
    expansion_shaft: float = STEEL_EXPANSION
    expansion_housing: float = STEEL_EXPANSION
    density_ring: float = _STEEL_RHO

    def __post_init__(self) -> None:
        where = "MountingConditions"
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is None:
                continue
            if isinstance(value, bool) or not isinstance(value, int | float) \
                    or math.isnan(value) or (math.isinf(value)
                                             and f.name != "housing_outside_diameter"):
                raise ModelError(f"{f.name} must be a finite number, got {value!r}", where)
        for key in ("bore", "outside_diameter", "E_ring", "E_shaft", "E_housing",
                    "density_ring"):
            if getattr(self, key) <= 0:
                raise ModelError(f"{key} must be > 0, got {getattr(self, key)!r}", where)
        if not 0 <= self.shaft_bore < self.bore:
            raise ModelError(f"shaft_bore must be in [0, bore = {self.bore}) m, got "
                             f"{self.shaft_bore!r}", where)
        if not self.bore < self.outside_diameter < self.housing_outside_diameter:
            raise ModelError("need bore < outside_diameter < housing_outside_diameter, got "
                             f"{self.bore}, {self.outside_diameter}, "
                             f"{self.housing_outside_diameter} m", where)


@dataclass(frozen=True)
class ClearanceChange:
    """Diametral clearances [m] of a mounted, running bearing and what changed them.

    Attributes
    ----------
    unmounted, mounted, operating : float
        ``P_d`` as delivered, after the fits (mounting temperature, at rest), and at the
        operating temperatures and speed (negative = preload).
    inner_fit, outer_fit : float
        Raceway expansion of the inner ring and contraction of the outer ring by the fits
        at operating temperature (mounted: at mounting temperature, ``mounted`` uses those).
    thermal : float
        Change of ``P_d`` by the free thermal growth of rings and elements.
    centrifugal : float
        Inner raceway growth by rotation.
    fit_pressures : (float, float)
        Contact pressures ``p_i, p_o`` [Pa] of the fits at operating temperature.
    """

    unmounted: float
    mounted: float
    operating: float
    inner_fit: float
    outer_fit: float
    thermal: float
    centrifugal: float
    fit_pressures: tuple[float, float]


def inner_fit_expansion(interference: float, bore: float, raceway: float,
                        shaft_bore: float = 0.0, E_ring: float = _STEEL_E,
                        nu_ring: float = _STEEL_NU, E_shaft: float = _STEEL_E,
                        nu_shaft: float = _STEEL_NU) -> tuple[float, float]:
    """Inner raceway expansion [m] and fit pressure [Pa] (module docstring; ``I <= 0``: 0).

    Examples
    --------
    >>> round(inner_fit_expansion(20e-6, 0.05, 0.0625)[0] * 1e6, 6)  # I d / D_i
    16.0
    """
    if interference <= 0.0:
        return 0.0, 0.0
    d2, r2, s2 = bore**2, raceway**2, shaft_bore**2
    compliance = ((r2 + d2) / (r2 - d2) + nu_ring) / E_ring \
        + ((d2 + s2) / (d2 - s2) - nu_shaft) / E_shaft
    p = interference / (bore * compliance)
    return 2.0 * p * d2 * raceway / (E_ring * (r2 - d2)), p


def outer_fit_contraction(interference: float, outside_diameter: float, raceway: float,
                          housing_outside_diameter: float = math.inf,
                          E_ring: float = _STEEL_E, nu_ring: float = _STEEL_NU,
                          E_housing: float = _STEEL_E, nu_housing: float = _STEEL_NU
                          ) -> tuple[float, float]:
    """Outer raceway contraction [m] and fit pressure [Pa] (module docstring).

    Examples
    --------
    >>> round(outer_fit_contraction(20e-6, 0.09, 0.0775)[0] * 1e6, 6)  # I D_o / D
    17.222222
    """
    if interference <= 0.0:
        return 0.0, 0.0
    o2, r2 = outside_diameter**2, raceway**2
    housing = 1.0 if math.isinf(housing_outside_diameter) else \
        (housing_outside_diameter**2 + o2) / (housing_outside_diameter**2 - o2)
    compliance = ((o2 + r2) / (o2 - r2) - nu_ring) / E_ring + (housing + nu_housing) / E_housing
    p = interference / (outside_diameter * compliance)
    return 2.0 * p * o2 * raceway / (E_ring * (o2 - r2)), p


def centrifugal_expansion(speed: float, bore: float, raceway: float,
                          E_ring: float = _STEEL_E, nu_ring: float = _STEEL_NU,
                          density: float = _STEEL_RHO) -> float:
    """Raceway diameter growth [m] of a free inner ring turning at ``speed`` [rad/s]."""
    c, b = 0.5 * raceway, 0.5 * bore
    return density * speed**2 * c / (2.0 * E_ring) * ((1 - nu_ring) * c**2
                                                      + (3 + nu_ring) * b**2)


def operating_clearance(diametral_clearance: float, inner_raceway: float,
                        outer_raceway: float, element_diameter: float,
                        conditions: MountingConditions) -> ClearanceChange:
    """Mounted and operating diametral clearance (module docstring).

    Parameters
    ----------
    diametral_clearance : float
        Unmounted ``P_d`` [m] (catalogue radial internal clearance).
    inner_raceway, outer_raceway : float
        Raceway diameters ``D_i``, ``D_o`` [m].
    element_diameter : float
        ``D_w`` [m].
    conditions : MountingConditions

    Examples
    --------
    >>> c = MountingConditions(bore=0.05, outside_diameter=0.09, shaft_interference=20e-6)
    >>> round(operating_clearance(30e-6, 0.0625, 0.0775, 0.0075, c).mounted * 1e6, 6)
    14.0
    """
    k = conditions
    if not (0 < k.bore < inner_raceway < outer_raceway < k.outside_diameter):
        raise ModelError("need bore < inner_raceway < outer_raceway < outside_diameter, got "
                         f"{k.bore}, {inner_raceway}, {outer_raceway}, "
                         f"{k.outside_diameter} m", "operating_clearance")
    t_e = 0.5 * (k.inner_temperature + k.outer_temperature) \
        if k.element_temperature is None else k.element_temperature
    t_s = k.inner_temperature if k.shaft_temperature is None else k.shaft_temperature
    t_h = k.outer_temperature if k.housing_temperature is None else k.housing_temperature
    inner = {"bore": k.bore, "raceway": inner_raceway, "shaft_bore": k.shaft_bore,
             "E_ring": k.E_ring, "nu_ring": k.nu_ring, "E_shaft": k.E_shaft,
             "nu_shaft": k.nu_shaft}
    outer = {"outside_diameter": k.outside_diameter, "raceway": outer_raceway,
             "housing_outside_diameter": k.housing_outside_diameter, "E_ring": k.E_ring,
             "nu_ring": k.nu_ring, "E_housing": k.E_housing, "nu_housing": k.nu_housing}
    mounted = diametral_clearance - inner_fit_expansion(k.shaft_interference, **inner)[0] \
        - outer_fit_contraction(k.housing_interference, **outer)[0]
    i_i = k.shaft_interference + k.bore * (k.expansion_shaft * t_s
                                           - k.expansion_ring * k.inner_temperature)
    i_o = k.housing_interference + k.outside_diameter * (
        k.expansion_ring * k.outer_temperature - k.expansion_housing * t_h)
    inner_fit, p_i = inner_fit_expansion(i_i, **inner)
    outer_fit, p_o = outer_fit_contraction(i_o, **outer)
    thermal = k.expansion_ring * (k.outer_temperature * outer_raceway
                                  - k.inner_temperature * inner_raceway) \
        - 2.0 * k.expansion_element * t_e * element_diameter
    rot = centrifugal_expansion(k.speed, k.bore, inner_raceway, k.E_ring, k.nu_ring,
                                k.density_ring)
    return ClearanceChange(
        unmounted=diametral_clearance, mounted=mounted,
        operating=diametral_clearance - inner_fit - outer_fit + thermal - rot,
        inner_fit=inner_fit, outer_fit=outer_fit, thermal=thermal, centrifugal=rot,
        fit_pressures=(p_i, p_o))


def raceway_diameters(model: Any) -> tuple[float, float, float]:
    """``D_i, D_o, D_w`` [m] of a ``BallBearing`` or ``RollerBearing``: ``d_m -/+ D_w cos a``."""
    diameter = float(getattr(model, "ball_diameter", None)
                     or model.diameter_for("the operating clearance"))
    spread = diameter * math.cos(float(model.contact_angle))
    return model.pitch_diameter - spread, model.pitch_diameter + spread, diameter


def with_operating_clearance(model: Any, conditions: MountingConditions
                             ) -> tuple[Any, ClearanceChange]:
    """The ``BallBearing`` or ``RollerBearing`` with its operating clearance, and the change.

    The model's clearance is taken as the unmounted one; the copy has
    ``diametral_clearance`` = the operating clearance (``radial_clearance`` half of it).

    Examples
    --------
    >>> from rotorsim.elements.rolling.ball.bearing import BallBearing
    >>> b = BallBearing(n_balls=9, pitch_diameter=0.07, ball_diameter=0.0075, Kn=8e9,
    ...                 A0=0.3e-3, diametral_clearance=30e-6)
    >>> c = MountingConditions(bore=0.05, outside_diameter=0.09, shaft_interference=20e-6)
    >>> mounted, change = with_operating_clearance(b, c)
    >>> round(mounted.clearance * 2e6, 6)
    14.0
    """
    d_i, d_o, d_w = raceway_diameters(model)
    change = operating_clearance(2.0 * float(model.clearance), d_i, d_o, d_w, conditions)
    return dataclasses.replace(model, radial_clearance=None,
                               diametral_clearance=change.operating), change
