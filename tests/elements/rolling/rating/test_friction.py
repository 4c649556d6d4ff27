"""Palmgren friction torque (issue 18 item 6): the formula in its textbook units by hand,
its two viscous regimes, the P1 rules, the torque law of torque-driven transients and the
torque along a bearing equilibrium."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.elements.rolling.rating.friction import (
    F1_FACTORS,
    PalmgrenFriction,
    friction_torque,
)
from rotorsim.errors import ModelError

RPM = math.pi / 30.0


def test_the_torque_is_palmgrens_formula_in_its_own_units():
    # deep groove, d_m = 38.5 mm, f0 = 2 (oil bath), 30 cSt, 3000 rpm, Fr = 1 kN, Fa = 0.5 kN:
    # P1 = max(3.3 Fa - 0.1 Fr, Fr) = 1550 N, f1 = 0.0009 (P1/C0)^0.5 with C0 = 7800 N,
    # M0 = 1e-7 f0 (nu n)^(2/3) dm^3 [N mm], M1 = f1 P1 dm [N mm]
    m = PalmgrenFriction("deep_groove", pitch_diameter=0.0385, f0=2.0, viscosity=30e-6,
                         C0=7800.0)
    f1 = 0.0009 * (1550.0 / 7800.0) ** 0.5
    m0 = 1e-7 * 2.0 * (30.0 * 3000.0) ** (2.0 / 3.0) * 38.5**3
    m1 = f1 * 1550.0 * 38.5
    got = m.torque(1000.0, 500.0, 3000.0 * RPM)
    assert float(got) == pytest.approx((m0 + m1) * 1e-3, rel=1e-12)


def test_f1_factors_are_the_printed_catalogue_values():
    """Schaeffler, catalogue HR 1 *Rolling Bearings* (Schaeffler KG, June 2006), "Friction
    and increases in temperature", pp. 57-59, bearing factor f1 (numbers only): deep groove
    62, 63, 64: 0.0009 (P0/C0)^0.5; angular contact 70-B, 72-B, 73-B: 0.001 (P0/C0)^0.33;
    axial deep groove ball 511-514: 0.0012 (Fa/C0)^0.33; cylindrical with cage 2..-E:
    0.00030; tapered 302, 303, 313, 320, 322, 323, 329, 330-332: 0.0004; spherical 213, 222:
    0.0005 (P0/C0)^0.33. Cross-check from a second catalogue (KRW, "Reibung", pp. 53-54):
    deep groove 62, 63, 64: 0.00089 (P0/C0)^0.53, tapered 0.00040, cylindrical series 2:
    0.00030 (the deep groove z within 1.2 % of Schaeffler's, whose y = 0.5 is taken).
    Tolerance: exact (the catalogue prints these digits)."""
    printed = {"deep_groove": (0.0009, 0.5), "angular_contact": (0.001, 0.33),
               "thrust_ball": (0.0012, 0.33), "cylindrical": (0.00030, 0.0),
               "tapered": (0.0004, 0.0), "spherical": (0.0005, 0.33)}
    assert F1_FACTORS == printed
    for kind, (z, y) in printed.items():
        m = PalmgrenFriction(kind, pitch_diameter=0.05, f0=1.0, viscosity=20e-6, C0=2e4,
                             contact_angle=math.radians(12.0))
        assert float(m.load_factor(2000.0)) == pytest.approx(z * 0.1**y, rel=1e-14)


def test_the_low_speed_viscous_term_is_constant_and_meets_the_high_speed_one():
    m = PalmgrenFriction("cylindrical", pitch_diameter=0.1, f0=2.0, viscosity=20e-6)
    slow = m.viscous_torque(np.array([0.0, 10.0, 99.0]) * RPM)  # nu n < 2000 cSt rpm
    assert np.all(slow == pytest.approx(160e-7 * 2.0 * 100.0**3 * 1e-3, rel=1e-14))
    # at nu n = 2000 the two branches differ by 2000^(2/3) / 160 - 1 = -0.8 %: Palmgren's
    # constant is the rounded value
    fast = m.viscous_torque(100.0 * (1 + 1e-12) * RPM)
    assert float(fast) / float(slow[0]) == pytest.approx(2000.0 ** (2 / 3) / 160.0, rel=1e-10)


@pytest.mark.parametrize(("kind", "angle", "fr", "fa", "p1"), [
    # Schaeffler HR 1 (2006) p. 60, P1 of single bearings, never below Fr
    ("deep_groove", 0.0, 1000.0, 300.0, 1000.0),         # 3.3 Fa - 0.1 Fr < Fr
    ("deep_groove", 0.0, 1000.0, 500.0, 1550.0),
    ("angular_contact", 0.0, 1000.0, 2000.0, 1900.0),
    ("thrust_ball", 0.0, 0.0, 3000.0, 3000.0),
    ("cylindrical", 0.0, 5000.0, 100.0, 5000.0),
    # 2 Y Fa with the catalogue's Y = 0.4 cot a of a single-row tapered bearing
    ("tapered", math.radians(15.0), 1000.0, 2000.0, 2 * 0.4 * 2000.0 / math.tan(
        math.radians(15.0))),
    # e = 1.5 tan(10 deg) = 0.2645: 1.6 Fa / e above it, Fr (1 + 0.6 (Fa/(e Fr))^3) below
    ("spherical", math.radians(10.0), 1000.0, 1000.0, 1.6 * 1000.0 / (1.5 * math.tan(
        math.radians(10.0)))),
    ("spherical", math.radians(10.0), 1000.0, 100.0, 1000.0 * (1.0 + 0.6 * (100.0 / (
        1.5 * math.tan(math.radians(10.0)) * 1000.0)) ** 3)),
    ("spherical", math.radians(10.0), 0.0, 500.0, 1.6 * 500.0 / (1.5 * math.tan(
        math.radians(10.0)))),
])
def test_p1_rules(kind, angle, fr, fa, p1):
    m = PalmgrenFriction(kind, pitch_diameter=0.05, f0=1.0, viscosity=20e-6, C0=1e4,
                         contact_angle=angle)
    assert float(m.load_term(fr, fa)) == pytest.approx(p1, rel=1e-14)


def test_the_spherical_p1_branches_meet_at_e():
    # at Fa/Fr = e both branches give 1.6 Fr (the catalogue's rule is continuous)
    a = math.radians(11.0)
    m = PalmgrenFriction("spherical", pitch_diameter=0.05, f0=1.0, viscosity=20e-6,
                         C0=1e4, contact_angle=a)
    e = 1.5 * math.tan(a)
    below, above = m.load_term([1000.0, 1000.0], [e * 1000.0 * (1 - 1e-12),
                                                  e * 1000.0 * (1 + 1e-12)])
    assert below == pytest.approx(1600.0, rel=1e-10) and above == pytest.approx(1600.0,
                                                                                 rel=1e-10)


def test_the_torque_law_of_a_torque_driven_transient():
    m = PalmgrenFriction("tapered", pitch_diameter=0.2, f0=4.0, viscosity=50e-6,
                         contact_angle=math.radians(12.0))
    law = m.torque_law(20e3, 5e3)
    assert law.reactive and law.describe()["law"] == "palmgren_friction"
    w = 150.0
    h = 1e-4 * w
    fd = (law.torque(w + h, 0.0, 0.0) - law.torque(w - h, 0.0, 0.0)) / (2 * h)
    assert law.slope(w, 0.0, 0.0) == pytest.approx(fd, rel=1e-7)  # central difference
    assert law.slope(0.1, 0.0, 0.0) == 0.0 and law.torque(0.0, 0.0, 0.0) > 0.0


def test_friction_along_a_bearing_equilibrium_history():
    b = rs.BallBearing.from_geometry(n_balls=9, pitch_diameter=38.5e-3, ball_diameter=7.938e-3,
                                     f_i=0.52, f_o=0.53)
    loads = np.array([[1000.0, 0.0, 0.0, 0.0, 0.0], [600.0, 800.0, 500.0, 0.0, 0.0]])
    force = np.array([rs.bearing_equilibrium(b, f).force for f in loads])
    m = PalmgrenFriction("deep_groove", pitch_diameter=38.5e-3, f0=2.0, viscosity=30e-6,
                         C0=7800.0)
    got = friction_torque(m, force, np.array([1000.0, 3000.0]) * RPM)
    want = [m.torque(1000.0, 0.0, 1000.0 * RPM), m.torque(1000.0, 500.0, 3000.0 * RPM)]
    np.testing.assert_allclose(got, np.ravel(want), rtol=1e-9)  # equilibrium to 1e-10


@pytest.mark.parametrize(("kwargs", "error", "message"), [
    ({"f0": 0.0}, ModelError, "f0"),
    ({"viscosity": float("nan")}, ModelError, "viscosity"),
    ({"C0": None}, ModelError, "C0"),
    ({"bearing_type": "needle"}, TypeError, "bearing_type"),
])
def test_bad_friction_inputs_are_refused_by_name(kwargs, error, message):
    base = {"bearing_type": "deep_groove", "pitch_diameter": 0.05, "f0": 1.0,
            "viscosity": 20e-6, "C0": 1e4}
    with pytest.raises(error, match=message):
        PalmgrenFriction(**{**base, **kwargs})
    with pytest.raises(ModelError, match="contact angle"):
        PalmgrenFriction("tapered", pitch_diameter=0.05, f0=1.0, viscosity=20e-6)


def test_a_coast_down_on_palmgren_friction_is_the_spin_ode():
    # a rigid rotor (J_p = 2e-3 kg m^2) coasting from 300 rad/s against the bearing friction
    # law in a torque-driven transient, against scipy's solve_ivp of J W' = -M(W)
    from scipy.integrate import solve_ivp

    m = PalmgrenFriction("deep_groove", pitch_diameter=0.0385, f0=2.0, viscosity=30e-6,
                         C0=7800.0)
    law = m.torque_law(1000.0, 0.0)
    rotor = rs.Rotor([], [rs.DiskElement(n=0, m=2.0, Id=1e-3, Ip=2e-3)],
                     [rs.BearingElement(n=0, kxx=1e6, kyy=1e6)],
                     fixed=tuple((0, d) for d in ("uz", "rx", "ry")))
    drive = rs.TorqueDrive(motor=0.0, drive_node=0, friction=[(0, law)], initial_speed=300.0)
    run = rs.transient(rotor, 0.2, 2e-3, speed=drive)
    ref = solve_ivp(lambda t, w: [-law.torque(w[0], t, 0.0) / 2e-3], (0.0, 0.2), [300.0],
                    rtol=1e-11, atol=1e-9, dense_output=True)
    # both integrate the same smooth ODE at rtol ~1e-10
    np.testing.assert_allclose(run.speed, ref.sol(run.t)[0], rtol=1e-9)
    assert run.speed[-1] < 300.0 - 0.2 * law.torque(300.0, 0.0, 0.0) / 2e-3 * 0.9
