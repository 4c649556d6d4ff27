"""Bad input to rolling bearings (ball, roller, flexible ring) and their statics."""

from __future__ import annotations

import math

import pytest
from corpus_checks import assert_one_line_error

import rotorsim as rs
from rotorsim.errors import ModelError

NAN = math.nan


def ball(**kw):
    args = {"n_balls": 9, "pitch_diameter": 0.0385, "ball_diameter": 0.00794, "Kn": 9.3e9,
            "f_i": 0.52, "f_o": 0.52, "tag": "DE"}
    args.update(kw)
    return lambda: rs.BallBearing(**args)


def roller(**kw):
    args = {"n_rollers": 14, "pitch_diameter": 0.0425, "roller_diameter": 0.0075,
            "effective_length": 0.0075, "Kn": 3.0e8, "tag": "NU"}
    args.update(kw)
    return lambda: rs.RollerBearing(**args)


def ring(**kw):
    args = {"n_rollers": 24, "pitch_radius": 0.075, "roller_radius": 0.0065,
            "effective_length": 0.016, "diametral_clearance": -40e-6, "shaft_radius": 0.054,
            "housing_radius": 0.097, "ring_width": 0.030, "tag": "FR"}
    args.update(kw)
    return lambda: rs.FlexibleRingRollerBearing(**args)


def valid_ball():
    return ball()()


MODEL_ERRORS = [
    pytest.param(ball(n_balls=0), r"^BallBearing 'DE': n_balls must be an integer >= 1, got 0",
                 id="ball-zero-balls"),
    pytest.param(ball(n_balls=9.0), r"^BallBearing 'DE': n_balls must be an integer",
                 id="ball-float-count"),
    pytest.param(ball(contact_angle=15.0), r"^BallBearing 'DE': contact_angle 15\.0 rad .*"
                 r"outside \[0, 90\] deg \(give it in radians\)", id="ball-angle-in-degrees"),
    pytest.param(ball(contact_angle=-0.1), r"^BallBearing 'DE': contact_angle -0\.1 rad",
                 id="ball-angle-negative"),
    pytest.param(ball(ball_diameter=NAN), r"^BallBearing 'DE': ball_diameter must be finite",
                 id="ball-diameter-nan"),
    pytest.param(ball(pitch_diameter=0.005), r"^BallBearing 'DE': ball_diameter 0\.00794 m must "
                 r"be in \(0, pitch_diameter 0\.005 m\)", id="ball-pitch-below-ball"),
    pytest.param(ball(Kn=0.0), r"^BallBearing 'DE': Kn must be positive", id="ball-Kn-zero"),
    pytest.param(ball(f_i=0.5), r"^BallBearing 'DE': f_i = 0\.5 must be > 0\.5",
                 id="ball-groove-factor"),
    pytest.param(ball(exponent=0.5), r"^BallBearing 'DE': exponent must be >= 1",
                 id="ball-exponent"),
    pytest.param(ball(Kn="9.3e9"), r"^BallBearing 'DE': Kn must be a number, got '9\.3e9'",
                 id="ball-Kn-string"),
    pytest.param(roller(n_rollers=0), r"^RollerBearing 'NU': n_rollers must be an integer >= 1",
                 id="roller-zero-rollers"),
    pytest.param(roller(roller_diameter=NAN),
                 r"^RollerBearing 'NU': roller_diameter must be positive and finite",
                 id="roller-diameter-nan"),
    pytest.param(roller(pitch_diameter=0.007), r"^RollerBearing 'NU': roller_diameter 0\.0075 m "
                 r"must be smaller than pitch_diameter", id="roller-pitch-below-roller"),
    pytest.param(roller(contact_angle=math.pi), r"^RollerBearing 'NU': contact_angle must be in "
                 r"\[0, pi/2\]", id="roller-angle-out-of-range"),
    pytest.param(roller(effective_length="7.5 mm"),
                 r"^RollerBearing 'NU': effective_length must be positive and finite",
                 id="roller-length-string"),
    pytest.param(roller(n_slices=0, model="slices"),
                 r"^RollerBearing 'NU': n_slices must be an integer >= 1", id="roller-no-slices"),
    pytest.param(roller(Kn=-1.0), r"^RollerBearing 'NU': Kn must be positive and finite",
                 id="roller-Kn-negative"),
    pytest.param(ring(n_rollers=0),
                 r"^FlexibleRingRollerBearing 'FR': n_rollers must be an integer >= 1",
                 id="ring-zero-rollers"),
    pytest.param(ring(roller_radius=NAN),
                 r"^FlexibleRingRollerBearing 'FR': roller_radius must be a positive finite",
                 id="ring-roller-nan"),
    pytest.param(ring(pitch_radius=0.006), r"^FlexibleRingRollerBearing 'FR': roller_radius "
                 r"0\.0065 m must be smaller than pitch_radius 0\.006 m", id="ring-pitch-small"),
    pytest.param(ring(shaft_radius=0.07), r"^FlexibleRingRollerBearing 'FR': shaft_radius R_s = "
                 r"0\.07 m must be smaller than the inner raceway", id="ring-bore-too-large"),
    pytest.param(ring(housing_radius=None), r"^FlexibleRingRollerBearing 'FR': the outer ring "
                 r"needs housing_radius and ring_width", id="ring-no-housing"),
    pytest.param(lambda: rs.RollingBearing(valid_ball(), n=-1, tag="DE"),
                 r"^RollingBearing 'DE': n must be a non-negative integer",
                 id="rolling-element-node"),
    pytest.param(lambda: rs.RollingBearing(valid_ball(), n=0, contact_damping="proportional",
                                           damping_factor=-1e-5, tag="DE"),
                 r"^RollingBearing 'DE': damping_factor must be a finite number >= 0",
                 id="rolling-damping-negative"),
    pytest.param(lambda: rs.RollingBearing(rs.BearingElement(n=0, kxx=1e6), n=0, tag="DE"),
                 r"^RollingBearing 'DE': bearing must be a rolling-bearing model",
                 id="rolling-wraps-linear-bearing"),
    pytest.param(lambda: rs.bearing_equilibrium(valid_ball(), [NAN, 0, 0, 0, 0]),
                 r"^BallBearing 'DE': load must be 5 finite numbers", id="equilibrium-load-nan"),
    pytest.param(lambda: rs.bearing_equilibrium(valid_ball(), "100 N"),
                 r"^BallBearing 'DE': load must be a number in SI units, got '100 N'",
                 id="equilibrium-load-unit-string"),
    pytest.param(lambda: rs.bearing_equilibrium(valid_ball(), [100.0, 0.0]),
                 r"^BallBearing 'DE': load must be 5 finite numbers .*got \[100\.0, 0\.0\]",
                 id="equilibrium-load-shape"),
]


@pytest.mark.parametrize(("call", "pattern"), MODEL_ERRORS)
def test_rolling_bearing_input_is_refused_by_name(call, pattern):
    assert_one_line_error(call, ModelError, pattern)


OPTION_ERRORS = [
    pytest.param(ball(cage="floating"), r"^BallBearing 'DE': cage must be one of", id="ball-cage"),
    pytest.param(roller(model="hertz"), r"^RollerBearing 'NU': unknown model 'hertz'; valid: ",
                 id="roller-model"),
    pytest.param(ring(cage="free"), r"^FlexibleRingRollerBearing 'FR': unknown cage 'free'; valid",
                 id="ring-cage"),
    pytest.param(lambda: rs.RollingBearing(valid_ball(), n=0, contact_damping="viscous"),
                 r"unknown contact_damping 'viscous'; valid: ", id="rolling-damping-model"),
    pytest.param(lambda: rs.bearing_equilibrium(valid_ball(), [100.0, 0, 0, 0, 0],
                                                method="bisect"),
                 r"^bearing_equilibrium: unknown method 'bisect'; valid: ",
                 id="equilibrium-method"),
]


@pytest.mark.parametrize(("call", "pattern"), OPTION_ERRORS)
def test_unknown_rolling_options_are_type_errors_listing_the_valid_ones(call, pattern):
    assert_one_line_error(call, TypeError, pattern)
