"""The accuracy ``rtol`` of a transient in model files and on the command line (issue 14):
a ``transient`` table takes ``dt`` (a fixed step) or ``rtol`` (the error-controlled method
``auto``), is refused with a message naming the key for bad values and combinations, writes
``rtol`` back, and runs as ``rs.transient(..., rtol=...)``; ``rotorsim transient --rtol``
does the same for one run."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from transient_tables import rolling_ball_with_transient

import rotorsim as rs
from rotorsim.cli.main import main
from rotorsim.errors import ModelError
from rotorsim.io.long_specs import TransientSpec
from rotorsim.io.model_file import model_from_dict, run_analysis, save_model

MODELS = Path(__file__).resolve().parents[2] / "models"
EXIT_BAD_INPUT = 2


def _raw(**transient):
    return rolling_ball_with_transient(**{"t_end": "3 ms", **transient})


def test_rtol_in_a_model_file_runs_the_automatic_path_as_the_api(tmp_path):
    model = model_from_dict(_raw(rtol=1e-4), source="m.toml")
    spec = model.analyses["run"]
    assert (spec.dt, spec.rtol, spec.method) == (None, 1e-4, None)
    assert spec.to_toml()["rtol"] == 1e-4 and "dt" not in spec.to_toml()
    again = rs.load_model(save_model(model, tmp_path / "m.toml")).analyses["run"]
    assert again == spec
    result = run_analysis(model, "run")
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    loads = model.loads
    direct = rs.transient(rotor, 3e-3, rtol=1e-4, speed=6000 * np.pi / 30, nodes=[5],
                          unbalance=list(loads.unbalance),
                          excitation=rs.Excitation(gravity=loads.gravity,
                                                   direction=loads.gravity_direction,
                                                   loads=list(loads.point_loads)),
                          on_failure="stop")
    # constant speed, gravity and unbalance on a small model: exponential collocation
    assert result.method == direct.method == "exponential" and result.options["rtol"] == 1e-4
    np.testing.assert_array_equal(result.q, direct.q)  # the same call: the same numbers


def test_method_auto_alone_runs_at_the_default_accuracy():
    spec = model_from_dict(_raw(method="auto"), source="m.toml").analyses["run"]
    assert (spec.dt, spec.rtol, spec.method) == (None, None, "auto")
    assert model_from_dict(_raw(rtol="1e-5"), source="m.toml").analyses["run"].rtol == 1e-5


@pytest.mark.parametrize(("keys", "message"), [
    (dict(rtol=0), r"analyses\.run\.rtol: must be > 0"),
    (dict(rtol=-1e-4), r"analyses\.run\.rtol: must be > 0"),
    (dict(rtol=0.5), r"analyses\.run\.rtol: .*in \[1e-10, 0\.1\]"),
    (dict(rtol=1e-12), r"analyses\.run\.rtol: .*in \[1e-10, 0\.1\]"),
    (dict(rtol="fine"), r"analyses\.run\.rtol"),
    (dict(rtol=1e-4, dt="20 us"), r"analyses\.run\.rtol: give dt .* or rtol .*not both"),
    (dict(rtol=1e-4, method="hht"), r"analyses\.run\.rtol: rtol is the accuracy of method "
                                    r"'auto'; method 'hht' takes a fixed dt"),
    (dict(method="auto", dt="20 us"), r"analyses\.run\.dt: method 'auto' chooses its own"),
    (dict(), r"analyses\.run\.dt: give dt .* or rtol"),
    (dict(dt="5 ms"), r"analyses\.run\.dt: .*exceeds t_end"),
])
def test_bad_step_options_in_a_model_file_name_the_key(keys, message):
    with pytest.raises(ModelError, match=message):
        model_from_dict(_raw(**keys), source="m.toml")


def test_specs_built_in_code_are_checked_the_same_way():
    assert TransientSpec(t_end=1.0, rtol=1e-5).method is None
    with pytest.raises(ModelError, match=r"transient\.rtol: give dt"):
        TransientSpec(t_end=1.0, dt=1e-4, rtol=1e-5)
    with pytest.raises(ModelError, match=r"transient\.dt: give dt"):
        TransientSpec(t_end=1.0)
    with pytest.raises(ModelError, match=r"transient\.rtol: rtol must be a number in"):
        TransientSpec(t_end=1.0, rtol=0.0)


def test_transient_subcommand_takes_rtol_in_place_of_the_models_dt(tmp_path, capsys):
    path = tmp_path / "m.toml"
    model = model_from_dict(_raw(dt="20 us", method="hht"), source="m.toml")
    save_model(model, path)
    code = main(["transient", str(path), "--rtol", "1e-4", "--t-end", "2 ms", "--no-plots",
                 "--no-progress", "--out", str(tmp_path)])
    assert code == 0, capsys.readouterr().err
    result = rs.load(next(tmp_path.glob("*/run.h5")))  # folder named after [model] name
    assert result.method == "exponential" and result.options["rtol"] == 1e-4


@pytest.mark.parametrize(("options", "message"), [
    (["--rtol", "1e-4", "--dt", "20 us"], "--dt .* or --rtol .*not both"),
    (["--rtol", "0"], "must be a number in"),
    (["--rtol=-1e-3"], "must be a number in"),
])
def test_transient_subcommand_refuses_bad_step_options(tmp_path, capsys, options, message):
    code = main(["transient", str(MODELS / "rolling_ball.toml"), "--t-end", "2 ms",
                 *options, "--no-plots", "--out", str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    assert any(re.search(message, line)
               for line in capsys.readouterr().err.splitlines())


def test_transient_subcommand_without_an_analysis_needs_dt_or_rtol(tmp_path, capsys):
    path = tmp_path / "bare.toml"
    raw = _raw()
    del raw["analyses"]
    save_model(model_from_dict(raw, source="bare.toml"), path)
    code = main(["transient", str(path), "--t-end", "2 ms", "--no-plots", "--out",
                 str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    assert "--dt (or --rtol)" in capsys.readouterr().err
