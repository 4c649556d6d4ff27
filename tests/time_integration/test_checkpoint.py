"""Checkpoints: an interrupted and resumed run equals an uninterrupted one bit for bit;
damaged or foreign checkpoints are refused with a clear error."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import h5py
import numpy as np
import pytest

from rotorsim.errors import ConvergenceError
from rotorsim.time_integration.adaptive import Adaptive
from rotorsim.time_integration.checkpoint import CheckpointError, load_checkpoint
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.output import OutputSpec, Reducer
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.radau import Radau


class Interrupted(Exception):
    pass


def stop_after(step):
    def callback(state):
        if state.step == step:
            raise Interrupted

    return callback


def duffing(load_nan_after=np.inf):
    def restoring(q, v, t):
        return 0.1 * q**3, np.diag(0.3 * q**2), None

    def load(t):
        return np.array([0.18 * np.cos(1.2 * t), np.nan if t > load_nan_after else 0.0])

    K = np.array([[1.0, -0.2], [-0.2, 0.5]])
    return SecondOrderProblem(np.eye(2), K, 0.05 * np.eye(2), restoring=restoring, load=load)


RUNS = {
    "hht-times": (Newmark.hht(-0.1), OutputSpec(times=np.linspace(0.0, 20.0, 333),
                                                reducers=(Reducer("max_abs", after=5.0),))),
    "adaptive-every": (Adaptive(Newmark.generalized_alpha(0.7), rtol=1e-5),
                       OutputSpec(every=3, dofs=[1], reducers=(Reducer("min", "v"),))),
    "radau-times": (Radau(rtol=1e-5), OutputSpec(times=np.linspace(0.0, 20.0, 101))),
}


def assert_identical(a, b):
    assert np.array_equal(a.t, b.t) and np.array_equal(a.q, b.q)
    assert (a.v is None and b.v is None) or np.array_equal(a.v, b.v)
    assert a.reduced.keys() == b.reduced.keys()
    for key in a.reduced:
        assert np.array_equal(a.reduced[key], b.reduced[key], equal_nan=True)
    for name in ("q", "v", "a", "force", "peak"):
        assert np.array_equal(getattr(a.state, name), getattr(b.state, name))
    assert (a.state.t, a.state.step, a.state.dt) == (b.state.t, b.state.step, b.state.dt)


@pytest.mark.parametrize("name", list(RUNS))
def test_resumed_run_is_bitwise_identical_to_uninterrupted_run(name, tmp_path):
    stepper, spec = RUNS[name]
    problem = duffing()
    args = (problem, stepper, (0.0, 20.0), [1.0, -0.5], [0.0, 0.3])
    whole = integrate(*args, dt=0.05, output=spec)
    path = tmp_path / "run.h5"
    with pytest.raises(Interrupted):
        integrate(*args, dt=0.05, output=spec, checkpoint=path, checkpoint_every=7,
                  callback=stop_after(penultimate := 7 * 9 + 3))
    state, _, _ = load_checkpoint(path)
    assert state.step == 7 * 9 < penultimate  # the last checkpoint before the interruption
    assert [p.name for p in tmp_path.iterdir()] == ["run.h5"]  # no temporary file left
    taken: list[int] = []
    resumed = integrate(*args, dt=0.05, output=spec, checkpoint=path, checkpoint_every=7,
                        resume=path, callback=lambda s: taken.append(s.step))
    assert taken[0] == 7 * 9 + 1 and taken[-1] == whole.state.step  # continued, not redone
    assert_identical(whole, resumed)
    for key in ("iterations", "residual_evaluations", "rejected_steps", "steps"):
        assert resumed.stats[key] == whole.stats[key]
    # a finished run's checkpoint resumes to the same result without stepping
    taken.clear()
    again = integrate(*args, dt=0.05, output=spec, resume=path,
                      callback=lambda s: taken.append(s.step))
    assert not taken
    assert_identical(whole, again)


def test_failed_run_leaves_its_last_checkpoint(tmp_path):
    path = tmp_path / "run.h5"
    with pytest.raises(ConvergenceError, match="not finite"):
        integrate(duffing(load_nan_after=1.01), Newmark(), (0.0, 5.0), [1.0, 0.0], [0.0, 0.0],
                  dt=0.05, checkpoint=path, checkpoint_every=4)
    state, output, _ = load_checkpoint(path)
    assert state.step == 20 and output["t"][-1, 0] == state.t == pytest.approx(1.0)


@pytest.fixture
def finished(tmp_path):
    path = tmp_path / "run.h5"
    args = (duffing(), Newmark(), (0.0, 1.0), [1.0, 0.0], [0.0, 0.0])
    integrate(*args, dt=0.1, checkpoint=path, checkpoint_every=3)
    return path, args


@pytest.mark.parametrize("change, culprit", [
    (dict(dt=0.05), "dt"),
    (dict(stepper=Newmark.hht(-0.1)), "stepper"),
    (dict(t_span=(0.0, 2.0)), "t_span"),
    (dict(q0=[1.0, 1e-9]), "initial"),
    (dict(output=OutputSpec(every=2)), "output"),
    (dict(problem=SecondOrderProblem(np.eye(2), np.eye(2))), "problem"),
])
def test_checkpoint_of_another_run_is_refused(finished, change, culprit):
    path, (problem, stepper, t_span, q0, v0) = finished
    kwargs = dict(problem=problem, stepper=stepper, t_span=t_span, q0=q0, v0=v0, dt=0.1)
    kwargs.update(change)
    with pytest.raises(CheckpointError, match=rf"different run \(.*{culprit}: checkpoint"):
        integrate(**kwargs, resume=path)


def test_damaged_checkpoints_are_refused(finished, tmp_path):
    path, args = finished
    garbage = tmp_path / "garbage.h5"
    garbage.write_bytes(b"not hdf5 at all" * 10)
    with pytest.raises(CheckpointError, match="not a readable HDF5 file"):
        integrate(*args, dt=0.1, resume=garbage)
    truncated = tmp_path / "truncated.h5"
    truncated.write_bytes(path.read_bytes()[:600])
    with pytest.raises(CheckpointError, match=r"not a readable HDF5 file|corrupted"):
        integrate(*args, dt=0.1, resume=truncated)
    cases = {
        "missing": lambda f: f["state"].__delitem__("q"),
        "shape": lambda f: (f["state"].__delitem__("v"),
                            f["state"].create_dataset("v", data=np.zeros(3))),
        "version": lambda f: f.attrs.__setitem__("format_version", 99),
        "format": lambda f: f.attrs.__setitem__("format", "rotorsim-results"),
    }
    messages = {"missing": "corrupted or incomplete", "shape": "state/v has shape",
                "version": "format_version 99 is not supported", "format": "not a rotorsim"}
    for case, damage in cases.items():
        copy = tmp_path / f"{case}.h5"
        copy.write_bytes(path.read_bytes())
        with h5py.File(copy, "r+") as f:
            damage(f)
        with pytest.raises(CheckpointError, match=messages[case]) as info:
            integrate(*args, dt=0.1, resume=copy)
        assert str(copy) in str(info.value)
    with pytest.raises(FileNotFoundError):
        integrate(*args, dt=0.1, resume=tmp_path / "absent.h5")


def test_state_round_trips_through_a_checkpoint(finished):
    path, _ = finished
    state, output, config = load_checkpoint(path)
    assert state.cache is None and state.step == 10 and state.t == 1.0
    assert dataclasses.asdict(state.counters)["factorizations"] >= 1
    assert config["stepper"]["options"]["method"] == "average_acceleration"
    assert output["q"].shape == (11, 2) and Path(path).stat().st_size > 0
