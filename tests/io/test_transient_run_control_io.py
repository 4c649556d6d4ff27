"""Run control of transients from model files and the command line: the keys ``every``,
``velocities``, ``reducers``, ``after``, ``stop_when_steady``, ``steady_*``; results files
store the reductions as datasets and the final state, from which a run continues."""

from __future__ import annotations

from pathlib import Path

import h5py
import numpy as np
import pytest
from transient_tables import rolling_ball_with_transient

import rotorsim as rs
from rotorsim.cli.main import main
from rotorsim.errors import ModelError
from rotorsim.io.model_file import model_from_dict, run_analysis, save_model

MODELS = Path(__file__).resolve().parents[2] / "models"
EXIT_BAD_INPUT = 2


def _raw(**transient):
    return rolling_ball_with_transient(**{"t_end": "8 ms", "dt": "20 us", **transient})


def test_model_file_keys_fill_output_and_steady(tmp_path):
    raw = _raw(every=50, velocities=True, reducers=["peak_to_peak", "rms"], after=0.002,
               stop_when_steady=True, steady_rtol=0.05, steady_revolutions=2)
    model = model_from_dict(raw, source="m.toml")
    spec = model.analyses["run"]
    assert spec.output == rs.Output(every=50, velocities=True,
                                    reducers=("peak_to_peak", "rms"), after=0.002)
    assert spec.stop_when_steady and spec.steady == rs.SteadyStop(rtol=0.05, revolutions=2)
    written = spec.to_toml()
    assert written["reducers"] == ["peak_to_peak", "rms"] and written["steady_rtol"] == 0.05
    again = rs.load_model(save_model(model, tmp_path / "m.toml")).analyses["run"]
    assert again.output == spec.output and again.steady == spec.steady
    result = run_analysis(model, "run")
    assert list(result.reduced) == ["peak_to_peak", "peak_to_peak_revolution", "rms"]
    assert result.v is not None and result.final is not None
    assert result.t.size == 9  # every 50th of 400 steps and the first


def test_bad_reducer_in_a_model_file_names_the_key():
    with pytest.raises(ModelError, match=r"analyses\.run\.reducers"):
        model_from_dict(_raw(reducers=["max", "p2p"]), source="m.toml")


def test_results_file_stores_reductions_as_datasets_and_continues(tmp_path):
    model = rs.load_model(MODELS / "rolling_ball.toml")
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    kw = dict(speed=300.0, nodes=[5], output=rs.Output(reducers=("max_amplitude",
                                                                 "peak_to_peak")))
    half = rs.transient(rotor, 0.002, 2e-5, **kw)
    path = tmp_path / "half.h5"
    rs.save(half, path)
    with h5py.File(path, "r") as f:
        group = next(g for g in f.values() if isinstance(g, h5py.Group))
        assert isinstance(group["reduced"]["max_amplitude"], h5py.Dataset)
        assert group["reduced"]["max_amplitude"].attrs["units"].startswith("m, rad")
        assert isinstance(group["final"]["stepper"]["q"], h5py.Dataset)
    loaded = rs.load(path)
    np.testing.assert_array_equal(loaded.reduced["peak_to_peak"], half.reduced["peak_to_peak"])
    np.testing.assert_array_equal(loaded.final.stepper.a, half.final.stepper.a)
    more = rs.transient(rotor, 0.004, 2e-5, initial=loaded, **kw)
    assert more.t[0] == half.t[-1] and more.angle[0] == half.angle[-1]


JEFFCOTT = """
[[disks]]
node = 0
m = "2.5 kg"
Id = "1e-3 kg*m^2"
Ip = "2e-3 kg*m^2"

[[bearings]]
node = 0
kxx = "4e6 N/m"
cxx = "126.5 N*s/m"

[[fixed]]
node = 0
dofs = ["uz", "rx", "ry", "rz"]

[loads]
gravity = false

[[loads.unbalance]]
node = 0
magnitude = "1e-4 kg*m"
phase = 0
"""


def test_transient_subcommand_with_reducers_and_steady_stop(tmp_path, capsys):
    """A Jeffcott rotor (damping ratio 0.02, wn 1265 rad/s) at 7000 rpm: its free vibration
    decays as exp(-25 t), so the peak-to-peak per revolution settles within 1e-3 after
    ~0.3 s (tests/analyses/transient/test_transient_run_control.py checks it against the exact
    response)."""
    path = tmp_path / "jeffcott.toml"
    path.write_text(JEFFCOTT)
    code = main(["transient", str(path), "--t-end", "1 s", "--dt", "20 us",
                 "--speed", "7000 rpm", "--every", "1000", "--reducers", "max_amplitude,rms",
                 "--stop-when-steady", "--steady-rtol", "1e-3", "--no-plots",
                 "--out", str(tmp_path)])
    assert code == 0
    result = rs.load(tmp_path / "jeffcott" / "transient.h5")
    assert result.stopped is not None and 0.15 < result.t[-1] < 0.6
    assert set(result.reduced) == {"max_amplitude", "rms"} and result.v is None
    out = capsys.readouterr().out
    assert "stopped early at t = " in out and "max radial amplitude" in out


def test_transient_subcommand_refuses_an_unknown_reducer(tmp_path, capsys):
    code = main(["transient", str(MODELS / "rolling_ball.toml"), "--t-end", "10 ms",
                 "--dt", "50 us", "--reducers", "peak", "--out", str(tmp_path)])
    assert code == EXIT_BAD_INPUT
    assert "reducers" in capsys.readouterr().err
