"""Hertz point contact: exact solution vs a direct Boussinesq integration, curvature
formulas, the Brewe-Hamrock fits, and the series combination of the two races."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from rotorsim.elements.rolling.contact.hertz_point import (
    ball_bearing_constant,
    contact_constant,
    effective_modulus,
    point_contact,
    race_curvature_radii,
    series_constant,
)
from rotorsim.errors import ModelError

# 6206 deep groove ball bearing (ball 9.525 mm, inner groove radius 4.89 mm, d_m 46 mm)
D, DM, F_I = 9.525e-3, 46e-3, 4.89 / 9.525


def _boussinesq_displacement(contact, x0: float, y0: float, e_star: float) -> float:
    """Surface approach at (x0, y0) under p0 sqrt(1 - x^2/b^2 - y^2/a^2), by quadrature.

    u = 1 / (pi E*) * integral p / r dA, written in polar coordinates around (x0, y0): the
    1/r cancels the area element, leaving the pressure integrated along each ray.
    """
    a, b, p0 = contact.semi_major, contact.semi_minor, contact.max_pressure

    def along_ray(theta: float) -> float:
        c, s = math.cos(theta), math.sin(theta)
        quad_c = c * c / b**2 + s * s / a**2
        lin = -2.0 * (x0 * c / b**2 + y0 * s / a**2)
        const = 1.0 - x0**2 / b**2 - y0**2 / a**2
        root = math.sqrt(lin * lin + 4.0 * const * quad_c)
        r_hi, r_lo = (lin + root) / (2.0 * quad_c), (lin - root) / (2.0 * quad_c)
        return quad(lambda r: math.sqrt(max(quad_c * (r_hi - r) * (r - r_lo), 0.0)), 0.0,
                    r_hi, epsabs=0.0, epsrel=1e-12, limit=200)[0]

    integral = quad(along_ray, 0.0, 2.0 * math.pi, epsabs=0.0, epsrel=1e-11, limit=400)[0]
    return p0 * integral / (math.pi * e_star)


@pytest.mark.validation
@pytest.mark.parametrize("race", ["inner", "outer"])
def test_exact_solution_satisfies_the_elastic_half_space_equations(race):
    """The exact Hertz ellipse must give a surface approach equal to ``delta`` at the
    centre and the parabolic gap ``x^2/(2 Rx)``, ``y^2/(2 Ry)`` inside the contact
    (Johnson, Contact Mechanics, sec. 3.5): checked by integrating the Boussinesq kernel,
    without elliptic-integral formulas."""
    rx, ry = race_curvature_radii(D, DM, 0.0, F_I if race == "inner" else 0.525, race)
    e_star = effective_modulus(2.08e11, 0.3, 2.08e11, 0.3)
    contact = point_contact(rx, ry, e_star, 500.0, method="exact")
    centre = _boussinesq_displacement(contact, 0.0, 0.0, e_star)
    assert centre == pytest.approx(contact.deflection, rel=1e-9)
    x0, y0 = 0.5 * contact.semi_minor, 0.5 * contact.semi_major
    drop_x = centre - _boussinesq_displacement(contact, x0, 0.0, e_star)
    drop_y = centre - _boussinesq_displacement(contact, 0.0, y0, e_star)
    assert drop_x == pytest.approx(x0**2 / (2.0 * rx), rel=1e-8)
    assert drop_y == pytest.approx(y0**2 / (2.0 * ry), rel=1e-8)
    assert contact.load == pytest.approx(
        2.0 / 3.0 * math.pi * contact.semi_major * contact.semi_minor * contact.max_pressure,
        rel=1e-14)


def test_sphere_limit_and_load_scaling():
    e_star, radius = 1.1e11, 0.02
    k = contact_constant(radius, radius, e_star, method="exact")
    assert k == pytest.approx(4.0 / 3.0 * e_star * math.sqrt(radius), rel=1e-12)
    small = point_contact(0.004, 0.06, e_star, 10.0)
    large = point_contact(0.004, 0.06, e_star, 80.0)
    assert large.deflection / small.deflection == pytest.approx(4.0, rel=1e-12)
    assert large.stiffness_constant == pytest.approx(small.stiffness_constant, rel=1e-12)
    swapped = point_contact(0.06, 0.004, e_star, 10.0)
    assert swapped.deflection == pytest.approx(small.deflection, rel=1e-14)


@pytest.mark.parametrize("alpha_deg", [0.0, 25.0, 40.0])
def test_race_curvatures_from_the_contact_point_radius(alpha_deg):
    """Meusnier: a race of revolution whose contact point lies at radius rho from the axis
    has the normal curvature cos(alpha) / rho in the rolling direction."""
    alpha = math.radians(alpha_deg)
    rho_inner = 0.5 * (DM - D * math.cos(alpha))
    rho_outer = 0.5 * (DM + D * math.cos(alpha))
    rx_i, ry_i = race_curvature_radii(D, DM, alpha, 0.52, "inner")
    rx_o, ry_o = race_curvature_radii(D, DM, alpha, 0.53, "outer")
    assert 1.0 / rx_i == pytest.approx(2.0 / D + math.cos(alpha) / rho_inner, rel=1e-13)
    assert 1.0 / rx_o == pytest.approx(2.0 / D - math.cos(alpha) / rho_outer, rel=1e-13)
    assert 1.0 / ry_i == pytest.approx(2.0 / D - 1.0 / (0.52 * D), rel=1e-13)
    assert 1.0 / ry_o == pytest.approx(2.0 / D - 1.0 / (0.53 * D), rel=1e-13)


@pytest.mark.validation
def test_brewe_hamrock_fits_reproduce_a_published_6206_example():
    """eng-tools.dev 'A2 Hertz contact' worked example (Hamrock-Brewe closed form): 6206,
    ball 9.525 mm, inner groove radius 4.89 mm, d_m 46 mm, E = 210 GPa, nu = 0.3, printed
    E* = 115.4 GPa, R_eq = 3.700 mm, k = 12.19, a x b = 1.368 x 0.112 mm, p0 = 1728 MPa.
    The printed load is the bearing's 1000 N radial load with 9 balls; the ball load
    Q = 5 Fr / Z = 555.6 N (Stribeck's design rule) is our reading, the one that gives
    every printed number. Tolerances: half a unit of the last printed digit."""
    e_star = effective_modulus(210e9, 0.3, 210e9, 0.3)
    rx, ry = race_curvature_radii(D, DM, 0.0, F_I, "inner")
    contact = point_contact(rx, ry, e_star, 5.0 * 1000.0 / 9.0, method="hamrock_brewe")
    assert e_star / 1e9 == pytest.approx(115.4, abs=0.05)
    assert 1e3 / (1.0 / rx + 1.0 / ry) == pytest.approx(3.700, abs=5e-4)
    assert contact.ellipticity == pytest.approx(12.19, abs=5e-3)
    assert contact.semi_major * 1e3 == pytest.approx(1.368, abs=5e-4)
    assert contact.semi_minor * 1e3 == pytest.approx(0.112, abs=5e-4)
    assert contact.max_pressure / 1e6 == pytest.approx(1728.0, abs=0.5)


def test_brewe_hamrock_fits_stay_close_to_the_exact_solution():
    """Guards the transcription of the fit constants; the bounds are the errors stated in
    the module docstring (measured against the exact solution)."""
    def error(ratio):
        return (contact_constant(1.0, ratio, 1e11, method="hamrock_brewe")
                / contact_constant(1.0, ratio, 1e11, method="exact") - 1.0)

    assert max(abs(error(r)) for r in np.geomspace(3.0, 30.0, 25)) < 0.015
    assert error(48.0) == pytest.approx(0.029, abs=1e-3)
    assert error(100.0) == pytest.approx(0.059, abs=1e-3)


def test_series_constant_adds_the_two_deflections():
    kn, k_i, k_o = ball_bearing_constant(D, DM, math.radians(15.0), 0.52, 0.53)
    load = 700.0
    assert (load / kn) ** (2 / 3) == pytest.approx((load / k_i) ** (2 / 3)
                                                   + (load / k_o) ** (2 / 3), rel=1e-13)
    assert series_constant(k_i, k_o) == kn
    assert min(k_i, k_o) > kn
    # with equal groove factors the inner (convex) race is the softer contact
    _, k_i_eq, k_o_eq = ball_bearing_constant(D, DM, math.radians(15.0), 0.52, 0.52)
    assert k_o_eq > k_i_eq
    # an outer ring of a softer material lowers K_o only
    _, k_i2, k_o2 = ball_bearing_constant(D, DM, math.radians(15.0), 0.52, 0.53,
                                          E_ring=1.1e11, nu_ring=0.33)
    assert k_o2 < k_o and k_i2 < k_i


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda: race_curvature_radii(D, DM, 0.0, 0.5, "inner"), ModelError, "> 0.5"),
    (lambda: race_curvature_radii(D, DM, 0.0, 0.52, "middle"), ModelError, "race"),
    (lambda: race_curvature_radii(DM, D, 0.0, 0.52, "inner"), ModelError, "ball diameter"),
    (lambda: race_curvature_radii(D, DM, 2.0, 0.52, "inner"), ModelError, "contact angle"),
    (lambda: point_contact(1e-3, 1e-2, 1e11, 0.0), ModelError, "load"),
    (lambda: point_contact(1e-3, 1e-2, 1e11, 1.0, method="fast"), TypeError, "valid"),
    (lambda: effective_modulus(-1.0, 0.3, 2e11, 0.3), ModelError, "E1"),
    (lambda: effective_modulus(2e11, 0.6, 2e11, 0.3), ModelError, "nu1"),
])
def test_bad_input(call, error, match):
    with pytest.raises(error, match=match):
        call()
