"""Interference (negative clearance, preload) of rolling bearings: physically absurd values
are refused with the plausible range, in the API and in model files; a preload is shown in
``rotorsim info`` (issue 12)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

import rotorsim as rs
from rotorsim.cli.main import main
from rotorsim.elements.rolling.geometry import MAX_INTERFERENCE_RATIO
from rotorsim.io.model_file import model_from_dict

MODELS = Path(__file__).resolve().parents[2] / "models"
BALL = dict(n_balls=8, ball_diameter=0.008, pitch_diameter=0.04, Kn=1e10, A0=3e-4)
ROLLER = dict(n_rollers=14, pitch_diameter=0.0425, roller_diameter=0.0075,
              effective_length=0.0075, Kn=3.0e8)
RING = dict(n_rollers=24, pitch_radius=0.075, roller_radius=0.0065, effective_length=0.016,
            shaft_radius=0.054, housing_radius=0.097, ring_width=0.030)


def _model(name: str) -> dict:
    with open(MODELS / f"{name}.toml", "rb") as stream:
        return tomllib.load(stream)


@pytest.mark.parametrize(("make", "diameter", "element"), [
    (lambda **k: rs.BallBearing(**BALL, **k), BALL["ball_diameter"], "ball"),
    (lambda **k: rs.RollerBearing(**ROLLER, **k), ROLLER["roller_diameter"], "roller"),
])
def test_absurd_interference_of_ball_and_roller_bearings_is_refused(make, diameter, element):
    make(diametral_clearance=-20e-6)  # a real preload: 10 um radial
    limit = MAX_INTERFERENCE_RATIO * diameter
    make(radial_clearance=-0.99 * limit)  # just inside the plausible range
    for key, value in (("diametral_clearance", -1e-3), ("radial_clearance", -1.01 * limit)):
        with pytest.raises(rs.ModelError, match=rf"radial interference .* of the {element} "
                           r"diameter .*; a preload is at most 1 % \(.* um\): check the sign"):
            make(**{key: value})


def test_absurd_interference_of_a_flexible_ring_bearing_is_refused():
    rs.FlexibleRingRollerBearing(**RING, diametral_clearance=-40e-6)  # the seed 001 case
    with pytest.raises(rs.ModelError, match=r"radial interference 500 um \(diametral "
                       r"clearance -1000 um\) is 3.85 % of the roller diameter 13 mm"):
        rs.FlexibleRingRollerBearing(**RING, diametral_clearance=-1e-3)


@pytest.mark.parametrize(("model", "key", "value"), [
    ("rolling_ball", "diametral_clearance", "-1 mm"),
    ("rolling_tapered", "radial_clearance", "-0.5 mm"),
])
def test_model_file_with_absurd_interference_names_the_key(model, key, value):
    data = _model(model)
    data["rolling_bearings"][1][key] = value
    with pytest.raises(rs.ModelError, match=rf"^rolling_bearings\[1\]\.{key}: radial "
                       r"interference 500 um \(diametral clearance -1000 um\) is .* %"):
        model_from_dict(data)


def test_info_reports_the_preload_of_each_preloaded_bearing(capsys, tmp_path):
    assert main(["info", str(MODELS / "rolling_tapered.toml")]) == 0
    out = capsys.readouterr().out
    for tag in ("A", "B"):
        assert f"preload {tag}  radial interference 2 um (diametral clearance -4 um)" in out
    assert main(["info", str(MODELS / "rolling_ball.toml")]) == 0  # positive clearance
    assert "preload" not in capsys.readouterr().out


def test_a_parameter_branch_into_absurd_interference_is_refused_at_load():
    data = _model("rolling_ball")
    data["analyses"] = {"clearance": {
        "type": "periodic_parameter", "vary": "rolling_bearings.DE.diametral_clearance",
        "speed": "3000 rpm", "start": 10e-6, "stop": -1e-3}}  # numbers: SI, not tried before
    with pytest.raises(rs.ModelError, match=r"^analyses\.clearance: parameter: with "
                       r"rolling_bearings\.DE\.diametral_clearance = -0\.001: .*radial "
                       r"interference 500 um"):
        model_from_dict(data)
