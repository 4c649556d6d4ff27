"""BLAS thread caps of the hot loops (issue 12, section 2).

Every test first raises the BLAS threads to 2 (``make test`` sets them to 1), so a hot
loop that forgot its cap reports 2 and fails.
"""

from __future__ import annotations

import subprocess
import sys
import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from threadpoolctl import threadpool_info, threadpool_limits

import rotorsim as rs
from rotorsim.analyses.linear.campbell import campbell
from rotorsim.analyses.sweep.sweep import Grid, sweep
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import make_residual
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.solvers import eigen
from rotorsim.solvers.threads import SMALL_WORK_SIZE, SWITCH, blas_threads_for, one_blas_thread
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.problem import SecondOrderProblem


def blas_threads() -> int:
    """Largest thread count of the loaded BLAS libraries."""
    counts = [lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"]
    assert counts, "no BLAS library found by threadpoolctl"
    return max(counts)


@pytest.fixture(autouse=True)
def two_threads(monkeypatch):
    monkeypatch.delenv(SWITCH, raising=False)
    with threadpool_limits(limits=2, user_api="blas"):
        assert blas_threads() == 2
        yield


def steel_rotor(n_elements: int) -> rs.Rotor:
    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.05, material=steel)
             for _ in range(n_elements)]
    return rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=1e7, cxx=100.0),
                                rs.BearingElement(n=n_elements, kxx=1e7, cxx=100.0)])


def test_time_steps_run_with_one_blas_thread_and_the_limit_comes_back():
    seen: list[int] = []
    problem = SecondOrderProblem(mass=np.eye(3), stiffness=np.diag([1.0, 2.0, 3.0]))
    integrate(problem, Newmark(), (0.0, 0.1), np.ones(3), np.zeros(3), dt=0.01,
              callback=lambda state: seen.append(blas_threads()))
    assert seen and set(seen) == {1}
    assert blas_threads() == 2


def test_campbell_calls_arpack_with_one_blas_thread(monkeypatch):
    seen: list[int] = []
    original = eigen.spl.eigs

    def recording_eigs(*args, **kwargs):
        seen.append(blas_threads())
        return original(*args, **kwargs)

    monkeypatch.setattr(eigen.spl, "eigs", recording_eigs)
    rotor = steel_rotor(10)   # 66 DOFs > DENSE_EIGEN_THRESHOLD: the ARPACK path
    campbell(rotor, [0.0, 100.0, 200.0], num_modes=2)
    assert len(seen) == 3 and set(seen) == {1}
    assert blas_threads() == 2


def test_harmonic_balance_newton_runs_with_one_blas_thread():
    seen: list[int] = []

    def cubic(q, v, tau, w, p):
        seen.append(blas_threads())
        return q**3, 3 * q[:, :, None] ** 2, None

    pb = HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1), nl_dofs=[0], force=cubic,
                   excitation=[[0.0], [1.0], [0.0]])
    solve_point(make_residual(pb, 1), 1.0)
    assert seen and set(seen) == {1}


def test_large_dense_work_keeps_the_threads():
    with blas_threads_for(SMALL_WORK_SIZE + 1):
        assert blas_threads() == 2
    with blas_threads_for(SMALL_WORK_SIZE):
        assert blas_threads() == 1


def test_the_switch_turns_the_caps_off(monkeypatch):
    monkeypatch.setenv(SWITCH, "off")
    with one_blas_thread():
        assert blas_threads() == 2


def test_the_cap_holds_until_the_last_of_several_threads_leaves():
    first_in, second_in, first_out = threading.Event(), threading.Event(), threading.Event()
    inside_after_first_left: list[int] = []

    def first():
        with one_blas_thread():
            first_in.set()
            second_in.wait(10)
        first_out.set()

    def second():
        first_in.wait(10)
        with one_blas_thread():
            second_in.set()
            first_out.wait(10)
            inside_after_first_left.append(blas_threads())

    workers = [threading.Thread(target=f) for f in (first, second)]
    for w in workers:
        w.start()
    for w in workers:
        w.join(20)
    assert inside_after_first_left == [1]
    assert blas_threads() == 2


def report_blas_threads(rotor, params):
    """Sweep evaluate function (module level: picklable for the process executor)."""
    return {"blas_threads": blas_threads()}


@pytest.mark.parametrize("executor", ["serial", "thread", "process"])
def test_sweep_workers_run_with_one_blas_thread(executor, monkeypatch):
    # spawned workers inherit the environment: without the cap they would start with 2
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "2")
    monkeypatch.setenv("OMP_NUM_THREADS", "2")
    space = Grid({"x": [0.0, 1.0, 2.0]})
    if executor == "thread":
        with ThreadPoolExecutor(max_workers=2) as pool:
            res = sweep(steel_rotor(2), space, None, report_blas_threads, executor=pool)
    else:
        res = sweep(steel_rotor(2), space, None, report_blas_threads, executor=executor,
                    max_workers=1)
    assert res.outputs["blas_threads"].tolist() == [1, 1, 1]
    assert blas_threads() == 2


def test_import_rotorsim_does_not_import_threadpoolctl():
    code = "import sys, rotorsim; print('threadpoolctl' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"


def test_the_limit_is_set_once_per_analysis_not_per_speed(monkeypatch):
    from rotorsim.solvers import threads

    lookups: list[int] = []
    original = threads._CAP.controller

    def counting_controller():
        lookups.append(1)
        return original()

    monkeypatch.setattr(threads._CAP, "controller", counting_controller)
    campbell(steel_rotor(10), [0.0, 100.0, 200.0, 300.0], num_modes=2)
    assert len(lookups) == 1   # campbell's entry; modal at each speed only counts


def test_the_transient_static_start_runs_with_one_blas_thread(monkeypatch):
    # the static start on the rolling bearings precedes the time steps: capped too (next to
    # a busy process it was the uncapped part of the default model's run-up)
    import rotorsim.analyses.transient.transient as transient_module

    seen: list[int] = []
    original = transient_module.initial_state

    def spy(*args, **kwargs):
        seen.append(blas_threads())
        return original(*args, **kwargs)

    monkeypatch.setattr(transient_module, "initial_state", spy)
    rotor = steel_rotor(4).with_fixed([(n, d) for n in range(5) for d in ("uz", "rz")])
    rs.transient(rotor, 0.002, 1e-3, speed=100.0)
    assert seen == [1]
    assert blas_threads() == 2


def test_the_hill_exponents_and_the_branch_of_tori_run_with_one_blas_thread(monkeypatch):
    """The Hill matrices of a torus (378-630 rows on the default model) are small dense
    eigenproblems: with two BLAS threads next to a busy process, the default model's tori
    up to 1000 rpm took 59.8 s of exponents instead of 3.4 s (issue 17)."""
    from pathlib import Path

    from rotorsim.harmonic_balance.quasi import QuasiProblem, TorusAFT, TorusHarmonics, hill

    seen: list[int] = []
    original = hill.sl.eig

    def recording_eig(*args, **kwargs):
        seen.append(blas_threads())
        return original(*args, **kwargs)

    monkeypatch.setattr(hill.sl, "eig", recording_eig)

    def force(q, v, t1, t2):
        k = 0.1 * (np.cos(t1) + np.cos(t2))
        return k[:, None] * q, k[:, None, None], None

    pb = QuasiProblem(np.eye(1), 0.2 * np.eye(1), np.eye(1), nl_dofs=np.array([0]),
                      force=force)
    aft = TorusAFT(TorusHarmonics.box(2, 2))
    hill.hill_exponents(pb, np.zeros((aft.harmonics.rows, 1)), aft, 3.1, 7.3)
    assert seen == [1]
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))
    from test_rigid_rotor_vc import textbook

    rotor, _ = textbook()          # the rigid rotor of validation case 36
    rs.quasi_periodic(rotor, start=800.0, stop=810.0, step=5.0, harmonics=(4, 2),
                      unbalance=[(0, 2e-6, 0.0)],
                      excitation=rs.Excitation(gravity=None, loads=[(0, "uy", -50.0)]),
                      max_points=3, beyond=None)
    assert len(seen) > 1 and set(seen) == {1}
    assert blas_threads() == 2
