"""Model-file key paths as parameters (rotorsim.io.model_parameter), the
``periodic_parameter`` analysis type and the ``rotorsim periodic-parameter`` command."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.cli.main import EXIT_BAD_INPUT, main
from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model, model_from_dict, save_model
from rotorsim.io.model_parameter import ModelParameter, current_value, si_value, with_value

MODELS = Path(__file__).resolve().parents[2] / "models"


@pytest.fixture(scope="module")
def ball():
    return load_model(MODELS / "rolling_ball.toml")


def test_paths_select_entries_by_tag_name_or_index(ball):
    data = ball.data
    assert current_value(data, "rolling_bearings.DE.diametral_clearance") == "10 um"
    assert current_value(data, "rolling_bearings.1.n_balls") == 9
    assert current_value(data, "materials.steel.E") == "211 GPa"
    assert current_value(data, "disks.disk.o_d") == "200 mm"
    assert current_value(data, "rolling_bearings.DE.preload") is None  # not given
    changed = with_value(data, "rolling_bearings.NDE.diametral_clearance", 2e-5)
    assert changed["rolling_bearings"][1]["diametral_clearance"] == 2e-5
    assert data["rolling_bearings"][1]["diametral_clearance"] == "10 um"  # a copy


@pytest.mark.parametrize("path, fragment", [
    ("rolling_bearings.XX.n_balls", "no entry 'XX' in [[rolling_bearings]]"),
    ("rolling_bearings.7.n_balls", "index 0..1"),
    ("gears.G1.ratio", "no 'gears'"),
    ("rolling_bearings", "not a key path"),
    ("rolling_bearings..n_balls", "not a key path"),
    ("rolling_bearings.DE", "ends at the array"),
    ("rolling_bearings.DE.n_balls.x", "is a value, not a table"),
])
def test_bad_paths_are_refused_naming_the_path(ball, path, fragment):
    with pytest.raises(ModelError, match="parameter") as err:
        ModelParameter(ball.data, path, model_from_dict)
    assert fragment in str(err.value)


def test_si_values_of_any_dimension():
    assert si_value("5 um", "x") == pytest.approx(5e-6, rel=1e-15)
    assert si_value("3000 rpm", "x") == pytest.approx(100 * math.pi, rel=1e-15)
    assert si_value("2 kN s/m", "x") == pytest.approx(2000.0, rel=1e-15)
    assert si_value(0.25, "x") == 0.25 and si_value("10 um", "x") == 1e-05  # exactly
    for bad in ("5 blorps", True, [1.0], "inf m"):
        with pytest.raises(ModelError, match="x"):
            si_value(bad, "x")


def test_a_parameter_rebuilds_the_model_with_the_value(ball):
    clearance = ModelParameter(ball.data, "rolling_bearings.DE.diametral_clearance",
                               model_from_dict)
    elements = clearance(14e-6)   # a path into rolling_bearings: the bearings only
    assert [e.tag for e in elements] == ["DE", "NDE"]
    assert elements[0].bearing.diametral_clearance == pytest.approx(14e-6, rel=1e-15)
    assert elements[1].bearing.diametral_clearance == pytest.approx(10e-6, rel=1e-15)
    disk = ball.parameter("disks.disk.o_d")(0.25)
    assert isinstance(disk, rs.Rotor) and [rb.tag for rb in disk.nonlinear_elements] == \
        ["DE", "NDE"]
    assert disk.disk_elements[0].m > ball.rotor.disk_elements[0].m
    # a string is checked against the key's dimension by the schema
    assert clearance.check("8 um", 1.2e-5) == (pytest.approx(8e-6), 1.2e-5)
    with pytest.raises(ModelError, match="diametral_clearance"):
        clearance.check("8 rpm", 1.2e-5)
    with pytest.raises(ModelError, match=r"disks\.disk\.o_d = -0\.1") as err:
        ball.parameter("disks.disk.o_d")(-0.1)
    assert "must be > 0" in str(err.value)


def test_model_file_analysis_converts_its_range_and_round_trips(tmp_path, ball):
    spec = ball.analyses["belt_pull"]
    assert (spec.vary, spec.start, spec.stop) == ("loads", 0.0, 2.0)
    assert spec.speed == pytest.approx(100 * math.pi, rel=1e-15)
    default = load_model(MODELS / "default.toml").analyses["clearance"]
    assert default.vary == "rolling_bearings.DE.radial_clearance"
    assert (default.start, default.stop) == (0.0, pytest.approx(20e-6, rel=1e-15))
    path = save_model(load_model(MODELS / "default.toml"), tmp_path / "again.toml")
    assert load_model(path).analyses["clearance"] == default


@pytest.mark.parametrize("changes, fragment", [
    ({"vary": "bearings.B9.cxx"}, "no 'bearings'"),
    ({"start": "3 N"}, "diametral_clearance"),
    ({"stop": "10 um"}, "start and stop are equal"),
    ({"speed": 0}, "must be > 0"),
])
def test_bad_periodic_parameter_tables_name_the_analysis(ball, changes, fragment):
    data = dict(ball.data)
    table = {"type": "periodic_parameter", "vary": "rolling_bearings.DE.diametral_clearance",
             "speed": "3000 rpm", "start": "10 um", "stop": "20 um", **changes}
    if changes.get("stop") == "10 um":
        table["start"] = 1e-5
    data["analyses"] = {"sweep": table}
    with pytest.raises(ModelError, match=r"analyses\.sweep") as err:
        model_from_dict(data)
    assert fragment in str(err.value)


def test_the_model_file_branch_equals_the_python_branch(ball):
    """run_analysis with a key path gives the branch of rs.periodic_parameter with a
    hand-written vary (same bearings, built by the Python API)."""
    from dataclasses import replace

    data = dict(ball.data)
    data["analyses"] = {"clearance": {
        "type": "periodic_parameter", "vary": "rolling_bearings.DE.diametral_clearance",
        "speed": "3000 rpm", "start": "10 um", "stop": "16 um", "harmonics": 4,
        "max_points": 12, "stability": "none", "nodes": [5]}}
    model = model_from_dict(data)
    from_file = rs.run_analysis(model, "clearance")

    def vary(c):
        de, nde = model.rolling_bearings
        return [replace(de, bearing=replace(de.bearing, diametral_clearance=c)), nde]

    loads = model.loads
    by_hand = rs.periodic_parameter(
        model.rotor.with_nonlinear(model.rolling_bearings), vary, speed=100 * math.pi,
        start=1e-5, stop=1.6e-5, harmonics=4, max_points=12, stability=None, nodes=[5],
        unbalance=list(loads.unbalance), loads=list(loads.point_loads),
        gravity=loads.gravity)
    assert from_file.parameter_name == "rolling_bearings.DE.diametral_clearance"
    np.testing.assert_allclose(from_file.parameter, by_hand.parameter, rtol=1e-12)
    np.testing.assert_allclose(from_file.coefficients, by_hand.coefficients, rtol=0,
                               atol=1e-12 * np.abs(by_hand.coefficients).max())


def test_periodic_parameter_subcommand(tmp_path, capsys):
    code = main(["periodic-parameter", str(MODELS / "rolling_ball.toml"), "--vary",
                 "rolling_bearings.NDE.diametral_clearance", "--speed", "3000 rpm",
                 "--start", "10 um", "--stop", "14 um", "--harmonics", "3",
                 "--max-points", "6", "--no-stability", "--no-plots", "--out", str(tmp_path)])
    assert code == 0
    result = rs.load(tmp_path / "rolling_ball" / "belt_pull.h5")
    assert len(result) == 6 and result.parameter[0] == pytest.approx(1e-5)
    assert result.parameter_name == "rolling_bearings.NDE.diametral_clearance"
    out = capsys.readouterr().out
    assert "rolling_bearings.NDE.diametral_clearance 1e-05 ->" in out
    assert "at 3000.0 rpm" in out


def test_periodic_parameter_subcommand_reports_bad_input(tmp_path, capsys):
    code = main(["periodic-parameter", str(MODELS / "default.toml"), "--vary",
                 "rolling_bearings.DE.radial_clearance", "--start", "5 rpm",
                 "--out", str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    assert "radial_clearance" in capsys.readouterr().err
    code = main(["periodic-parameter", str(MODELS / "friswell_5_9_1.toml"),
                 "--out", str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    assert "--vary, --speed, --start and --stop" in capsys.readouterr().err
