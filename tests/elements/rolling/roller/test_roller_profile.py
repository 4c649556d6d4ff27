"""Roller profiles, slicing geometry and line-contact constants (hertz_line)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.elements.rolling.contact.hertz_line import (
    LINE_EXPONENT,
    constant_to_si,
    iso_roller_constant,
    line_half_width,
    palmgren_contact_constant,
    palmgren_roller_constant,
    roller_constant_from_contacts,
    slice_constant,
)
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    StraightProfile,
    slice_centres,
)
from rotorsim.errors import ModelError


def test_slice_centres_cover_the_length_symmetrically():
    xi = slice_centres(9)
    assert xi.shape == (9,)
    assert np.allclose(xi, -xi[::-1], atol=1e-15)
    assert np.allclose(np.diff(xi), 1 / 9)
    assert xi[0] - 1 / 18 == pytest.approx(-0.5) and xi[-1] + 1 / 18 == pytest.approx(0.5)
    for bad in (0, -2, 2.0):
        with pytest.raises(ModelError):
            slice_centres(bad)


def test_straight_profile():
    assert StraightProfile().is_straight
    assert np.all(StraightProfile().drop(np.linspace(-0.5, 0.5, 7), 0.02) == 0.0)


def test_partial_circular_crown_geometry():
    length, drop, zone = 0.02, 8e-6, 4e-3
    crown = CircularCrown(crown_drop=drop, crown_length=zone)
    x = np.linspace(-0.5, 0.5, 2001)
    c = crown.drop(x, length)
    flat = np.abs(x) * length <= 0.5 * length - zone
    assert np.all(c[flat] == 0.0) and c[~flat].min() > 0.0
    assert crown.drop(np.array([0.5, -0.5]), length) == pytest.approx([drop, drop], rel=1e-12)
    # a circle of radius R through the end point, tangent to the flat part
    radius = (zone**2 + drop**2) / (2 * drop)
    x_e = np.abs(x[~flat]) * length - (0.5 * length - zone)
    assert np.allclose((radius - c[~flat]) ** 2 + x_e**2, radius**2, rtol=1e-12)
    same = CircularCrown.from_radius(radius, zone)
    assert same.crown_drop == pytest.approx(drop, rel=1e-12)


def test_full_crown_is_nearly_parabolic():
    crown = CircularCrown(crown_drop=5e-6)
    x = np.linspace(-0.5, 0.5, 11)
    # R = L^2/(8D) = 10 m >> L: circle = parabola 4 D xi^2 to O(D^2/R)
    assert np.allclose(crown.drop(x, 0.02), 4 * 5e-6 * x**2, rtol=1e-6, atol=0.0)


def test_logarithmic_profiles():
    p = LogarithmicProfile.with_end_drop(scale=2e-6, end_drop=12e-6)
    x = np.linspace(0.0, 0.5, 51)
    c = p.drop(x, 0.02)
    assert c[0] == 0.0 and c[-1] == pytest.approx(12e-6, rel=1e-12)
    assert np.all(np.diff(c) > 0.0)
    assert np.allclose(p.drop(-x, 0.02), c)
    # Lundberg: A = 2Q/(pi L E'), infinite drop at the ends only
    lund = LogarithmicProfile.lundberg(10e3, 0.02, 2.26e11)
    assert lund.scale == pytest.approx(2 * 10e3 / (math.pi * 0.02 * 2.26e11))
    assert np.isinf(lund.drop(np.array([0.5]), 0.02)[0])
    assert np.all(np.isfinite(lund.drop(slice_centres(50), 0.02)))
    # Johns-Gohar: B = 1 - 0.3033 b / a with the Hertz semi-width b at the design load
    jg = LogarithmicProfile.johns_gohar(10e3, 0.02, 2.26e11, 0.006)
    b = line_half_width(10e3, 0.02, 0.006, 2.26e11)
    assert jg.shape == pytest.approx(1 - 0.3033 * b / 0.01)
    assert jg.scale == lund.scale


@pytest.mark.parametrize("profile, match", [
    (CircularCrown(-1e-6), "crown drop"),
    (CircularCrown(1e-6, crown_length=0.02), "crown length"),
    (CircularCrown(1e-6, crown_length=-1.0), "crown length"),
    (LogarithmicProfile(0.0), "scale"),
    (LogarithmicProfile(1e-6, 0.0), "shape"),
    (LogarithmicProfile(1e-6, 1.2), "shape"),
])
def test_profile_validation(profile, match):
    with pytest.raises(ModelError, match=match):
        profile.validate(0.02, "roller")


def test_iso_constant_and_units():
    """ISO/TS 16281: c_L = 35948 L^(8/9) N/mm^(10/9) with L in mm (whole roller)."""
    for length_mm in (2.0, 10.0, 18.251):
        k_mm = 35948.0 * length_mm ** (8 / 9)
        assert iso_roller_constant(length_mm / 1000) == pytest.approx(
            k_mm * 1000 ** (10 / 9), rel=1e-12)
    # N/mm^n -> N/m^n: the same load at the same deflection
    k_si = constant_to_si(5.0, 1.5)
    assert k_si * (2e-3) ** 1.5 == pytest.approx(5.0 * 2.0**1.5, rel=1e-12)


def test_palmgren_per_contact_and_whole_roller():
    """Seed 002 eq 2.6 (delta = 3.84e-5 Q^0.9/L^0.8, N mm, per contact) and eq 2.19
    (8.0560e10 L^(8/9), N m; four printed digits: tolerance 1e-3)."""
    length = 0.012
    k_c = palmgren_contact_constant(length)
    q = 2000.0
    delta_mm = 1000.0 * (q / k_c) ** (9 / 10)
    assert delta_mm == pytest.approx(3.84e-5 * q**0.9 / (1000 * length) ** 0.8, rel=1e-12)
    assert k_c == pytest.approx(8.0560e10 * length ** (8 / 9), rel=1e-3)
    whole = palmgren_roller_constant(length)
    assert k_c / whole == pytest.approx(2 ** (10 / 9), rel=1e-12)  # README: 2.16
    # two equal contacts in series: each deflects half the total
    assert whole * (2e-6) ** LINE_EXPONENT == pytest.approx(k_c * (1e-6) ** LINE_EXPONENT)


def test_series_of_unequal_contacts():
    k_i, k_o, n, q = 3e10, 5e10, LINE_EXPONENT, 800.0
    kn = roller_constant_from_contacts(k_i, k_o, n)
    total = (q / k_i) ** (1 / n) + (q / k_o) ** (1 / n)
    assert kn * total**n == pytest.approx(q, rel=1e-12)


def test_slice_constant_and_half_width():
    assert slice_constant(3e9, 30) * 30 == pytest.approx(3e9)
    with pytest.raises(ModelError):
        slice_constant(3e9, 0)
    with pytest.raises(ModelError):
        slice_constant(-1.0, 5)
    # Hertz: b = sqrt(4 w R / (pi E*)), E* = E'/2, w = Q/L
    b = line_half_width(1000.0, 0.01, 0.004, 2.2e11)
    assert b == pytest.approx(math.sqrt(4 * 1e5 * 0.004 / (math.pi * 1.1e11)), rel=1e-12)
