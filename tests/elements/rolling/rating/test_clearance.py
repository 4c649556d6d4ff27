"""Operating clearance (issue 18 item 5): thick-ring fits against an independent Lame solve,
the catalogue closed forms, the temperature rule of the IKO catalogue and the rotating-ring
growth against a numerical solution of the rotating-disk equation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_bvp

import rotorsim as rs
from rotorsim.elements.rolling.rating.clearance import (
    MountingConditions,
    centrifugal_expansion,
    inner_fit_expansion,
    operating_clearance,
    outer_fit_contraction,
    with_operating_clearance,
)
from rotorsim.errors import ModelError


def _lame_pair(radii, moduli, poissons, radial_interference):
    """Two shrink-fitted plane-stress cylinders (radii a < b < c, cylinder 1 inside):
    u = A r + B / r in each; sigma_r(a) = 0 (a > 0) or B_1 = 0 (a = 0), sigma_r(c) = 0,
    equal sigma_r at b, u_2(b) - u_1(b) = radial interference. Returns (u_1, u_2) callables
    and the interface pressure (an independent linear solve, not the closed form)."""
    a, b, c = radii
    (e1, e2), (n1, n2) = moduli, poissons

    def sig(e, n, r):  # sigma_r coefficients of (A, B)
        return e / (1 - n**2) * np.array([1 + n, -(1 - n) / r**2])

    m = np.zeros((4, 4))
    rhs = np.zeros(4)
    m[0, :2] = sig(e1, n1, a) if a > 0 else [0.0, 1.0]
    m[1, :2], m[1, 2:] = sig(e1, n1, b), -sig(e2, n2, b)
    m[2, :2], m[2, 2:] = [-b, -1 / b], [b, 1 / b]
    rhs[2] = radial_interference
    m[3, 2:] = sig(e2, n2, c) if math.isfinite(c) else [1.0, 0.0]  # infinite: A_2 = 0
    coef = np.linalg.solve(m, rhs)
    pressure = -float(sig(e2, n2, b) @ coef[2:])
    return (lambda r: coef[0] * r + coef[1] / r), (lambda r: coef[2] * r + coef[3] / r), pressure


@pytest.mark.parametrize(("shaft_bore", "e_shaft", "nu_shaft"), [
    (0.0, 2.08e11, 0.3), (0.035, 2.08e11, 0.3), (0.02, 1.1e11, 0.34)],
    ids=["solid steel", "hollow steel", "hollow titanium"])
def test_inner_fit_is_the_lame_solution(shaft_bore, e_shaft, nu_shaft):
    bore, raceway, interference = 0.05, 0.0625, 25e-6
    got, p = inner_fit_expansion(interference, bore, raceway, shaft_bore, E_shaft=e_shaft,
                                 nu_shaft=nu_shaft)
    _, ring, pressure = _lame_pair((shaft_bore / 2, bore / 2, raceway / 2),
                                   (e_shaft, 2.08e11), (nu_shaft, 0.3), interference / 2)
    assert got == pytest.approx(2 * ring(raceway / 2), rel=1e-12)
    assert p == pytest.approx(pressure, rel=1e-12)


@pytest.mark.parametrize("housing", [0.14, math.inf], ids=["finite housing", "thick housing"])
def test_outer_fit_is_the_lame_solution(housing):
    outside, raceway, interference = 0.09, 0.0775, 15e-6
    got, p = outer_fit_contraction(interference, outside, raceway, housing, E_housing=7e10,
                                   nu_housing=0.33)  # aluminium housing
    ring, _, pressure = _lame_pair((raceway / 2, outside / 2, housing / 2), (2.08e11, 7e10),
                                   (0.3, 0.33), interference / 2)
    assert got == pytest.approx(-2 * ring(raceway / 2), rel=1e-12)
    assert p == pytest.approx(pressure, rel=1e-12)


def test_same_material_limits_are_the_catalogue_reduction_factors():
    # solid shaft / thick housing of the ring's material: f_1 = d / D_i, f_2 = D_o / D
    assert inner_fit_expansion(30e-6, 0.04, 0.052)[0] == pytest.approx(30e-6 * 0.04 / 0.052,
                                                                      rel=1e-14)
    assert outer_fit_contraction(30e-6, 0.09, 0.0775)[0] == pytest.approx(
        30e-6 * 0.0775 / 0.09, rel=1e-14)
    assert inner_fit_expansion(-5e-6, 0.04, 0.052) == (0.0, 0.0)  # a loose fit


def test_temperature_difference_follows_the_iko_catalogue_rule():
    # IKO catalogue eq (29): reduction = alpha dT E, dT of inner ring and rolling elements
    # (as one unit) over the outer ring, E the outer raceway diameter. Here the reduction
    # is alpha dT (D_i + 2 D_w) = alpha dT (E - P_d): IKO's rule up to alpha dT P_d (4e-4
    # of it), which the catalogue neglects
    d_i, d_o, d_w, p_d = 0.0625, 0.0775, 0.0075, 30e-6
    c = MountingConditions(bore=0.05, outside_diameter=0.09, inner_temperature=15.0,
                           element_temperature=15.0, expansion_ring=12.5e-6,
                           expansion_element=12.5e-6)
    change = operating_clearance(p_d, d_i, d_o + p_d, d_w, c)
    assert -change.thermal == pytest.approx(12.5e-6 * 15.0 * d_o, rel=1e-12)
    assert -change.thermal == pytest.approx(12.5e-6 * 15.0 * (d_o + p_d), rel=5e-4)
    assert change.operating == pytest.approx(p_d + change.thermal, rel=1e-14)


def test_shaft_and_housing_temperatures_change_the_fits():
    # aluminium housing warming with the outer ring loosens the outer fit
    c = MountingConditions(bore=0.05, outside_diameter=0.09, housing_interference=20e-6,
                           outer_temperature=30.0, expansion_housing=23e-6, E_housing=7e10,
                           nu_housing=0.33)
    change = operating_clearance(30e-6, 0.0625, 0.0775, 0.0075, c)
    effective = 20e-6 + 0.09 * (11.5e-6 - 23e-6) * 30.0
    assert change.outer_fit == pytest.approx(outer_fit_contraction(
        effective, 0.09, 0.0775, E_housing=7e10, nu_housing=0.33)[0], rel=1e-14)
    assert change.outer_fit < change.unmounted - change.mounted


def test_rotating_ring_growth_is_the_rotating_disk_solution():
    # u'' + u'/r - u/r^2 = -(1 - nu^2) rho W^2 r / E with sigma_r = 0 at both radii,
    # solved by scipy's solve_bvp
    e, nu, rho, w, b, c = 2.08e11, 0.3, 7850.0, 2000.0, 0.025, 0.03125
    k = (1 - nu**2) * rho * w**2 / e

    def rhs(r, y):
        return np.vstack([y[1], -y[1] / r + y[0] / r**2 - k * r])

    def bc(ya, yb):
        return np.array([ya[1] + nu * ya[0] / b, yb[1] + nu * yb[0] / c])

    r = np.linspace(b, c, 50)
    sol = solve_bvp(rhs, bc, r, np.zeros((2, r.size)), tol=1e-10)
    assert sol.status == 0
    got = centrifugal_expansion(w, 2 * b, 2 * c, e, nu, rho)
    assert got == pytest.approx(2 * sol.sol(c)[0], rel=1e-6)  # BVP tolerance


def test_a_bearing_model_gets_its_operating_clearance():
    roller = rs.RollerBearing(n_rollers=14, pitch_diameter=0.0425, roller_diameter=0.0075,
                              effective_length=0.0075, Kn=3e8, diametral_clearance=40e-6)
    c = MountingConditions(bore=0.03, outside_diameter=0.055, shaft_interference=15e-6,
                           inner_temperature=10.0, element_temperature=5.0, speed=600.0)
    mounted, change = with_operating_clearance(roller, c)
    assert 2 * mounted.clearance == pytest.approx(change.operating, rel=1e-14)
    parts = change.inner_fit + change.outer_fit - change.thermal + change.centrifugal
    assert change.operating == pytest.approx(40e-6 - parts, rel=1e-14)
    assert change.operating < change.mounted < change.unmounted


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"bore": -0.01}, "bore"),
    ({"shaft_bore": 0.06}, "shaft_bore"),
    ({"outside_diameter": 0.04}, "outside_diameter"),
    ({"speed": float("nan")}, "speed"),
])
def test_bad_mounting_conditions_are_refused_by_name(kwargs, message):
    base = {"bore": 0.05, "outside_diameter": 0.09}
    with pytest.raises(ModelError, match=message):
        MountingConditions(**{**base, **kwargs})
    with pytest.raises(ModelError, match="inner_raceway"):
        operating_clearance(1e-5, 0.04, 0.08, 0.01, MountingConditions(**base))


_MODEL = """
[model]
name = "mounted"

[[disks]]
node = 0
m = "1 kg"
Id = "2.5e-4 kg*m^2"
Ip = "4.5e-4 kg*m^2"

[[rolling_bearings]]
tag = "B"
type = "ball"
node = 0
n_balls = 9
pitch_diameter = "70 mm"
ball_diameter = "7.5 mm"
f_i = 0.52
f_o = 0.53
diametral_clearance = "30 um"

[rolling_bearings.mounting]
{mounting}
"""


def test_a_model_file_mounting_table_sets_the_operating_clearance(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(_MODEL.format(mounting='bore = "50 mm"\noutside_diameter = "90 mm"\n'
                                           'shaft_interference = "20 um"\n'
                                           'inner_temperature = 10\nspeed = "3000 rpm"'))
    model = rs.load_model(path).rolling_bearings[0].bearing
    api = rs.BallBearing.from_geometry(n_balls=9, pitch_diameter=0.07, ball_diameter=0.0075,
                                       f_i=0.52, f_o=0.53, diametral_clearance=30e-6)
    c = MountingConditions(bore=0.05, outside_diameter=0.09, shaft_interference=20e-6,
                           inner_temperature=10.0, speed=3000 * math.pi / 30)
    assert model.clearance == pytest.approx(with_operating_clearance(api, c)[0].clearance,
                                            rel=1e-12)
    assert model.clearance < 15e-6 / 2  # fit + warm inner ring + speed


def test_a_model_file_mounting_table_is_checked(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(_MODEL.format(mounting='bore = "50 mm"\noutside_diameter = "40 mm"'))
    with pytest.raises(ModelError, match=r"rolling_bearings\[0\].*outside_diameter"):
        rs.load_model(path)
    path.write_text(_MODEL.format(mounting='bore = "50 mm"'))
    with pytest.raises(ModelError, match="outside_diameter"):
        rs.load_model(path)
