"""Every writer creates missing folders of its target (as the CLI does for its results
folder): results, model files, sweep stores and checkpoints (issue 12)."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.sweep.sweep import Grid, min_log_dec, set_bearing_stiffness, sweep
from rotorsim.io.model_file import load_model, save_model
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.problem import SecondOrderProblem

steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


@pytest.fixture(scope="module")
def rotor() -> rs.Rotor:
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    return rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=1e6, cxx=500.0),
                                rs.BearingElement(n=4, kxx=1e6, cxx=500.0)])


def test_save_and_save_model_create_folders(rotor, tmp_path):
    result = rs.modal(rotor, num_modes=2)
    path = rs.save(result, tmp_path / "a" / "b" / "modes.h5")
    assert np.array_equal(rs.load(path).wn, result.wn)
    model_path = save_model(rotor, tmp_path / "models" / "r.toml")
    assert load_model(model_path).rotor.n_nodes == rotor.n_nodes


def test_sweep_store_and_checkpoint_create_folders(rotor, tmp_path):
    store = tmp_path / "sweeps" / "k.h5"
    res = sweep(rotor, Grid({"bearing_k": [1e6, 1e7], "speed": [0.0]}),
                set_bearing_stiffness([0, 1]), min_log_dec(num_modes=2), store=store)
    assert store.is_file() and res.outputs["log_dec_min"].shape == (2,)
    problem = SecondOrderProblem(mass=np.eye(1), stiffness=np.eye(1))
    checkpoint = tmp_path / "runs" / "deep" / "run.h5"
    integrate(problem, Newmark(), (0.0, 1.0), [1.0], [0.0], dt=0.1, checkpoint=checkpoint)
    assert checkpoint.is_file()


def test_a_model_file_sweep_runs_in_memory_or_into_its_store(tmp_path):
    import tomllib
    from pathlib import Path

    from rotorsim.io.model_file import model_from_dict, run_analysis

    with open(Path(__file__).resolve().parents[2] / "models" / "friswell_5_9_5.toml",
              "rb") as stream:
        data = tomllib.load(stream)
    data["analyses"] = {"k": {"type": "sweep", "stiffness": [1e6, 1e7], "bearings": ["B1"],
                              "evaluate": "critical_speeds", "num_modes": 2}}
    model = model_from_dict(data)
    in_memory = run_analysis(model, "k")
    assert in_memory.options["store"] is None
    assert in_memory.outputs["critical_speeds"].shape == (2, 2)
    # the two stiffnesses give different first critical speeds (the sweep varied B1)
    assert in_memory.outputs["critical_speeds"][0, 0] < in_memory.outputs["critical_speeds"][1, 0]
    stored = run_analysis(model, "k", checkpoint_dir=tmp_path / "out")
    assert (tmp_path / "out" / "k.h5").is_file()
    np.testing.assert_array_equal(stored.outputs["critical_speeds"],
                                  rs.load(tmp_path / "out" / "k.h5").outputs["critical_speeds"])
