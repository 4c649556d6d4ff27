"""Every file in models/ loads, assembles and runs each of its named analyses (fast grids),
and the results of the static, modal, Campbell, critical-speed and unbalance analyses are
checked against physics computed here; the textbook files build exactly the rotors of
examples/textbook_rotors.py."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

from rotorsim.assembly.system import assemble
from rotorsim.errors import Status
from rotorsim.io.analysis_runners import FAST_POINTS
from rotorsim.io.model_file import load_model, run_analysis
from rotorsim.io.spec_registry import SPEC_TYPES
from rotorsim.results.api import ApiLevel1Result, ApiUnbalanceResult
from rotorsim.results.campbell import CampbellResult
from rotorsim.results.critical_speeds import CriticalSpeedMapResult, CriticalSpeeds
from rotorsim.results.frequency_response import FrequencyResponseResult
from rotorsim.results.modal import ModalResult
from rotorsim.results.periodic import PeriodicResult
from rotorsim.results.quasi_periodic import QuasiPeriodicResult
from rotorsim.results.static import StaticResult
from rotorsim.results.sweep import SweepResult
from rotorsim.results.transient import TransientResult

ROOT = Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import textbook_rotors as textbook  # noqa: E402

RPM = math.pi / 30.0  # rad/s per rpm
RESULT_TYPES = {
    "modal": ModalResult, "campbell": CampbellResult, "critical_speeds": CriticalSpeeds,
    "critical_speed_map": CriticalSpeedMapResult, "unbalance": FrequencyResponseResult,
    "frequency_response": FrequencyResponseResult, "static": StaticResult,
    "transient": TransientResult, "periodic": (PeriodicResult, QuasiPeriodicResult),
    "periodic_parameter": PeriodicResult, "sweep": SweepResult,
    "api_stability": ApiLevel1Result, "api_unbalance": ApiUnbalanceResult,
}
FILES = sorted(p.stem for p in MODELS.glob("*.toml"))
CASES = [(f, a) for f in FILES for a in load_model(MODELS / f"{f}.toml").analyses]


def test_the_expected_model_files_exist():
    assert set(FILES) >= {"default", "compressor", "large_rotor", "tapered", "friswell_5_9_1",
                          "friswell_5_9_2", "friswell_5_9_5", "friswell_5_9_9"}
    assert set(RESULT_TYPES) == set(SPEC_TYPES)


@pytest.mark.parametrize(("name", "analysis"), CASES, ids=[f"{f}-{a}" for f, a in CASES])
def test_every_named_analysis_runs(name, analysis):
    model = load_model(MODELS / f"{name}.toml")
    spec = model.analyses[analysis]
    result = run_analysis(model, analysis, fast=True)
    assert isinstance(result, RESULT_TYPES[spec.type])
    if (name, analysis) == ("default", "branch"):
        # unbalance with the balls' varying compliance (Z kappa = 4.09): the branch of tori
        # with nothing frozen (issue 17)
        assert isinstance(result, QuasiPeriodicResult) and result.approximation == ""
        assert result.vc_order == pytest.approx(4.09, abs=0.01)
    # a branch's max_points: the file's, else the analysis default (1000 or 200, above 10)
    if isinstance(result, PeriodicResult) and len(result) == min(
            spec.continuation.max_points or 10, 10):
        # fast=True caps a branch at 10 points: short of its end, it says so (issue 12)
        assert result.status in (Status.OK, Status.NOT_CONVERGED)
        assert result.status == Status.OK or "(max_points reached)" in result.reason
    else:
        assert np.all(np.asarray(result.status) == Status.OK)
    if isinstance(result, CampbellResult):
        assert 2 <= result.speeds.size <= FAST_POINTS
    if isinstance(result, FrequencyResponseResult):
        assert 2 <= result.frequencies.size <= FAST_POINTS
        assert np.all(np.isfinite(result.response))
    if isinstance(result, ModalResult):
        assert result.wn.size == spec.num_modes and np.all(np.isfinite(result.wn))
    if isinstance(result, CriticalSpeeds):
        assert len(result) > 0 and np.all(np.isfinite(result.speed))


TEXTBOOK = {
    "friswell_5_9_1": textbook.friswell_5_9_1,
    "friswell_5_9_2": textbook.friswell_5_9_2,
    "friswell_5_9_5": textbook.friswell_5_9_5,
    "friswell_5_9_9": textbook.friswell_5_9_9,
    "tapered": textbook.tapered_rotor,
    "friswell_5_9_5_fine": lambda: textbook.friswell_5_9_5(n_elements=24),
}


@pytest.mark.parametrize("name", sorted(TEXTBOOK))
def test_textbook_files_build_the_builder_rotors_exactly(name):
    # bit-identical: the files give the same numbers (unit strings convert to the nearest
    # double) and segments split into the same elements as the builders
    loaded, built = assemble(load_model(MODELS / f"{name}.toml").rotor), \
        assemble(TEXTBOOK[name]())
    assert loaded.dof_map.n_free == built.dof_map.n_free
    for speed in (0.0, 300.0):
        a, b = loaded.matrices(speed), built.matrices(speed)
        for key in "MCGK":
            assert (getattr(a, key) - getattr(b, key)).count_nonzero() == 0, (key, speed)


def test_default_model_is_the_showcase():
    """The Friswell two-disk rotor (24 elements) on two ball bearings of the seed 000 model,
    with every analysis of the showcase."""
    model = load_model(MODELS / "default.toml")
    assert len(model.rotor.shaft_elements) == 24
    built = textbook.friswell_5_9_5(n_elements=24)
    assert [d.m for d in model.rotor.disk_elements] == [d.m for d in built.disk_elements]
    assert not model.rotor.bearing_elements  # the supports are the rolling bearings
    assert [rb.tag for rb in model.rolling_bearings] == ["DE", "NDE"]
    assert all(type(rb.bearing).__name__ == "BallBearing" for rb in model.rolling_bearings)
    a = model.analyses
    assert {"campbell", "critical_speeds", "unbalance", "static",
            "critical_speed_map", "modes"} <= set(a)
    speeds = a["campbell"].speeds.array()
    assert speeds[0] == 0.0 and speeds[-1] == pytest.approx(4500 * RPM, rel=1e-15)
    # 0.2 g m at the 350 mm disk (z = 1.0 m, node 16 of 24)
    assert model.loads.unbalance == ((16, 2e-4, 0.0),)
    assert model.rotor.disk_elements[1].tag == "disk_350" \
        and model.rotor.disk_elements[1].n == 16


def test_compressor_has_speed_dependent_cross_coupled_bearings():
    model = load_model(MODELS / "compressor.toml")
    rotor = model.rotor
    assert len(rotor.disk_elements) == 2 and rotor.speed_dependent
    assert abs(rotor.length - 1.2) < 1e-12
    for b in rotor.bearing_elements:
        for speed in (150.0, 1000.0):
            kxy, kyx = b.coefficient("kxy", speed), b.coefficient("kyx", speed)
            assert kxy > 0 > kyx and b.coefficient("cxx", speed) > 0
        assert b.coefficient("kxx", 1000.0) < b.coefficient("kxx", 150.0)
    assert {s.type for s in model.analyses.values()} >= {"campbell", "critical_speed_map",
                                                         "unbalance"}
    unbalance = model.loads.unbalance
    assert [u[0] for u in unbalance] == [d.n for d in rotor.disk_elements]


def test_large_rotor_is_large():
    rotor = load_model(MODELS / "large_rotor.toml").rotor
    assert len(rotor.shaft_elements) >= 100
    assert len(rotor.disk_elements) == 3 and len(rotor.bearing_elements) == 2


# ---------------------------------------------------------------- physics of the shipped models
# Each result of the loop above is checked against a computation that does not go through
# the analysis that produced it: scipy's dense eigen solver on the first-order form of the
# assembled matrices, the dynamic equation of the response, the weight of the rotor.
def _cases(kind: str) -> list[tuple[str, str]]:
    return [(f, a) for f, a in CASES
            if load_model(MODELS / f"{f}.toml").analyses[a].type == kind]


def _ids(cases: list[tuple[str, str]]) -> list[str]:
    return [f"{f}-{a}" for f, a in cases]


# what run_analysis solves: the rotor, with its rolling bearings linearised at the static
# load (at the spec's speed for modal and static, else at rest)
def _linear_rotor(model, speed: float = 0.0):
    return model.linearized(speed).rotor if model.rolling_bearings else model.rotor


def _state_eigenvalues(rotor, speed: float, damped: bool = True) -> np.ndarray:
    """All eigenvalues of ``[[0, I], [-M^-1 K, -M^-1 (C + W G)]]`` by scipy (dense)."""
    mats = assemble(rotor).matrices(speed)
    M, C, G, K = (getattr(mats, key).toarray() for key in "MCGK")
    n = M.shape[0]
    damping = (C if damped else np.zeros_like(C)) + speed * G
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, damping)]])
    return scipy.linalg.eigvals(A)


# Two dense eigen solvers on two forms of the same problem (rotorsim's and the state matrix
# above): measured <= 1e-8 relative (the 42-DOF tapered-roller model, whose bearings are
# 1e4 times stiffer than the shaft), 1e-11 elsewhere. 1e-6 is far below any modelling change
# (a shifted disk or a bearing of another stiffness moves the frequencies by > 1e-3).
EIGEN_MATCH = 1e-6
# rigid-body modes come out of the state matrix as |lam| ~ 1e-3 rad/s (round-off of zero);
# every elastic mode of the shipped models is above 80 rad/s
RIGID = 1.0


def _nearest(lam: np.ndarray, value: complex) -> float:
    return float(np.min(np.abs(lam - value)) / abs(value))


@pytest.mark.parametrize(("name", "analysis"), _cases("static"), ids=_ids(_cases("static")))
def test_static_reactions_carry_the_weight_and_the_point_loads(name, analysis):
    """The supports (bearings and held DOFs) carry the weight m g of the rotor (its mass
    summed by the model, independent of the static solve) plus the point loads."""
    model = load_model(MODELS / f"{name}.toml")
    s = run_analysis(model, analysis, fast=True)
    loads = model.loads
    g = 0.0 if loads.gravity is None else loads.gravity  # None: the model has no gravity
    applied = g * model.rotor.m * np.asarray(loads.gravity_direction, float)
    for _, dof, value in loads.point_loads:
        if dof in ("ux", "uy", "uz"):
            applied[("ux", "uy", "uz").index(dof)] += value
    np.testing.assert_allclose(s.applied_force, applied, rtol=1e-12,
                               atol=1e-12 * np.abs(applied).max())
    support = np.zeros(3)
    if s.bearing_forces is not None and len(s.bearing_forces):
        support += s.bearing_forces.sum(axis=0)
    if s.constraint_reactions is not None:
        support += s.constraint_reactions.reshape(-1, 6)[:, :3].sum(axis=0)
    # nonlinear bearings: equilibrium converged to 1e-6 of the bearing loads (Model.linearized);
    # linear supports: round-off of one solve. Measured <= 1e-15 for all shipped models.
    tol = 1e-6 if model.rolling_bearings else 1e-9
    np.testing.assert_allclose(support + applied, 0.0, atol=tol * np.abs(applied).max())


@pytest.mark.parametrize(("name", "analysis"), _cases("modal"), ids=_ids(_cases("modal")))
def test_modal_frequencies_are_the_lowest_eigenvalues_of_the_state_matrix(name, analysis):
    model = load_model(MODELS / f"{name}.toml")
    spec = model.analyses[analysis]
    result = run_analysis(model, analysis, fast=True)
    speed = float(spec.speed or 0.0)
    lam = _state_eigenvalues(_linear_rotor(model, speed), speed)
    found = np.asarray(result.eigenvalues)
    assert found.size == spec.num_modes
    for value in found:
        assert _nearest(lam, value) < EIGEN_MATCH, value
    # and none is skipped: every elastic eigenvalue (upper half plane) below the largest
    # one reported is reported (pairs of equal frequencies count twice)
    elastic = lam[(np.abs(lam) > RIGID) & (lam.imag > 0)]
    below = elastic[np.abs(elastic) < np.abs(found).max() * (1 - EIGEN_MATCH)]
    assert below.size <= found.size
    for value in below:
        assert _nearest(found, value) < EIGEN_MATCH, value


@pytest.mark.parametrize(("name", "analysis"), _cases("campbell"), ids=_ids(_cases("campbell")))
def test_campbell_ends_are_eigenvalues_of_the_state_matrix(name, analysis):
    """At the first and the last speed (0 rpm: the modal problem), every tracked mode
    ``-wd log_dec / (2 pi) + i wd`` is an eigenvalue of the state matrix at that speed. An
    overdamped mode is reported as ``wd = 0``, ``log_dec = inf`` (its eigenvalues are real):
    the state matrix must then have at least two real eigenvalues per such mode."""
    model = load_model(MODELS / f"{name}.toml")
    c = run_analysis(model, analysis, fast=True)
    rotor = _linear_rotor(model)
    for row in (0, -1):
        lam = _state_eigenvalues(rotor, float(c.speeds[row]))
        overdamped = (c.wd[row] == 0) & (c.log_dec[row] == np.inf)
        good = np.isfinite(c.wd[row]) & ~overdamped
        assert good.sum() + overdamped.sum() >= c.wd.shape[1] // 2
        real = np.sum((np.abs(lam.imag) < EIGEN_MATCH * np.abs(lam)) & (np.abs(lam) > RIGID))
        assert real >= 2 * overdamped.sum(), (row, real)
        for wd, log_dec in zip(c.wd[row, good], c.log_dec[row, good], strict=True):
            value = -wd * log_dec / (2 * np.pi) + 1j * wd
            assert _nearest(lam, value) < EIGEN_MATCH, (row, value)


@pytest.mark.parametrize(("name", "analysis"), _cases("critical_speeds"),
                         ids=_ids(_cases("critical_speeds")))
def test_critical_speeds_are_synchronous_undamped_frequencies(name, analysis):
    """At each critical speed W the undamped rotor spinning at W has a natural frequency
    equal to the excitation k W (the definition, checked on the state matrix)."""
    model = load_model(MODELS / f"{name}.toml")
    cs = run_analysis(model, analysis, fast=True)
    rotor = _linear_rotor(model)
    assert len(cs) > 0
    for speed, frequency in zip(cs.speed, cs.frequency, strict=True):
        lam = _state_eigenvalues(rotor, float(speed), damped=False)
        assert np.min(np.abs(np.abs(lam.imag) - frequency)) < EIGEN_MATCH * frequency, speed


@pytest.mark.parametrize(("name", "analysis"), _cases("unbalance"),
                         ids=_ids(_cases("unbalance")))
def test_unbalance_response_satisfies_the_equation_of_motion(name, analysis):
    """``(K - W^2 M + i W (C + W G)) x = F(W)`` with the unbalance forces built here from
    the model's unbalance list (``m e W^2 e^(i a)`` on ux, ``-i`` times it on uy)."""
    model = load_model(MODELS / f"{name}.toml")
    spec = model.analyses[analysis]
    r = run_analysis(model, analysis, fast=True)
    system = assemble(_linear_rotor(model))
    to_free = system.dof_map.full_to_free
    unbalance = model.loads.unbalance if spec.unbalance is None else spec.unbalance
    assert len(unbalance) > 0
    # a machine's spools: column k holds the unbalance of the spool at ratio r_k, which
    # turns at w = r_k W (written at |w|: conjugated for r_k < 0); one column otherwise
    ratio_of = system.node_speed_ratio
    ratios = [1.0] if r.input_ratios is None else list(r.input_ratios)
    for column, ratio in enumerate(ratios):
        on_spool = [u for u in unbalance if r.input_ratios is None
                    or ratio_of[u[0]] == ratio]
        for i, W in enumerate(r.speeds):
            w = ratio * W
            mats = system.matrices(W)
            dynamic = (mats.K - w**2 * mats.M + 1j * w * (mats.C + W * mats.G)).toarray()
            force = np.zeros(dynamic.shape[0], complex)
            for node, me, phase in on_spool:
                assert to_free[6 * node] >= 0 and to_free[6 * node + 1] >= 0  # free ux, uy
                force[to_free[6 * node]] += me * w**2 * np.exp(1j * phase)
                force[to_free[6 * node + 1]] += -1j * me * w**2 * np.exp(1j * phase)
            kept = to_free >= 0
            x = np.zeros(dynamic.shape[0], complex)
            x[to_free[kept]] = r.response[i, kept, column]
            x = x if ratio > 0 else x.conj()
            assert np.abs(x).max() > 0.0
            # backward error of a stable LU solve, ~ n eps: measured <= 2e-16
            residual = np.abs(dynamic @ x - force).max()
            assert residual <= 1e-12 * np.abs(dynamic).max() * np.abs(x).max(), W
