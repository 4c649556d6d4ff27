"""The ISO/TS 16281 ball spring constant (issue 18): its own elliptic solve against exact
Hertz (:mod:`rotorsim.elements.rolling.contact.hertz_point`): the ratio is the rounding of
``pi / sqrt(4.5)`` to the standard's 1.48."""

from __future__ import annotations

import math

import pytest

import rotorsim as rs
from rotorsim.elements.rolling.contact.hertz_point import ball_bearing_constant
from rotorsim.elements.rolling.rating.spring_constant import iso16281_ball_constant
from rotorsim.errors import ModelError


@pytest.mark.parametrize(("d", "dm", "angle", "f_i", "f_o"), [
    (11.5e-3, 43.5e-3, 0.0, 0.52, 0.53),      # the bearing of validation case 34
    (7.938e-3, 38.5e-3, 0.0, 0.515, 0.525),
    (8e-3, 50e-3, math.radians(40.0), 0.52, 0.53),
    (20e-3, 120e-3, math.radians(25.0), 0.505, 0.51),   # close conformity: chi ~ 20
])
def test_the_iso_constant_is_exact_hertz_times_the_rounding_of_its_factor(d, dm, angle, f_i,
                                                                         f_o):
    iso = iso16281_ball_constant(d, dm, angle, f_i, f_o, E=2.1e11, nu=0.3)
    exact, _, _ = ball_bearing_constant(d, dm, angle, f_i, f_o, E_ball=2.1e11, nu_ball=0.3,
                                        E_ring=2.1e11, nu_ring=0.3)
    # both solve the ellipse ratio to ~1e-14 with different root finders
    assert iso / exact == pytest.approx(1.48 / (math.pi / math.sqrt(4.5)), rel=1e-10)


def test_a_bearing_with_the_iso_constant():
    kn = iso16281_ball_constant(11.5e-3, 43.5e-3, 0.0, 0.52, 0.53, E=2.1e11)
    b = rs.BallBearing(n_balls=7, pitch_diameter=43.5e-3, ball_diameter=11.5e-3, Kn=kn,
                       f_i=0.52, f_o=0.53, groove_center_radius="pitch")
    d = rs.bearing_equilibrium(b, [1000.0, 0, 0, 0, 0]).displacement[0]
    # validation case 34's reference 15.1101 um is exact Hertz: the ISO constant deflects
    # (1.48096 / 1.48)^(2/3) - 1 = +0.043 % more
    assert d * 1e6 / 15.1101 - 1 == pytest.approx(0.000433, abs=6e-5)


@pytest.mark.parametrize(("args", "message"), [
    ((0.05, 0.04, 0.0, 0.52, 0.53), "ball_diameter"),
    ((0.01, 0.04, 0.0, 0.5, 0.53), "groove"),
])
def test_bad_iso_constant_inputs_are_refused(args, message):
    with pytest.raises(ModelError, match=message):
        iso16281_ball_constant(*args)
