"""The automatic transient path (``rs.transient(..., rtol=)``): a rotor on two ball bearings
with clearance against an independent solve_ivp reference, the choice of method, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import rotorsim as rs
from rotorsim.analyses.transient.equation import rotor_problem as _problem
from rotorsim.analyses.transient.speed_profile import ConstantSpeed
from rotorsim.analyses.transient.transient import transient
from rotorsim.assembly.system import assemble
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.errors import ModelError

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
SPEED, T_END, PROBE = 800.0, 0.003, 4
UNBALANCE = [(PROBE, 1e-5, 0.3)]


def small_rolling_rotor():
    shaft = [rs.ShaftElement(L=0.05, idl=0.0, odl=0.03, material=STEEL) for _ in range(8)]
    disk = rs.DiskElement.from_geometry(n=PROBE, material=STEEL, width=0.02, i_d=0.03,
                                        o_d=0.12)
    ball = BallBearing(n_balls=8, pitch_diameter=0.035, ball_diameter=0.007, Kn=8e9,
                       diametral_clearance=10e-6, f_i=0.52, f_o=0.52)
    bearings = [RollingBearing(ball, n=n, tag=t, contact_damping="proportional",
                               damping_factor=2e-5) for n, t in ((0, "A"), (8, "B"))]
    return rs.Rotor(shaft, [disk]), bearings


@pytest.fixture(scope="module")
def reference():
    """solve_ivp (LSODA, rtol 1e-10, exact Jacobian) on ``y = [q, v]`` with rotorsim's force
    model, from the static equilibrium rotorsim starts from; the probe's ``uy``."""
    rotor, bearings = small_rolling_rotor()
    start = transient(rotor, T_END, 1e-4, nonlinear=bearings, speed=SPEED,
                      unbalance=UNBALANCE, output=rs.Output(times=[0.0]))
    system = assemble(rotor, bearings)
    profile = ConstantSpeed(SPEED).bind(0.0, T_END)
    problem, loads = _problem(system, profile, 0.0, rs.Excitation(unbalance=UNBALANCE))
    n = system.n_free
    M, K, C, G = (np.asarray(problem.mass), np.asarray(problem.stiffness),
                  np.asarray(problem.damping), np.asarray(problem.gyroscopic))
    Minv = np.linalg.inv(M)
    D = C + SPEED * G

    def rhs(t, y):
        r, _, _ = problem.restoring(y[:n], y[n:], t)
        return np.concatenate([y[n:], Minv @ (loads(t) - K @ y[:n] - D @ y[n:] - r)])

    def jac(t, y):
        _, kt, ct = problem.restoring(y[:n], y[n:], t)
        return np.block([[np.zeros((n, n)), np.eye(n)],
                         [-Minv @ (K + kt.toarray()), -Minv @ (D + ct.toarray())]])

    q0 = start.q[0][np.searchsorted(start.dofs, system.dof_map.free)]
    times = np.linspace(0.0, T_END, 31)
    atol = np.concatenate([np.full(n, 1e-6), np.full(n, 1e-3)]) * 1e-10
    sol = solve_ivp(rhs, (0.0, T_END), np.concatenate([q0, np.zeros(n)]), method="LSODA",
                    jac=jac, rtol=1e-10, atol=atol, t_eval=times)
    assert sol.success
    probe = system.dofs_of(PROBE, ("uy",))[0]
    return times, sol.y[probe]


@pytest.mark.validation
@pytest.mark.parametrize("rtol", [1e-3, 1e-5])
def test_auto_meets_the_accuracy_asked_on_a_rolling_bearing_rotor(reference, rtol):
    # the requested accuracy is a bound on the error relative to the probe's motion
    times, ref = reference
    rotor, bearings = small_rolling_rotor()
    res = transient(rotor, T_END, nonlinear=bearings, speed=SPEED, unbalance=UNBALANCE,
                    rtol=rtol, nodes=[PROBE], output=rs.Output(times=times))
    # constant speed, gravity and unbalance, a small model: exponential collocation
    assert res.method == "exponential" and res.options["rtol"] == rtol
    err = np.max(np.abs(res.displacement(PROBE, "uy") - ref)) / np.ptp(ref)
    assert err <= rtol


def test_without_dt_the_path_is_automatic():
    rotor, bearings = small_rolling_rotor()
    res = transient(rotor, 5e-4, nonlinear=bearings, speed=SPEED, unbalance=UNBALANCE,
                    nodes=[PROBE])
    assert res.method == "exponential" and res.stats["steps"] > 0
    fixed = transient(rotor, 5e-4, 1e-4, nonlinear=bearings, speed=SPEED,
                      unbalance=UNBALANCE, nodes=[PROBE])
    assert fixed.method == "average_acceleration"  # a step size keeps the old default


@pytest.mark.parametrize("kwargs, culprit", [
    ({"rtol": 0.5}, "transient.rtol"), ({"rtol": 1e-4, "method": "newmark"}, "transient.rtol"),
    ({"method": "hht"}, "transient.dt")])
def test_bad_accuracy_requests_are_refused(kwargs, culprit):
    rotor, bearings = small_rolling_rotor()
    with pytest.raises(ModelError, match=culprit.replace(".", r"\.")):
        transient(rotor, 5e-4, nonlinear=bearings, speed=SPEED, **kwargs)


@pytest.mark.validation
def test_auto_run_up_of_a_gyroscopic_rotor_against_solve_ivp():
    # a linear rotor with a heavy disk spun up 0 -> 2000 rad/s: the gyroscopic term W(t) G
    # changes along the run (factors reused while |W - W_f| h < 0.02, the Newton iteration
    # absorbing the rest); reference: solve_ivp LSODA at rtol 1e-10 on the same matrices
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.03, material=STEEL) for _ in range(4)]
    disk = rs.DiskElement.from_geometry(n=2, material=STEEL, width=0.03, i_d=0.03, o_d=0.25)
    rotor = rs.Rotor(shaft, [disk], [rs.BearingElement(n=0, kxx=5e6, cxx=200.0),
                                     rs.BearingElement(n=4, kxx=5e6, cxx=200.0)])
    t_end, unbalance = 0.05, [(2, 1e-4, 0.0)]
    speed = rs.LinearSpeed(0.0, 2000.0, t_start=0.0, t_stop=t_end)
    times = np.linspace(0.0, t_end, 51)
    res = transient(rotor, t_end, rtol=1e-5, speed=speed, unbalance=unbalance, initial="zero",
                    excitation=rs.Excitation(gravity=None), output=rs.Output(times=times))
    system = assemble(rotor)
    profile = speed.bind(0.0, t_end)
    problem, loads = _problem(system, profile, 0.0, rs.Excitation(gravity=None,
                                                                   unbalance=unbalance))
    M, K, C, G = (np.asarray(problem.mass), np.asarray(problem.stiffness),
                  np.asarray(problem.damping), np.asarray(problem.gyroscopic))
    Minv, n = np.linalg.inv(M), system.n_free

    def rhs(t, y):
        D = C + profile.speed(t) * G
        return np.concatenate([y[n:], Minv @ (loads(t) - K @ y[:n] - D @ y[n:])])

    sol = solve_ivp(rhs, (0.0, t_end), np.zeros(2 * n), method="LSODA", rtol=1e-10,
                    atol=1e-18, t_eval=times)
    probe = system.dofs_of(2, ("uy",))[0]
    ref = sol.y[probe]
    err = np.max(np.abs(res.displacement(2, "uy") - ref)) / np.ptp(ref)
    assert err <= 1e-5


@pytest.fixture()
def reduce_any_run(monkeypatch):
    """The automatic reduction's size and length gates opened, so that the small rotor's
    short run is reduced when the accuracy checks pass."""
    import rotorsim.analyses.transient.auto_reduction as auto_red

    for name, value in (("MIN_FREE", 0), ("MIN_REVOLUTIONS", 0.0), ("MAX_FRACTION", 1.0)):
        monkeypatch.setattr(auto_red, name, value)


@pytest.mark.validation
@pytest.mark.parametrize("rtol", [1e-2, 1e-3])
def test_automatic_reduction_meets_the_accuracy_asked(reference, reduce_any_run, rtol):
    # the a-priori checks pick the modes; against the full-model LSODA reference the error
    # relative to the probe's motion stays below rtol
    times, ref = reference
    rotor, bearings = small_rolling_rotor()
    res = transient(rotor, T_END, nonlinear=bearings, speed=SPEED, unbalance=UNBALANCE,
                    rtol=rtol, nodes=[PROBE], output=rs.Output(times=times))
    decision = res.options["auto_reduction"]
    assert decision["reduced"], decision
    assert res.options["reduction"]["size"] < res.options["reduction"]["full_size"]
    assert decision["tried"][-1]["estimate"] <= 0.2 * rtol  # RINGING_SHARE
    err = np.max(np.abs(res.displacement(PROBE, "uy") - ref)) / np.ptp(ref)
    assert err <= rtol


def test_small_or_short_runs_stay_full_and_say_why():
    rotor, bearings = small_rolling_rotor()
    kw = dict(nonlinear=bearings, speed=SPEED, unbalance=UNBALANCE, rtol=1e-3, nodes=[PROBE])
    res = transient(rotor, 5e-4, **kw)
    assert res.options["auto_reduction"]["reduced"] is False
    assert "revolutions" in res.options["auto_reduction"]["reason"]
    assert res.options["reduction"] is None
    off = transient(rotor, 5e-4, reduction=False, **kw)
    np.testing.assert_array_equal(off.q, res.q)  # the same run, in the same process
    with pytest.raises(ModelError, match=r"transient\.reduction"):
        transient(rotor, 5e-4, reduction=True, **kw)


def test_an_automatically_reduced_run_continues_with_its_reduction(reduce_any_run):
    rotor, bearings = small_rolling_rotor()
    kw = dict(nonlinear=bearings, speed=SPEED, unbalance=UNBALANCE, rtol=1e-2, nodes=[PROBE])
    first = transient(rotor, 5e-4, **kw)
    assert first.options["auto_reduction"]["reduced"]
    with pytest.raises(ModelError, match=r"transient\.reduction"):
        transient(rotor, 1e-3, initial=first, **kw)
    modes = first.options["reduction"]["requested_modes"]
    more = transient(rotor, 1e-3, initial=first, reduction=modes, **kw)
    assert more.t[-1] == pytest.approx(1e-3)
