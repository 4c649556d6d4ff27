"""Batched Hertz pressures (:mod:`rotorsim.elements.rolling.rating.hertz_pressure`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.contact.hertz_point import (
    effective_modulus,
    point_contact,
    race_curvature_radii,
)
from rotorsim.elements.rolling.rating.hertz_pressure import (
    ball_pressures,
    contact_pressures,
    ellipticity,
    roller_pressures,
)
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.errors import ModelError


@pytest.mark.parametrize("ratio", [1.0, 1.001, 1.7, 12.0, 48.4, 300.0, 1e4])
def test_batched_ellipticity_equals_the_scalar_exact_solution(ratio):
    """The batched Newton solve equals the scalar bracketing solve of
    :mod:`.hertz_point` (itself checked against a Boussinesq integration) to 1e-10:
    both solve the same transcendental relation to ~1e-14."""
    k, e, f = ellipticity([ratio])
    contact = point_contact(1.0, ratio, 1e11, 1.0)
    assert k[0] == pytest.approx(contact.ellipticity, rel=1e-10)
    assert 3.0 * k[0] ** 2 * e[0] == pytest.approx(
        contact.semi_major**3 * math.pi * 1e11 / (1.0 / (1.0 + 1.0 / ratio)), rel=1e-9)
    assert f[0] >= e[0]


def test_ball_pressures_equal_the_scalar_hertz_solution_per_race():
    d, dm = 12.7e-3, 65e-3
    loads = np.array([[0.0, 500.0, 4000.0]])
    angles = np.array([[0.0, 0.2, 0.4]])
    c = ball_pressures(d, dm, 0.52, 0.53, loads, angles)
    e_star = effective_modulus(2.08e11, 0.3, 2.08e11, 0.3)
    for j in (1, 2):
        for race, f in ((0, 0.52), (1, 0.53)):
            rx, ry = race_curvature_radii(d, dm, float(angles[0, j]), f,
                                          ("inner", "outer")[race])
            ref = point_contact(rx, ry, e_star, float(loads[0, j]))
            assert c.max_pressure[0, j, race] == pytest.approx(ref.max_pressure, rel=1e-9)
            assert c.semi_major[0, j, race] == pytest.approx(ref.semi_major, rel=1e-9)
            assert c.semi_minor[0, j, race] == pytest.approx(ref.semi_minor, rel=1e-9)
    assert (c.max_pressure[0, 0] == 0).all()


def test_shoulder_truncation_margin():
    """At a contact angle near the shoulder angle the ellipse crosses it; the margin is
    ``theta_s - alpha - arcsin(a / r)`` with ``theta_s = arccos(1 - h / r)``."""
    d, f = 10e-3, 0.52
    h = 0.2 * d  # shoulder 2 mm above the groove bottom
    theta_s = math.acos(1 - h / (f * d))
    c = ball_pressures(d, 50e-3, f, f, [[3000.0, 3000.0]], [[0.1, theta_s - 0.01]],
                       shoulder_heights=(h, h))
    half = np.arcsin(c.semi_major / (f * d))
    np.testing.assert_allclose(c.shoulder_margin,
                               theta_s - np.array([0.1, theta_s - 0.01])[None, :, None] - half,
                               rtol=1e-12)
    assert c.truncated.tolist() == [[[False, False], [True, True]]]


def test_line_contact_closed_form():
    """``b = sqrt(4 q R / (pi E*))`` and ``p = 2 q / (pi b)``: the elliptical pressure over
    ``2 b`` integrates back to the line load (Johnson 1985, eq 4.45)."""
    c = roller_pressures(10e-3, 60e-3, 0.0, [[[2e5, 0.0]]], [0.0, 0.1])
    q = 2e5
    assert c.max_pressure[0, 0, 0, 0] * math.pi * c.half_width[0, 0, 0, 0] / 2 == \
        pytest.approx(q, rel=1e-12)
    e_star = effective_modulus(2.08e11, 0.3, 2.08e11, 0.3)
    r_inner = 5e-3 * (1 - 10 / 60)
    assert c.max_pressure[0, 0, 0, 0] == pytest.approx(
        math.sqrt(q * e_star / (math.pi * r_inner)), rel=1e-12)
    assert c.max_pressure[0, 0, 1].tolist() == [0.0, 0.0]


def test_contact_pressures_of_the_bearing_models():
    ball = BallBearing.from_geometry(n_balls=9, pitch_diameter=38.5e-3,
                                     ball_diameter=7.938e-3, f_i=0.52, f_o=0.53)
    c = contact_pressures(ball, [[15e-6, 0, 0, 0, 0]])
    assert c.max_pressure.shape == (1, 9, 2) and c.max_pressure[0, 0, 0] > 1e9
    roller = RollerBearing(14, 65e-3, 10e-3, 9.6e-3, model="slices", n_slices=10)
    tilted = contact_pressures(roller, [[10e-6, 0, 0, 0, 1e-3]])
    p = tilted.max_pressure[0, 0, :, 0]
    assert p[-1] > p[0]  # the tilt loads one end of the roller more
    assert tilted.edge_pressure[0, 0, 0] == p.max()
    with pytest.raises(ModelError, match="f_i and f_o"):
        contact_pressures(BallBearing(9, 38.5e-3, 7.938e-3, Kn=9e9, A0=0.3e-3), [[1e-5] * 5])
    with pytest.raises(ModelError, match="not object"):
        contact_pressures(object(), [[0.0] * 5], [[0.0]])
    with pytest.raises(ModelError, match=">= 0"):
        ball_pressures(8e-3, 40e-3, 0.52, 0.52, [[-1.0]], [[0.0]])
