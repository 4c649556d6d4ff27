"""Parameter sweeps: spaces, executors, failure recording, resume after interruption."""

from __future__ import annotations

import concurrent.futures as cf
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.analyses.sweep.sweep import (
    Grid,
    Normal,
    Sample,
    Uniform,
    chain,
    critical_speeds_eval,
    min_log_dec,
    scale_bearing_stiffness,
    scale_disk_mass,
    set_bearing_stiffness,
    sweep,
)
from rotorsim.elements.disk import DiskElement
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.io.sweep_store import load_sweep
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

STEEL = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810.0)
# dense eigen solvers: ARPACK starts from a random vector, so its results differ in the
# last digits from call to call; the dense path is bitwise reproducible
CRITICAL = critical_speeds_eval(1.0, 2, whirl="forward", sparse=False)
# Results of different processes, threads or code paths are compared at the accuracy of
# the dense eigen solver, not bit for bit: a worker may run its BLAS with another number
# of threads or another kernel, which changes the last bits. The eigen solve is backward
# stable (n eps cond ~ 1e-13 on these 20-DOF models); 1e-8 is the margin kept for eigen
# results, and any mix-up of points or parameters moves the speeds by > 1e-3.
EIGEN_RTOL = 1e-8
# log dec = -2 pi Re(lam) / Im(lam): an eigenvalue error of EIGEN_RTOL |lam| moves it by at
# most 2 pi EIGEN_RTOL in absolute terms (the log decs here go through zero)
LOG_DEC_ATOL = 2 * np.pi * EIGEN_RTOL


def assert_outputs_agree(result, reference, name: str = "") -> None:
    """Every output of ``result`` equals ``reference`` at the eigen-solver accuracy."""
    assert sorted(result.outputs) == sorted(reference.outputs), name
    for key, expected in reference.outputs.items():
        if key.startswith("log_dec"):
            np.testing.assert_allclose(result.outputs[key], expected, rtol=0,
                                       atol=LOG_DEC_ATOL, err_msg=f"{name} {key}")
        else:
            np.testing.assert_allclose(result.outputs[key], expected, rtol=EIGEN_RTOL,
                                       err_msg=f"{name} {key}")


def small_rotor(k: float = 1e6, c: float = 0.0) -> Rotor:
    """A 1 m shaft on two bearings with one disk; lateral DOFs only (20 free DOFs)."""
    shaft = [ShaftElement(L=0.25, idl=0.0, odl=0.05, material=STEEL) for _ in range(4)]
    disk = DiskElement.from_geometry(2, STEEL, width=0.05, i_d=0.05, o_d=0.25)
    bearings = [BearingElement(n=n, kxx=k, cxx=c) for n in (0, 4)]
    return Rotor(shaft, [disk], bearings, tag="small").without_axial_torsion()


def stiffness_grid() -> Grid:
    return Grid({"bearing_k": np.logspace(5.5, 7.5, 5), "disk_scale": [0.8, 1.0, 1.25]})


APPLY = chain(set_bearing_stiffness([0, 1], "bearing_k"), scale_disk_mass(0, "disk_scale"))


# ---------------------------------------------------------------------------- spaces
def test_grid_is_a_cartesian_product_with_the_last_parameter_fastest():
    g = Grid({"a": [1.0, 2.0], "b": [10.0, 20.0, 30.0]})
    assert g.shape == (2, 3) and g.n_points == 6 and g.names == ("a", "b")
    assert g.values.tolist() == [[1, 10], [1, 20], [1, 30], [2, 10], [2, 20], [2, 30]]
    assert g.point(5) == {"a": 2.0, "b": 30.0}
    with pytest.raises(ValueError):  # read-only: a space is immutable
        g.values[0, 0] = 5.0


@pytest.mark.parametrize("parameters, culprit", [
    ({"k": []}, "Grid['k']"),
    ({"k": [[1.0, 2.0]]}, "Grid['k']"),
    ({"k": [1.0, np.nan]}, "Grid['k']"),
    ({"k": ["stiff"]}, "Grid['k']"),
    ({}, "needs at least one parameter"),
    ({"a/b": [1.0]}, "without '/'"),
    ([1.0, 2.0], "mapping"),
])
def test_grid_rejects_bad_values(parameters, culprit):
    with pytest.raises(ModelError, match=culprit.replace("[", r"\[").replace("]", r"\]")):
        Grid(parameters)


def test_sample_is_reproducible_and_follows_its_distributions():
    dists = {"k": Normal(1e6, 5e4), "m": Uniform(9.0, 11.0)}
    a, b = Sample(4000, dists, seed=7), Sample(4000, dists, seed=7)
    assert np.array_equal(a.values, b.values) and a.shape is None and a.n_points == 4000
    assert not np.array_equal(a.values, Sample(4000, dists, seed=8).values)
    k, m = a.values.T
    # 4000 draws: standard error of the mean 5e4 / sqrt(4000) = 790 N/m; 5 SE bounds
    assert abs(k.mean() - 1e6) < 5 * 5e4 / np.sqrt(4000)
    assert abs(k.std() / 5e4 - 1) < 5 / np.sqrt(2 * 4000)
    assert m.min() >= 9.0 and m.max() < 11.0


@pytest.mark.parametrize("kwargs, culprit", [
    ({"seed": None}, "Sample.seed"),
    ({"seed": -1}, "Sample.seed"),
    ({"seed": 1.5}, "Sample.seed"),
    ({"seed": True}, "Sample.seed"),
    ({"n": 0}, "Sample.n"),
    ({"distributions": {"k": "normal"}}, "unknown distribution"),
    ({"distributions": {"k": (1e6, 5e4)}}, "unknown distribution"),
    ({"distributions": {}}, "needs at least one parameter"),
])
def test_sample_rejects_bad_input(kwargs, culprit):
    args = {"n": 3, "distributions": {"k": Normal(1.0, 0.1)}, "seed": 0, **kwargs}
    with pytest.raises(ModelError, match=culprit):
        Sample(**args)


@pytest.mark.parametrize("make", [lambda: Normal(1.0, -0.1), lambda: Normal(np.inf, 1.0),
                                  lambda: Uniform(2.0, 1.0), lambda: Uniform(0.0, "1")])
def test_distributions_validate_their_parameters(make):
    with pytest.raises(ModelError):
        make()


# ---------------------------------------------------------------------------- sweep
def test_serial_sweep_matches_direct_analyses_point_by_point():
    rotor = small_rotor()
    space = stiffness_grid()
    res = sweep(rotor, space, APPLY, CRITICAL)
    assert res.kind == "grid" and res.shape == (5, 3) and res.status == Status.OK
    assert res.outputs["critical_speeds"].shape == (15, 2)
    for i in (0, 7, 14):  # rebuilt by hand: bearings replaced, disk scaled
        k, s = space.values[i]
        d = rotor.disk_elements[0]
        model = Rotor(rotor.shaft_elements, [DiskElement(2, d.m * s, d.Id * s, d.Ip * s)],
                      [BearingElement(n=n, kxx=k) for n in (0, 4)], fixed=rotor.fixed)
        expected = critical_speeds(model, 1, 2, whirl="forward", sparse=False).speed
        # another model-building path (disk rebuilt by hand): solver accuracy, not bits
        np.testing.assert_allclose(res.outputs["critical_speeds"][i], expected,
                                   rtol=EIGEN_RTOL)
    # heavier disk -> lower first critical speed; stiffer bearings -> higher
    first = res.reshape("critical_speeds")[..., 0]
    assert np.all(np.diff(first, axis=1) < 0) and np.all(np.diff(first, axis=0) > 0)
    assert res.axis("disk_scale").tolist() == [0.8, 1.0, 1.25]
    assert res.stats["evaluated"] == 15 and res.stats["resumed"] == 0
    assert res.to_dict()["shape"] == [5, 3]


def test_scaled_stiffness_equals_set_stiffness():
    rotor = small_rotor(k=2e6)
    scaled = sweep(rotor, Grid({"f": [0.5, 2.0]}),
                   scale_bearing_stiffness([0, 1], "f"), CRITICAL)
    direct = sweep(rotor, Grid({"k": [1e6, 4e6]}), set_bearing_stiffness([0, 1], "k"), CRITICAL)
    # 2e6 x 0.5 and 2e6 x 2 are exact, but the two functions build the bearings differently
    assert_outputs_agree(scaled, direct)


def test_sample_sweep_cannot_be_reshaped():
    res = sweep(small_rotor(), Sample(3, {"k": Normal(1e6, 1e4)}, seed=1),
                set_bearing_stiffness([0, 1], "k"), CRITICAL)
    assert res.kind == "sample" and res.outputs["critical_speeds"].shape == (3, 2)
    with pytest.raises(ModelError, match="needs a grid"):
        res.reshape("critical_speeds")


def _rotor_then_fail(rotor, params):
    if params["k"] == 3e6:
        raise ConvergenceError("synthetic failure", "test", iteration=7)
    return rotor


def test_failures_are_recorded_with_status_and_nan():
    space = Grid({"k": [1e6, -1e6, 3e6, 2e6]})  # -1e6: BearingElement rejects it
    apply = chain(set_bearing_stiffness([0, 1], "k"), _rotor_then_fail)
    res = sweep(small_rotor(), space, apply, CRITICAL)
    assert res.point_status.tolist() == [Status.OK, Status.FAILED, Status.NOT_CONVERGED,
                                         Status.OK]
    assert res.status == Status.FAILED  # the worst point status
    out = res.outputs["critical_speeds"]
    assert np.all(np.isnan(out[[1, 2]])) and np.all(np.isfinite(out[[0, 3]]))
    assert "ModelError" in res.messages[1] and "kxx" in res.messages[1]
    assert "synthetic failure" in res.messages[2] and res.messages[0] == ""
    assert res.stats["failed"] == 2
    with pytest.raises(ModelError, match="kxx"):
        sweep(small_rotor(), space, apply, CRITICAL, on_failure="raise")


def _bug(rotor, params):
    if params["k"] > 1.5e6:
        raise ZeroDivisionError("a bug, not a model failure")
    return {"y": params["k"]}


def test_other_exceptions_abort_but_keep_stored_points(tmp_path):
    store = tmp_path / "bug.h5"
    with pytest.raises(ZeroDivisionError):
        sweep(small_rotor(), Grid({"k": [1e6, 2e6, 1.2e6]}), None, _bug, store=store)
    partial = load_sweep(store)
    assert partial.point_status.tolist() == [Status.OK, Status.SKIPPED, Status.SKIPPED]
    assert partial.outputs["y"][0] == 1e6 and np.isnan(partial.outputs["y"][1])


@pytest.mark.parametrize("kwargs, error", [
    ({"executor": "threads"}, TypeError), ({"executor": 3}, TypeError),
    ({"on_failure": "ignore"}, TypeError), ({"max_workers": 0}, TypeError),
    ({"evaluate": "modal"}, TypeError), ({"space": {"k": [1.0]}}, ModelError),
    ({"rotor": "rotor.toml"}, ModelError), ({"apply": 5}, TypeError),
])
def test_sweep_rejects_bad_options(kwargs, error):
    args = {"rotor": small_rotor(), "space": Grid({"k": [1.0]}), "apply": None,
            "evaluate": CRITICAL, **kwargs}
    with pytest.raises(error):
        sweep(**args)


def test_process_executor_needs_picklable_functions():
    with pytest.raises(TypeError, match="picklable"):
        sweep(small_rotor(), Grid({"k": [1.0]}), None, lambda r, p: {"y": 1.0},
              executor="process")


# ---------------------------------------------------------------------------- executors
@pytest.fixture(scope="module")
def dask_client():
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                       dashboard_address=None)
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


def _stability_case():
    rotor = small_rotor(c=500.0)
    q = np.array([0.0, 400.0]) * 0.5 * 500.0
    seals = [BearingElement(n=n, kxx=1e6, cxx=500.0, kxy=q, kyx=-q, frequency=[0.0, 400.0])
             for n in (0, 4)]
    space = Grid({"bearing_k": [3e5, 1e6, 3e6], "speed": np.linspace(0.0, 400.0, 6)})
    return rotor.with_bearings(seals), space, set_bearing_stiffness([0, 1], "bearing_k"), \
        min_log_dec("speed", 4, sparse=False)


def test_process_and_thread_executors_agree_with_serial(tmp_path):
    rotor, space, apply, evaluate = _stability_case()
    serial = sweep(rotor, space, apply, evaluate)
    assert np.any(serial.outputs["log_dec_min"] < 0) and np.any(serial.outputs["log_dec_min"] > 0)
    runs = {"process": sweep(rotor, space, apply, evaluate, executor="process", max_workers=2,
                             store=tmp_path / "process.h5")}
    with cf.ThreadPoolExecutor(2) as pool:
        runs["threads"] = sweep(rotor, space, apply, evaluate, executor=pool)
    for name, res in runs.items():
        assert res.status == Status.OK, name
        assert_outputs_agree(res, serial, name)
    # the store holds what the process sweep returned (the same numbers, written once)
    np.testing.assert_array_equal(load_sweep(tmp_path / "process.h5").outputs["log_dec"],
                                  runs["process"].outputs["log_dec"])


def test_dask_executor_agrees_with_serial(tmp_path, dask_client):
    rotor, space, apply, evaluate = _stability_case()
    serial = sweep(rotor, space, apply, evaluate)
    res = sweep(rotor, space, apply, evaluate, executor=dask_client, store=tmp_path / "dask.h5")
    assert res.status == Status.OK
    assert_outputs_agree(res, serial, "dask")
    np.testing.assert_array_equal(load_sweep(tmp_path / "dask.h5").outputs["log_dec"],
                                  res.outputs["log_dec"])
    assert res.options["executor"] == "Client"


def test_dask_records_failures_like_serial(dask_client):
    space = Grid({"k": [1e6, -1e6, 2e6]})
    apply = set_bearing_stiffness([0, 1], "k")
    res = sweep(small_rotor(), space, apply, CRITICAL, executor=dask_client)
    assert res.point_status.tolist() == [Status.OK, Status.FAILED, Status.OK]
    with pytest.raises(ModelError):
        sweep(small_rotor(), space, apply, CRITICAL, executor=dask_client, on_failure="raise")


# ---------------------------------------------------------------------------- resume
HELPER = """
import os
from rotorsim.analyses.sweep.sweep import critical_speeds_eval

_CALLS = [0]
_CRITICAL = critical_speeds_eval(1.0, 2, whirl="forward", sparse=False)


def evaluate(rotor, params):
    '''Critical speeds; dies (os._exit) or raises KeyboardInterrupt at call ROTORSIM_DIE_AT.'''
    _CALLS[0] += 1
    if str(_CALLS[0]) == os.environ.get("ROTORSIM_DIE_AT"):
        if os.environ.get("ROTORSIM_DIE_HOW") == "interrupt":
            raise KeyboardInterrupt
        os._exit(3)
    return _CRITICAL(rotor, params)
"""

SCRIPT = """
import sys
sys.path.insert(0, {tests!r})
sys.path.insert(0, {helper!r})
import sweep_interrupt_helper as helper
from test_sweep import APPLY, small_rotor, stiffness_grid
from rotorsim.analyses.sweep.sweep import sweep

if __name__ == "__main__":
    sweep(small_rotor(), stiffness_grid(), APPLY, helper.evaluate, store={store!r},
          executor={executor!r}, max_workers=2)
"""


@pytest.fixture
def helper(tmp_path, monkeypatch):
    (tmp_path / "sweep_interrupt_helper.py").write_text(textwrap.dedent(HELPER))
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delenv("ROTORSIM_DIE_AT", raising=False)
    sys.modules.pop("sweep_interrupt_helper", None)
    import sweep_interrupt_helper

    yield sweep_interrupt_helper
    sys.modules.pop("sweep_interrupt_helper", None)


def _run_killed(tmp_path: Path, store: Path, executor: str, die_at: int) -> int:
    script = tmp_path / "run_sweep.py"
    script.write_text(SCRIPT.format(tests=str(Path(__file__).parent), helper=str(tmp_path),
                                    store=str(store), executor=executor))
    env = {**__import__("os").environ, "ROTORSIM_DIE_AT": str(die_at)}
    return subprocess.run([sys.executable, str(script)], env=env, capture_output=True,
                          timeout=120).returncode


def test_sweep_killed_in_a_subprocess_resumes_to_the_uninterrupted_result(tmp_path, helper):
    reference = sweep(small_rotor(), stiffness_grid(), APPLY, helper.evaluate)
    store = tmp_path / "killed.h5"
    assert _run_killed(tmp_path, store, "serial", die_at=8) == 3  # os._exit inside point 7
    partial = load_sweep(store)
    assert partial.point_status.tolist() == [Status.OK] * 7 + [Status.SKIPPED] * 8
    np.testing.assert_array_equal(partial.outputs["critical_speeds"][:7],
                                  reference.outputs["critical_speeds"][:7])
    assert np.all(np.isnan(partial.outputs["critical_speeds"][7:]))
    resumed = sweep(small_rotor(), stiffness_grid(), APPLY, helper.evaluate, store=store)
    assert resumed.stats["resumed"] == 7 and resumed.stats["evaluated"] == 8
    assert resumed.status == Status.OK
    np.testing.assert_array_equal(resumed.outputs["critical_speeds"],
                                  reference.outputs["critical_speeds"])
    np.testing.assert_array_equal(load_sweep(store).outputs["critical_speeds"],
                                  reference.outputs["critical_speeds"])


def test_worker_death_in_a_process_pool_keeps_finished_points(tmp_path, helper):
    reference = sweep(small_rotor(), stiffness_grid(), APPLY, helper.evaluate)
    store = tmp_path / "pool.h5"
    # each worker counts its own calls: the first to reach call 4 dies, the parent
    # gets BrokenProcessPool after storing what had arrived
    assert _run_killed(tmp_path, store, "process", die_at=4) != 0
    partial = load_sweep(store)
    done = partial.point_status == Status.OK
    assert 3 <= done.sum() < 15
    # points of pool workers against the serial reference: solver accuracy (EIGEN_RTOL)
    np.testing.assert_allclose(partial.outputs["critical_speeds"][done],
                               reference.outputs["critical_speeds"][done], rtol=EIGEN_RTOL)
    resumed = sweep(small_rotor(), stiffness_grid(), APPLY, helper.evaluate, store=store)
    assert resumed.stats["resumed"] == done.sum()
    # the resumed points are read back bit for bit from the store
    np.testing.assert_array_equal(resumed.outputs["critical_speeds"][done],
                                  partial.outputs["critical_speeds"][done])
    np.testing.assert_allclose(resumed.outputs["critical_speeds"],
                               reference.outputs["critical_speeds"], rtol=EIGEN_RTOL)


def test_keyboard_interrupt_keeps_finished_points(tmp_path, helper, monkeypatch):
    reference = sweep(small_rotor(), stiffness_grid(), APPLY, helper.evaluate)
    store = tmp_path / "ctrl_c.h5"
    helper._CALLS[0] = 0
    monkeypatch.setenv("ROTORSIM_DIE_AT", "6")
    monkeypatch.setenv("ROTORSIM_DIE_HOW", "interrupt")
    with pytest.raises(KeyboardInterrupt):
        sweep(small_rotor(), stiffness_grid(), APPLY, helper.evaluate, store=store)
    monkeypatch.delenv("ROTORSIM_DIE_AT")
    assert (load_sweep(store).point_status == Status.OK).sum() == 5
    resumed = sweep(small_rotor(), stiffness_grid(), APPLY, helper.evaluate, store=store)
    assert resumed.stats["resumed"] == 5
    np.testing.assert_array_equal(resumed.outputs["critical_speeds"],
                                  reference.outputs["critical_speeds"])


@pytest.mark.parametrize("change", ["space", "rotor", "evaluate", "apply"])
def test_resume_refuses_a_store_of_another_sweep(tmp_path, change):
    store = tmp_path / "s.h5"
    base = {"rotor": small_rotor(), "space": Grid({"k": [1e6, 2e6]}),
            "apply": set_bearing_stiffness([0, 1], "k"), "evaluate": CRITICAL}
    sweep(**base, store=store)
    other = {"space": Grid({"k": [1e6, 2.5e6]}), "rotor": small_rotor(c=10.0),
             "evaluate": critical_speeds_eval(1.0, 3, sparse=False),
             "apply": set_bearing_stiffness([0], "k")}
    with pytest.raises(ModelError, match=f"different sweep \\({change}"):
        sweep(**{**base, change: other[change]}, store=store)
    fresh = sweep(**{**base, change: other[change]}, store=store, resume=False)
    assert fresh.stats["evaluated"] == 2 and fresh.stats["resumed"] == 0


def test_rs_load_reads_a_sweep_store(tmp_path):
    """``rs.load`` recognises a sweep store and returns its SweepResult."""
    import rotorsim as rs

    rotor = rs.Rotor([rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=rs.Material(
        name="s", E=211e9, G_s=81.2e9, rho=7810.0)) for _ in range(4)], [],
        [rs.BearingElement(n=0, kxx=1e6), rs.BearingElement(n=4, kxx=1e6)])
    space = rs.Grid({"bearing_k": [1e6, 2e6]})
    from rotorsim.analyses.sweep.sweep import critical_speeds_eval, set_bearing_stiffness

    result = rs.sweep(rotor, space, set_bearing_stiffness([0, 1]),
                      critical_speeds_eval(num_modes=1, sparse=False), store=tmp_path / "s.h5")
    loaded = rs.load(tmp_path / "s.h5")
    assert type(loaded).__name__ == "SweepResult"
    assert np.array_equal(loaded.outputs["critical_speeds"], result.outputs["critical_speeds"])


def test_a_parameter_missing_from_the_sweep_is_a_named_error():
    # min_log_dec reads the speed from each point: a sweep without it names the parameter
    # (it was a bare KeyError)
    space = Grid({"k": [1e6, 2e6]})
    apply = set_bearing_stiffness([0, 1], "k")
    with pytest.raises(ModelError, match="'speed' is not in the sweep"):
        sweep(small_rotor(), space, apply, min_log_dec("speed", 4, sparse=False),
              on_failure="raise")
    res = sweep(small_rotor(), space, apply, min_log_dec("speed", 4, sparse=False))
    assert res.point_status.tolist() == [Status.FAILED, Status.FAILED]
    assert all("'speed' is not in the sweep" in m for m in res.messages)
