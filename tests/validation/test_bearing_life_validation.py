"""Bearing life and contact pressure against references no one here wrote (issue 18;
docs/validation.md, case 29).

* Catalogue: the 6205 deep-groove ball bearing, internal geometry from the Case Western
  Reserve University Bearing Data Center (SKF 6205-2RS JEM: 9 balls of 0.3126 in on a
  1.537 in pitch diameter), ratings of the catalogue 6205, ``C_r = 14.0 kN``,
  ``C_0r = 7.80 kN`` (KT Bearing's 6205 page, ktbearing.com "What are the 6205 bearing
  dimensions", standard open 6205; the same 14.0 kN with ``C_0r = 7.85`` kN in the 62-series
  table of a Japanese catalogue reproduced in gist nagae/8756dc2de16082219e1ae6a80a73dfb3;
  the SKF catalogue lists 14.8 kN for its Explorer grade, above the ISO 281 formula by its
  material factor).
* ISO 281 Table 3, single-row angular-contact factors: LYC's "Equivalent dynamic load,
  angular contact ball bearings" (25 deg: ``e = 0.68``, ``P = 0.41 F_r + 0.87 F_a``; 40 deg:
  ``1.14``, ``0.35 F_r + 0.57 F_a``) and the product page of a 7206-B (40 deg, fgfa.com.cn:
  ``e = 1.14, X = 0.35, Y = 0.57``); Koyo's technical section 3.1 (30 deg: ``e = 0.8``,
  ``X = 0.39``, ``Y = 0.76``).
* Hertz pressure: the worked example "Contact stresses in a steel ball bearing" of
  amesweb.info (ball 4.90 mm radius in a 5 mm groove of a 25 mm inner race, 1500 N,
  E = 210 GPa, nu = 0.29: p_max = 2193.6 MPa, a = 2.101 mm, b = 0.156 mm).
* ISO/TS 16281 in the ISO 281 reference case: radial load, zero clearance, inner ring
  turning; ``L10r -> (C/P)^p`` as the number of rolling elements grows (the reference case
  integrates a continuous load zone).
"""

from __future__ import annotations

import math

import pytest

import rotorsim as rs
from rotorsim.elements.rolling.contact.hertz_point import effective_modulus
from rotorsim.elements.rolling.rating.hertz_pressure import ellipticity

pytestmark = pytest.mark.validation

INCH = 25.4e-3
CWRU_6205 = {"n_balls": 9, "ball_diameter": 0.3126 * INCH, "pitch_diameter": 1.537 * INCH}


def test_6205_ratings_and_life_against_the_catalogue():
    """ISO 281 from the geometry against the catalogue: C within 1 % (the catalogue rounds
    to 0.1 kN, 0.4 %; the geometry is given to 4 digits; b_m = 1.3 as in ISO 281), C0
    within 1.5 % (C0r rounded to 0.1 kN, 0.6 %, and f_0 read at the CWRU pitch diameter,
    0.6 % above the nominal (d + D) / 2). The catalogue life at P = 2 kN,
    ``(14 000 / 2 000)^3 = 343`` million revolutions, within 3 x 1 % (cube of C)."""
    rating = rs.BearingRating.from_geometry(
        "ball", n_elements=9, element_diameter=CWRU_6205["ball_diameter"],
        pitch_diameter=CWRU_6205["pitch_diameter"])
    assert rating.C == pytest.approx(14_000.0, rel=0.01)
    assert rating.C0 == pytest.approx(7_800.0, rel=0.015)
    assert float(rating.basic_life(2000.0)) == pytest.approx((14_000 / 2_000) ** 3, rel=0.03)


@pytest.mark.parametrize(("angle", "e", "x", "y"), [(25.0, 0.68, 0.41, 0.87),
                                                    (30.0, 0.80, 0.39, 0.76),
                                                    (40.0, 1.14, 0.35, 0.57)])
def test_single_row_angular_contact_factors_are_the_catalogue_ones(angle, e, x, y):
    """``P`` just below and above ``e`` against the catalogue factors (exact: the table
    entries themselves)."""
    r = rs.BearingRating("ball", C=1e4, contact_angle=math.radians(angle))
    assert float(r.equivalent_load(1000.0, 0.999 * e * 1000.0)) == 1000.0
    assert float(r.equivalent_load(1000.0, 1.001 * e * 1000.0)) == pytest.approx(
        x * 1000.0 + y * 1.001 * e * 1000.0, rel=1e-12)


def test_catalogue_life_of_a_6205_from_bearing_life():
    """``rs.bearing_life`` of the CWRU 6205 under a named load, 2 kN radial: ISO 281 ``L10``
    with the catalogue ``C`` is the catalogue life ``(14.0 / 2)^3 = 343`` million
    revolutions exactly; from the geometry within 3 x 1 % (the cube of the ``C`` error)."""
    model = rs.BallBearing.from_geometry(n_balls=9, pitch_diameter=CWRU_6205["pitch_diameter"],
                                         ball_diameter=CWRU_6205["ball_diameter"], f_i=0.52,
                                         f_o=0.52)
    catalogue = rs.bearing_life(model, [2000.0, 0, 0, 0, 0],
                                options=rs.RatingOptions(C=14.0e3, C0=7.8e3))
    assert catalogue.L10 == pytest.approx(343.0, rel=1e-12)
    geometry = rs.bearing_life(model, [2000.0, 0, 0, 0, 0])
    assert geometry.L10 == pytest.approx(343.0, rel=0.03)


def test_hertz_pressure_of_a_published_worked_example():
    """p_max, a and b of the amesweb example within 0.5 % (printed to 4-5 digits; its
    elliptic integrals are evaluated by an unstated method: the three differ from the
    exact solution by -0.1 %, +0.4 % and +0.1 %)."""
    e_star = effective_modulus(210e9, 0.29, 210e9, 0.29)
    rx = 1.0 / (1.0 / 4.90e-3 + 1.0 / 25e-3)
    ry = 1.0 / (1.0 / 4.90e-3 - 1.0 / 5e-3)
    k, big_e, _ = ellipticity([ry / rx])
    r_eff = 1.0 / (1.0 / rx + 1.0 / ry)
    a = (3 * k[0] ** 2 * big_e[0] * 1500.0 * r_eff / (math.pi * e_star)) ** (1 / 3)
    b = a / k[0]
    p_max = 1.5 * 1500.0 / (math.pi * a * b)
    assert p_max == pytest.approx(2193.6e6, rel=0.005)
    assert a == pytest.approx(2.101e-3, rel=0.005)
    assert b == pytest.approx(0.156e-3, rel=0.005)


@pytest.mark.parametrize(("z", "pitch", "tol"), [(9, 39.04e-3, 0.015), (20, 80e-3, 1e-3),
                                                   (40, 150e-3, 1e-4)])
def test_reference_life_reduces_to_iso_281_as_the_load_zone_fills(z, pitch, tol):
    """Zero clearance, radial load: rotorsim's equilibrium gives the ball loads, ISO/TS
    16281 their life. The difference to ``(C/P)^3`` is the discreteness of Z balls against
    the continuous load zone of the reference case; measured -1.1 % / +1.0 % (Z = 9, a
    ball on the load line or two astride it), 0.06 % (Z = 20), 0.005 % (Z = 40)."""
    for psi0 in (0.0, math.pi / z):
        b = rs.BallBearing.from_geometry(n_balls=z, pitch_diameter=pitch,
                                         ball_diameter=7.94e-3, f_i=0.52, f_o=0.53,
                                         psi0=psi0)
        r = rs.bearing_life(b, [2000.0, 0.0, 0.0, 0.0, 0.0])
        assert r.L10r == pytest.approx(r.L10, rel=tol)
        assert r.P_ref == pytest.approx(2000.0, rel=tol / 3 + 1e-12)


def test_roller_lamina_life_reduces_to_the_reference_case():
    """Cylindrical roller bearing, zero clearance, radial load, 10 laminae: ``L10r =
    (C/P)^4`` (the raceway exponent of line contact) within 0.2 % at Z = 14 (measured
    -0.11 % / +0.14 %), and ``P_ref = P``."""
    for psi0 in (0.0, math.pi / 14):
        rb = rs.RollerBearing(14, 65e-3, 10e-3, 9.6e-3, model="slices", n_slices=10,
                              psi0=psi0)
        r = rs.bearing_life(rb, [8000.0, 0.0, 0.0, 0.0, 0.0])
        assert r.L10r == pytest.approx((r.C / 8000.0) ** 4, rel=2e-3)
        assert r.P_ref == pytest.approx(8000.0, rel=1e-3)
