"""The Craig-Bampton reduction ahead of exponential collocation on the automatic path
(:mod:`rotorsim.analyses.transient.exponential_reduction`): accuracy against an independent
LSODA reference and against the full path, the a-priori estimate against its modal sum,
the choice, its fallback to the full model, and bad input."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sl
from test_transient_auto import (  # noqa: F401 (the module-scoped LSODA reference fixture)
    PROBE,
    SPEED,
    T_END,
    UNBALANCE,
    reference,
    small_rolling_rotor,
)

import rotorsim as rs
from rotorsim.analyses.transient.auto import dof_weights
from rotorsim.analyses.transient.auto_exponential import exponential_stepper
from rotorsim.analyses.transient.auto_reduction import _interior
from rotorsim.analyses.transient.equation import rotor_problem
from rotorsim.analyses.transient.exponential_reduction import (
    SHARE,
    exponential_reduction,
    interior_modes,
)
from rotorsim.analyses.transient.speed_profile import ConstantSpeed
from rotorsim.analyses.transient.transient import transient
from rotorsim.assembly.reduction import fixed_interface_modes
from rotorsim.assembly.system import assemble
from rotorsim.errors import ModelError
from rotorsim.time_integration.exponential import Exponential
from rotorsim.time_integration.exponential_modes import HarmonicLoad, cexp
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.problem import SecondOrderProblem

KW = dict(speed=SPEED, unbalance=UNBALANCE, nodes=[PROBE])


@pytest.mark.validation
@pytest.mark.parametrize("rtol", [1e-1, 1e-2])
def test_reduced_run_meets_the_accuracy_asked_and_agrees_with_the_full_path(reference, rtol):  # noqa: F811
    times, ref = reference
    rotor, bearings = small_rolling_rotor()
    out = rs.Output(times=times)
    res = transient(rotor, T_END, nonlinear=bearings, rtol=rtol, output=out, **KW)
    full = transient(rotor, T_END, nonlinear=bearings, rtol=rtol, output=out,
                     reduction=False, **KW)
    decision = res.options["auto_reduction"]
    assert decision["reduced"] and decision["for"] == "exponential", decision
    assert res.method == full.method == "exponential"
    size = res.options["reduction"]["size"]
    assert size <= 0.5 * assemble(rotor, bearings).n_free
    motion = np.ptp(ref)
    # rtol bounds the error relative to the probe's motion (an LSODA reference at 1e-10)
    err = np.max(np.abs(res.displacement(PROBE, "uy") - ref)) / motion
    assert err <= rtol
    # the reduced and the full path agree to the accuracy asked of both
    gap = np.max(np.abs(res.displacement(PROBE, "uy") - full.displacement(PROBE, "uy")))
    assert gap <= rtol * motion
    # a step size set by the bearings, which see the same physical motion: about the
    # full model's steps (9 / 16 against 13 / 15 measured)
    assert res.stats["steps"] <= 1.25 * full.stats["steps"]


def test_a_reduced_run_measures_motion_and_error_on_the_physical_dofs():
    # measured on the reduced coordinates, the motion scale of the issue14 benchmark rotor
    # was a third of the physical one and its runs took 20-40 % more steps; the stepper of
    # a reduced run carries the basis and measures both on T q
    rotor, bearings = small_rolling_rotor()
    system = assemble(rotor, bearings)
    profile = ConstantSpeed(SPEED).bind(0.0, T_END)
    problem, loads = rotor_problem(system, profile, 0.0, rs.Excitation(unbalance=UNBALANCE))
    weights = dof_weights(system, problem.n)
    assert weights is not None
    q_full = np.linspace(0.0, 1e-6, system.n_free)
    # an a-priori motion of 0.1 mm: the estimate passes and the model is reduced
    small, basis, decision = exponential_reduction(system, problem, loads, SPEED, 1e-2,
                                                   1e-4, weights, tangent=None, phase=0.0,
                                                   duration=T_END)
    assert basis is not None and decision["reduced"]
    stepper = exponential_stepper(small, loads, profile, (0.0, T_END), 1e-2,
                                  dof_weights(system, small.n, basis), 1e-4, basis.T,
                                  weights)
    assert stepper is not None
    x0 = basis.project(q_full)
    state = stepper.init(small, 0.0, x0, np.zeros(small.n), dt=1e-5)
    cache = state.cache
    assert state.peak.shape == (system.n_free,)
    np.testing.assert_array_equal(cache.scales.weights, np.asarray(weights))
    x1 = x0 + np.cos(np.arange(small.n)) * 1e-7
    # |T (x1 - x0)|: the physical motion, whatever the cancellation between columns
    expected = np.abs(basis.T @ (x1 - x0))
    assert np.allclose(cache.moved(x1, x0), expected, rtol=1e-12, atol=0.0)
    # the modal error maps to the physical displacements through T
    n = small.n
    assert np.allclose(cache.error_map, basis.T @ cache.modes.V[:n], rtol=1e-12,
                       atol=1e-12 * np.max(np.abs(cache.error_map)))


def test_the_estimate_is_the_static_share_of_the_dropped_modes():
    # r = S - Phi Phi^T M S equals the modal sum sum_{j > c} phi_j phi_j^T f / w_j^2 over
    # the dropped modes, here from one dense eigensolution of the whole interior; the
    # grouped eigensolution gives the frequencies of the one-block one
    rotor, bearings = small_rolling_rotor()
    system = assemble(rotor, bearings)
    profile = ConstantSpeed(SPEED).bind(0.0, T_END)
    _, loads = rotor_problem(system, profile, 0.0, rs.Excitation(unbalance=UNBALANCE))
    assert system.nonlinear is not None
    inner = np.setdiff1d(np.arange(system.n_free), system.nonlinear.dofs)
    K_ii, M_ii, S, _ = _interior(system, loads, inner, (SPEED, SPEED))
    w2, phi = sl.eigh(K_ii.toarray(), M_ii.toarray())
    f = K_ii @ S  # the interior unbalance loads
    count = 8
    freqs, kept = interior_modes(K_ii, M_ii, count)
    r = S - kept[:, :count] @ (kept[:, :count].T @ (M_ii @ S))
    dropped = phi[:, count:]
    modal = dropped @ ((dropped.T @ f) / w2[count:, None])
    # both are differences of O(|S|) terms: agreement to 1e-9 of |S| (round-off of the
    # eigensolutions, about 1e-12 here)
    assert np.max(np.abs(r - modal)) <= 1e-9 * np.max(np.abs(S))
    one, _ = fixed_interface_modes(K_ii, M_ii, count)
    assert np.allclose(freqs[:count], one[:count], rtol=1e-9, atol=0.0)


def test_tight_accuracy_keeps_the_full_model_and_says_why():
    rotor, bearings = small_rolling_rotor()
    res = transient(rotor, 5e-4, nonlinear=bearings, rtol=1e-5, **KW)
    decision = res.options["auto_reduction"]
    assert decision["reduced"] is False and res.options["reduction"] is None
    chosen = decision["exponential"]
    assert chosen["reason"].startswith("no mode count")
    # every count tried was refused by its estimate (the a-priori truncation error)
    assert all(t["estimate"] > SHARE * 1e-5 for t in chosen["tried"])
    assert res.method == "exponential"


def test_a_run_up_or_a_model_without_unbalance_is_not_reduced():
    rotor, bearings = small_rolling_rotor()
    ramp = rs.LinearSpeed(700.0, 800.0, t_start=0.0, t_stop=5e-4)
    up = transient(rotor, 5e-4, nonlinear=bearings, speed=ramp, unbalance=UNBALANCE,
                   rtol=1e-2, nodes=[PROBE])
    assert up.method == "radau5" and up.options["reduction"] is None
    still = transient(rotor, 5e-4, nonlinear=bearings, speed=SPEED, rtol=1e-2, nodes=[PROBE])
    assert still.options["reduction"] is None
    assert "no unbalance" in still.options["auto_reduction"]["exponential"]["reason"]


def test_a_given_reduction_is_integrated_by_exponential_collocation_and_continues():
    rotor, bearings = small_rolling_rotor()
    first = transient(rotor, 5e-4, nonlinear=bearings, rtol=1e-2, reduction=8, **KW)
    assert first.method == "exponential" and first.options["reduction"]["size"] < 54
    more = transient(rotor, 1e-3, nonlinear=bearings, rtol=1e-2, reduction=8,
                     initial=first, **KW)
    assert more.method == "exponential" and more.t[-1] == pytest.approx(1e-3)


def test_a_wrong_basis_is_refused():
    M, K = np.eye(2), np.diag([1.0, 4.0])
    load = HarmonicLoad(np.zeros(2), np.array([1.0, 0.0], dtype=complex), 3.0)

    def batch(q, v, t):
        zero = np.zeros((q.shape[0], 1, 1))
        return np.array([0]), np.zeros((q.shape[0], 1)), zero, zero

    def restoring(q, v, t):
        return np.zeros(2), None, None

    restoring.batch = batch  # type: ignore[attr-defined]
    p = SecondOrderProblem(mass=M, stiffness=K, load=load, restoring=restoring)
    for kw, match in (({"basis": np.ones((5, 3))}, "basis must"),
                      ({"basis": np.ones((5, 2)), "basis_weights": (1.0, 1.0)},
                       "weights must")):
        with pytest.raises(ModelError, match=match):
            integrate(p, Exponential(load, **kw), (0.0, 0.1), [0.0, 0.0], [0.0, 0.0],
                      dt=1e-2)


def test_complex_exponential_from_real_functions():
    rng = np.random.default_rng(3)
    z = -np.abs(rng.standard_normal(200)) * 30 + 1j * rng.standard_normal(200) * 1e3
    # e^x (cos y + i sin y): a few ulps of |e^z| from numpy's complex exp
    assert np.allclose(cexp(z), np.exp(z), rtol=1e-14, atol=0.0)
