"""Rolling bearings in model files: keys, units, profiles, linearisation points, the bad-input
corpus (one line naming the key path), save/load round trips, and analyses run on the rotor
linearised at the static loads."""

from __future__ import annotations

import copy
import math
import tempfile
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import tomli_w
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    StraightProfile,
)
from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model, model_from_dict, run_analysis, save_model

MODELS = Path(__file__).resolve().parents[2] / "models"


def data(name: str = "rolling_ball") -> dict[str, Any]:
    with open(MODELS / f"{name}.toml", "rb") as stream:
        return tomllib.load(stream)


def with_bearing(index: int = 0, name: str = "rolling_ball", **changes: Any) -> dict[str, Any]:
    """The model file with keys of ``rolling_bearings[index]`` changed (None deletes)."""
    out = data(name)
    entry = out["rolling_bearings"][index]
    for key, value in changes.items():
        if value is None:
            entry.pop(key, None)
        else:
            entry[key] = value
    return out


# ---------------------------------------------------------------- loading
def test_ball_model_file_is_resolved_to_si():
    model = load_model(MODELS / "rolling_ball.toml")
    assert model.rotor.bearing_elements == ()  # the rotor stays linear
    assert [rb.tag for rb in model.rolling_bearings] == ["DE", "NDE"]
    assert [rb.n for rb in model.rolling_bearings] == [0, 10]
    assert [p.kind for p in model.linearize] == ["static", "static"]
    rb = model.rolling_bearings[0]
    assert isinstance(rb, RollingBearing) and isinstance(rb.bearing, BallBearing)
    b = rb.bearing
    assert (b.n_balls, b.Kn, b.contact_angle, b.f_i, b.f_o) == (9, 9.3e9, 0.0, 0.52, 0.52)
    assert b.pitch_diameter == 0.0385 and b.ball_diameter == pytest.approx(7.94e-3, rel=1e-15)
    assert b.clearance == 5e-6  # 10 um diametral
    assert b.center_distance == pytest.approx(0.04 * 7.94e-3, rel=1e-12)


def test_tapered_model_file_mounts_the_pair_back_to_back():
    model = load_model(MODELS / "rolling_tapered.toml")
    a, b = (rb.bearing for rb in model.rolling_bearings)
    assert isinstance(a, RollerBearing) and isinstance(b, ReversedBearing)
    assert isinstance(b.bearing, RollerBearing)
    assert a.contact_angle == pytest.approx(math.radians(14.0), rel=1e-15)
    assert a.clearance == -2e-6 and a.model == "slices" and a.n_slices == 10
    assert a.profile == CircularCrown(crown_drop=5e-6, crown_length=3e-3)
    # Kn left out: ISO/TS 16281, c_L = 35948 L^(8/9) N/mm^(10/9) with L = 12 mm
    assert a.kn == pytest.approx(35948 * 12 ** (8 / 9) * 1e3 ** (10 / 9), rel=1e-12)
    lin = model.linearized()
    # the 400 N thrust towards +z: bearing A carries it on top of the common preload
    assert lin.loads[0, 2] - (-lin.loads[1, 2]) == pytest.approx(400.0, rel=1e-5)
    assert -lin.loads[1, 2] > 400.0  # B stays preloaded


@pytest.mark.parametrize(("text", "exponent", "expected"), [
    (9.3e9, 1.5, 9.3e9),
    ("9.3e9 N/m^1.5", 1.5, 9.3e9),
    ("294 kN/mm^1.5", 1.5, 294e3 * 1e3**1.5),
    ("3e8 N/m^(10/9)", None, 3e8),
    ("35948 N/mm^(10/9)", None, 35948 * 1e3 ** (10 / 9)),
    ("2e8 N/m^1.2", 1.2, 2e8),
])
def test_load_deflection_constant_units(text, exponent, expected):
    kind = "ball" if exponent == 1.5 else "roller"
    changes: dict[str, Any] = {"Kn": text, "exponent": exponent}
    if kind == "roller":
        out = data("rolling_tapered")
        out["rolling_bearings"][0].update({k: v for k, v in changes.items() if v is not None})
    else:
        out = with_bearing(**changes)
    bearing = model_from_dict(out).rolling_bearings[0].bearing
    assert bearing.Kn == pytest.approx(expected, rel=1e-12)


def test_ball_kn_from_hertz_theory_when_left_out():
    model = model_from_dict(with_bearing(Kn=None))
    expected = BallBearing.from_geometry(n_balls=9, pitch_diameter=0.0385,
                                         ball_diameter=7.94e-3, f_i=0.52, f_o=0.52).Kn
    assert model.rolling_bearings[0].bearing.Kn == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(("profile", "expected"), [
    ({"type": "straight"}, StraightProfile()),
    ({"type": "crowned", "crown_drop": "4 um"}, CircularCrown(crown_drop=4e-6)),
    ({"type": "crowned", "crown_radius": "2 m", "crown_length": "2 mm"},
     CircularCrown.from_radius(2.0, 2e-3)),
    ({"type": "logarithmic", "scale": "1 um", "shape": 0.9},
     LogarithmicProfile(scale=1e-6, shape=0.9)),
    ({"type": "logarithmic", "scale": "2 um", "end_drop": "10 um"},
     LogarithmicProfile.with_end_drop(2e-6, 10e-6)),
])
def test_roller_profiles(profile, expected):
    out = data("rolling_tapered")
    out["rolling_bearings"][0]["profile"] = profile
    assert model_from_dict(out).rolling_bearings[0].bearing.profile == expected


def test_linearisation_points_with_units():
    out = with_bearing(linearize={"load": ["0 N", "-1 kN", "300 N", 0, "2 N m"]})
    model = model_from_dict(out)
    assert model.linearize[0].kind == "load"
    assert model.linearize[0].value == (0.0, -1000.0, 300.0, 0.0, 2.0)
    out = with_bearing(1, linearize={"displacement": ["1 um", 0, 0, "0.1 mrad", 0]})
    point = model_from_dict(out).linearize[1]
    assert point.kind == "displacement" and point.value == pytest.approx(
        (1e-6, 0.0, 0.0, 1e-4, 0.0), rel=1e-15)


# ---------------------------------------------------------------- bad input
BAD = [
    ({"type": "balls"}, "rolling_bearings[0].type: unknown bearing type \"balls\" "
                        "(did you mean 'ball'?)"),
    ({"type": None}, "rolling_bearings[0].type: field required"),
    ({"contact_angle": "95 deg"}, "rolling_bearings[0].contact_angle: must be in [0, 90] deg,"
                                  " got 95 deg"),
    ({"contact_angle": -0.1}, "rolling_bearings[0].contact_angle: must be in [0, 90] deg"),
    ({"n_ball": 9}, "rolling_bearings[0]: unknown key 'n_ball' (did you mean 'n_balls'?)"),
    ({"n_balls": 0}, "rolling_bearings[0].n_balls: must be >= 1"),
    ({"n_balls": 9.5}, "rolling_bearings[0].n_balls: expected an integer"),
    ({"Kn": "8.5e9 N/m^2"}, "rolling_bearings[0].Kn: \"8.5e9 N/m^2\" is not a load-deflection"
                            " constant in N/m^1.5"),
    ({"Kn": -1.0}, "rolling_bearings[0].Kn: must be > 0"),
    ({"Kn": None, "f_o": None}, "rolling_bearings[0].Kn: field required (or give f_i and f_o"),
    ({"pitch_diameter": "50 kg"}, "rolling_bearings[0].pitch_diameter: \"50 kg\" is a mass, "
                                  "expected a length"),
    ({"ball_diameter": "40 mm"}, "rolling_bearings[0]: ball_diameter"),
    ({"f_i": 0.4}, "rolling_bearings[0]: f_i = 0.4 must be > 0.5"),
    ({"diametral_clearance": "10 mm"}, "rolling_bearings[0]: radial clearance 0.005 m "
                                       "exceeds the ball radius"),
    ({"z": "0.12 m"}, "rolling_bearings[0].z: 0.12 m is not a node position"),
    ({"n_link": 0}, "rolling_bearings[0].n_link: must differ from the bearing node (0)"),
    ({"n_link": 40}, "rolling_bearings[0].n_link: node 40 is neither a shaft node"),
    ({"cage": "loose"}, "rolling_bearings[0].cage: must be one of"),
    ({"axial_direction": "up"}, "rolling_bearings[0].axial_direction: must be one of"),
    ({"exponent": 0.5}, "rolling_bearings[0].exponent: must be >= 1"),
    ({"linearize": "dynamic"}, "rolling_bearings[0].linearize: expected \"static\""),
    ({"linearize": {"lod": [0, 0, 0, 0, 0]}},
     "rolling_bearings[0].linearize: give exactly one of load, displacement (unknown key "
     "'lod' (did you mean 'load'?))"),
    ({"linearize": {"load": [0, "1 kN"]}},
     "rolling_bearings[0].linearize.load: expected 5 values"),
    ({"linearize": {"load": [0, "1 m", 0, 0, 0]}},
     "rolling_bearings[0].linearize.load[1]: \"1 m\" is a length, expected a force"),
    ({"contact_damping": None}, "rolling_bearings[0]: damping_factor is given but "
                               "contact_damping is 'none'"),
]


@pytest.mark.parametrize(("changes", "message"), BAD, ids=[str(c) for c, _ in BAD])
def test_bad_ball_input_names_the_key(changes, message):
    with pytest.raises(ModelError) as info:
        model_from_dict(with_bearing(**changes))
    text = str(info.value)
    assert text.startswith(message), text
    assert "\n" not in text


BAD_ROLLER = [
    ({"profile": {"type": "crowned"}}, "rolling_bearings[0].profile.crown_drop: give "
                                       "crown_drop"),
    ({"profile": {"type": "straight", "scale": 1e-6}},
     "rolling_bearings[0].profile.scale: is not a key of a straight profile"),
    ({"profile": {"type": "barrel"}}, "rolling_bearings[0].profile.type: must be one of"),
    ({"model": "tilt_integral"}, "rolling_bearings[0]: the tilt-integral model"),
    ({"profile": {"type": "crowned", "crown_drop": "5 um", "crown_length": "8 mm"}},
     "rolling_bearings[0]: crown length"),
    ({"n_balls": 9}, "rolling_bearings[0]: unknown key 'n_balls'"),
    ({"effective_length": None}, "rolling_bearings[0].effective_length: field required"),
]


@pytest.mark.parametrize(("changes", "message"), BAD_ROLLER,
                         ids=[str(c) for c, _ in BAD_ROLLER])
def test_bad_roller_input_names_the_key(changes, message):
    with pytest.raises(ModelError) as info:
        model_from_dict(with_bearing(name="rolling_tapered", **changes))
    assert str(info.value).startswith(message), str(info.value)


def test_rolling_bearings_must_be_tables():
    out = data()
    out["rolling_bearings"] = [1]
    with pytest.raises(ModelError, match=r"^rolling_bearings\[0\]: expected a table"):
        model_from_dict(out)


VALUES = st.one_of(st.integers(-3, 30), st.floats(allow_nan=True, allow_infinity=True),
                   st.booleans(), st.sampled_from(["5 um", "50 kg", "25 deg", "ball", "roller",
                                                   "static", "-z", "9e9 N/m^1.5", "1 (", ""]),
                   st.lists(st.integers(-2, 2), max_size=6),
                   st.dictionaries(st.sampled_from(["type", "load", "crown_drop", "x"]),
                                   st.sampled_from([0, "straight", "crowned", [0] * 5]),
                                   max_size=2))


@settings(max_examples=60, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_mutated_rolling_bearings_load_or_raise_model_error(draw):
    out = copy.deepcopy(data(draw.draw(st.sampled_from(["rolling_ball", "rolling_tapered"]))))
    entry = out["rolling_bearings"][draw.draw(st.integers(0, 1))]
    for _ in range(draw.draw(st.integers(1, 3))):
        key = draw.draw(st.sampled_from([*sorted(entry), "linearize", "profile", "extra"]))
        if draw.draw(st.booleans()) and key in entry:
            del entry[key]
        else:
            entry[key] = draw.draw(VALUES)
    try:
        model_from_dict(out)
    except ModelError as err:
        assert "\n" not in str(err) and str(err).startswith("rolling_bearings[")


# ---------------------------------------------------------------- saving
@pytest.mark.parametrize("name", ["rolling_ball", "rolling_tapered"])
def test_save_and_load_round_trip(name, tmp_path):
    out = data(name)
    out["rolling_bearings"][1]["linearize"] = {"load": [0, -500.0, -800.0, 0, 0]}
    out["rolling_bearings"][0].update(contact_damping="proportional", damping_factor=2e-5)
    model = model_from_dict(out)
    again = load_model(save_model(model, tmp_path / "copy.toml"))
    assert again.linearize == model.linearize
    rng = np.random.default_rng(1)
    u = rng.normal(size=(8, 6)) * [2e-5, 2e-5, 2e-5, 1e-3, 1e-3, 0.0]
    v = rng.normal(size=(8, 6)) * 1e-3
    for a, b in zip(model.rolling_bearings, again.rolling_bearings, strict=True):
        assert (type(a.bearing), a.n, a.n_link, a.tag, a.contact_damping, a.damping_factor) \
            == (type(b.bearing), b.n, b.n_link, b.tag, b.contact_damping, b.damping_factor)
        fa, fb = a.force(u, v, 0.3, 10.0), b.force(u, v, 0.3, 10.0)
        np.testing.assert_array_equal(fa.f, fb.f)
        np.testing.assert_array_equal(fa.C, fb.C)
    la, lb = model.linearized(), again.linearized()
    np.testing.assert_array_equal(la.loads, lb.loads)
    for ea, eb in zip(la.bearings, lb.bearings, strict=True):
        np.testing.assert_array_equal(ea.stiffness_matrix, eb.stiffness_matrix)
    assert lb.bearings[0].damping_matrix is not None


# ---------------------------------------------------------------- analyses
def test_analyses_run_on_the_linearised_rotor():
    model = load_model(MODELS / "rolling_ball.toml")
    lin = model.linearized()
    assert model.linearized() is lin  # computed once
    static = run_analysis(model, "static")
    assert static is not lin.static and static.options["rolling_bearings"]["tags"] == [
        "DE", "NDE"]
    np.testing.assert_array_equal(static.displacement, lin.static.displacement)
    # reactions of the rolling bearings balance the weight and the 300 N point load
    weight = 9.80665 * model.rotor.m
    assert static.bearing_forces[:, 1].sum() == pytest.approx(weight + 300.0, rel=1e-6)
    crit = run_analysis(model, "critical_speeds")
    assert crit.options["rolling_bearings"]["points"] == ["static", "static"]
    assert np.all(np.isfinite(crit.speed))


def test_critical_speed_map_refers_to_rolling_bearings_by_tag():
    out = data()
    out["analyses"] = {"map": {"type": "critical_speed_map", "bearings": ["NDE", "DE"],
                               "num_modes": 2, "stiffness": {"start": 1e6, "stop": 1e9,
                                                             "num": 4}}}
    model = model_from_dict(out)
    assert model.analyses["map"].bearings == (1, 0)
    result = run_analysis(model, "map")
    # both supports isotropic springs: the first critical speed rises with the stiffness
    # towards the rigid-support value (measured 3058 rpm at 1 MN/m, 4150 rpm at 1 GN/m)
    assert result.critical_speeds.shape == (4, 2) and np.all(np.diff(result.curve(0)) > 0)
    out["analyses"]["map"]["bearings"] = ["XX"]
    with pytest.raises(ModelError, match=r"analyses\.map\.bearings\[0\]: no bearing tagged"):
        model_from_dict(out)


def test_model_file_as_toml_text_round_trips(tmp_path):
    text = tomli_w.dumps(data("rolling_tapered"))
    with tempfile.NamedTemporaryFile("w", suffix=".toml", dir=tmp_path, delete=False) as f:
        f.write(text)
    model = load_model(f.name)
    assert len(model.rolling_bearings) == 2
