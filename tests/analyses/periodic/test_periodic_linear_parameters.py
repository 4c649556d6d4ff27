"""Branches of rs.periodic_parameter over parameters of the linear part and static loads.

Rotor: the Jeffcott rotor of ``test_periodic.py`` (two ball bearings with 10 um clearance,
two linear dampers ``c`` at the bearing nodes, disk unbalance) at 1250 rad/s, inside the
hysteresis of its unbalance response.

References that this code did not produce:

* a fold of the damping branch at ``c_f`` means that the speed branch of the rotor with
  dampers ``c_f`` (an independent ``rs.periodic`` run, continuation in the speed with the
  rotor assembled once) has a fold at 1250 rad/s;
* points of the damping and load branches equal ``rs.periodic`` solved with that damping or
  load (up to the linear interpolation between branch points);
* the branch over a whole rotor (``vary -> Rotor``) whose only change is the bearing
  clearance equals the branch over the nonlinear elements (the other code path: one
  assembly, only the force callback varies).
"""

from __future__ import annotations

import numpy as np
import pytest
from test_periodic import UNBALANCE, ball, jeffcott

import rotorsim as rs
from rotorsim.analyses.periodic.branch import first_point, unknown_scales
from rotorsim.analyses.periodic.excitation import plan_excitation
from rotorsim.analyses.periodic.periodic import periodic
from rotorsim.analyses.periodic.problem import build_problem
from rotorsim.analyses.periodic.variation import RotorFamilyResidual, parametric_residual
from rotorsim.assembly.system import assemble
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.errors import InconsistentModelError, ModelError
from rotorsim.harmonic_balance.residual import make_residual
from rotorsim.solvers.stats import Stats

W, DISK = 1250.0, 1


def damped(c: float) -> rs.Rotor:
    return jeffcott(damping=c)


def at_fixed(rotor: rs.Rotor, **kw):
    """rs.periodic solved at W alone (two points, no stability): amplitude of the disk."""
    res = periodic(rotor, start=W, stop=W + 0.5, unbalance=UNBALANCE, harmonics=6,
                   continuation=rs.ContinuationOptions(max_points=2),
                   stability=rs.StabilityOptions(None, bifurcations=False), **kw)
    return res.amplitude(DISK, "uy", "peak_to_peak")[0]


@pytest.fixture(scope="module")
def damping_branch():
    """Damper coefficient from 40000 down to 2000 N s/m: an S-curve with three folds."""
    return rs.periodic_parameter(damped(40000.0), damped, speed=W, start=40000.0,
                                 stop=2000.0, unbalance=UNBALANCE, harmonics=6,
                                 name="damper [N s/m]",
                                 continuation=rs.ContinuationOptions(max_points=200))


@pytest.mark.verification
def test_folds_in_the_damping_are_folds_of_the_speed_branch_at_that_damping(damping_branch):
    res = damping_branch
    # the S-curve's three folds come first along the branch; with steps that grow with
    # the response (Continuation.relative_step) the 200 points reach further and may
    # pass more turns of the branch beyond them
    folds = sorted(res.events("fold"), key=lambda f: f.index)
    assert len(folds) >= 3 and all(f.located for f in folds)
    assert sorted(round(f.parameter, -1) for f in folds[:3]) == [2390.0, 4660.0, 5180.0]
    assert res.options["vary"] == "model"
    # the two folds of the main S-curve: the speed branch with dampers c_f turns at W
    for fold in sorted(folds, key=lambda f: f.index)[:2]:
        speed = periodic(damped(fold.parameter), start=1190.0, stop=1330.0,
                         unbalance=UNBALANCE, harmonics=6,
                         continuation=rs.ContinuationOptions(tol=1e-9, max_step=0.1),
                         stability=None)
        assert min(abs(f.parameter - W) for f in speed.events("fold")) < 1e-6 * W


@pytest.mark.verification
def test_damping_branch_points_equal_the_response_at_that_damping(damping_branch):
    res = damping_branch
    first_fold = min(f.index for f in res.events("fold"))
    leg = slice(0, first_fold + 1)          # single-valued above the first fold
    p, a = res.parameter[leg], res.amplitude(DISK, "uy", "peak_to_peak")[leg]
    for c in (20000.0, 6000.0):
        assert np.interp(c, p[::-1], a[::-1]) == pytest.approx(at_fixed(damped(c)),
                                                               rel=1e-3)
    # more damping, less response; stable until the S-curve turns
    assert np.all(np.diff(a) > 0) and res.stable[: first_fold].all()
    # each side of a fold differs in stability (a multiplier crosses +1 there)
    for fold in res.events("fold"):
        assert res.stable[fold.index - 1] != res.stable[fold.index + 2]
        assert abs(fold.multiplier - 1.0) < 0.05


@pytest.mark.verification
def test_jump_map_in_the_damping_crosses_the_folds_of_the_damping_branch(damping_branch):
    """fold_map=ParameterMap(vary -> Rotor): the upper fold of the 5000 N s/m speed branch
    continued in the damper coefficient passes 1250 rad/s where the damping branch at
    1250 rad/s folds (two independent continuations, in the speed and in the damping),
    and at 4000 N s/m it matches the fold of a speed branch computed at 4000."""
    from rotorsim.analyses.periodic.folds import ParameterMap

    mapped = periodic(damped(5000.0), start=1190.0, stop=1310.0, unbalance=UNBALANCE,
                      harmonics=6, continuation=rs.ContinuationOptions(tol=1e-9, max_step=0.1),
                      stability=None,
                      fold_map=ParameterMap(damped, 5000.0, 3000.0, "damper [N s/m]"))
    curves = mapped.options["fold_map"]["curves"]
    upper = max(curves, key=lambda c: c["parameter"][0])
    assert upper["status"] == "OK" and upper["mu"][-1] == pytest.approx(3000.0)
    mu, speed = np.array(upper["mu"]), np.array(upper["parameter"])
    c_fold = min(f.parameter for f in damping_branch.events("fold")
                 if 4000.0 < f.parameter < 5000.0)
    crossing = float(np.interp(W, speed[::-1], mu[::-1]))   # the curve is monotonic here
    assert np.all(np.diff(speed) < 0)
    assert crossing == pytest.approx(c_fold, rel=1e-4)       # interpolation: 1.7e-6 seen
    direct = periodic(damped(4000.0), start=1150.0, stop=1330.0, unbalance=UNBALANCE,
                      harmonics=6, continuation=rs.ContinuationOptions(tol=1e-9, max_step=0.1),
                      stability=None)
    at_4000 = float(np.interp(4000.0, mu[::-1], speed[::-1]))
    assert min(abs(at_4000 - f.parameter) for f in direct.events("fold")) < 1e-4 * W  # 1.7e-5


@pytest.mark.verification
def test_static_load_branch_equals_the_response_under_that_load():
    res = rs.periodic_parameter(jeffcott(), "loads", speed=W, start=0.0, stop=500.0,
                                excitation=rs.Excitation(loads=[(DISK, "uy", -1.0)]),
                                unbalance=UNBALANCE, harmonics=6, name="disk load [N]",
                                continuation=rs.ContinuationOptions(max_points=200))
    assert res.status == 0 and res.parameter[-1] == pytest.approx(500.0)
    a = res.amplitude(DISK, "uy", "peak_to_peak")
    for load in (150.0, 400.0):
        assert np.interp(load, res.parameter, a) == pytest.approx(
            at_fixed(jeffcott(), excitation=rs.Excitation(loads=[(DISK, "uy", -load)])),
            rel=1e-3)
    # harmonic 0 of the disk follows the load: it sags more under a larger load
    sag = res.coefficients[:, 0, res.column(DISK, "uy")]
    assert sag[-1] < sag[0] - 1e-6


def clearance_rotor(c: float) -> rs.Rotor:
    return jeffcott().linear_part().with_nonlinear(clearance_bearings(c))


def clearance_bearings(c: float) -> list[RollingBearing]:
    return [RollingBearing(ball("fixed", clearance=c), n=n, tag=f"B{n}") for n in (0, 2)]


def residuals(vary, start=10e-6):
    system = assemble(clearance_rotor(start))
    assert system.nonlinear is not None
    plan = plan_excitation(system.nonlinear.elements, unbalance=True, base=None,
                           varying_compliance=None, fundamental=None,
                           frequency_parameter=False)
    rp = build_problem(system, plan, speed0=W, fixed_speed=None, phi0=0.0,
                       unbalance=UNBALANCE, gravity=9.81, direction=(0, -1, 0), loads=[],
                       base=None, stats=Stats())
    standard = make_residual(rp.problem, 4)
    X0 = np.zeros((standard.aft.rows, rp.problem.n))
    X0[0] = rp.static[rp.active]
    x0 = first_point(standard, W, standard.restrict(X0),
                     unknown_scales(system, rp, standard), 1e-10, Stats())
    return parametric_residual(rp, system, vary, 4, None, 8e-6, start), x0


def test_a_varied_rotor_and_varied_elements_give_the_same_residual_and_derivative():
    family, x0 = residuals(clearance_rotor)
    elements, _ = residuals(clearance_bearings)
    assert isinstance(family, RotorFamilyResidual)
    assert not isinstance(elements, RotorFamilyResidual)
    for c in (10e-6, 8e-6):
        a = family.evaluate(x0, W, c, d_param=True, d_omega=True)
        b = elements.evaluate(x0, W, c, d_param=True, d_omega=True)
        scale = np.max(np.abs(b.r))
        np.testing.assert_allclose(a.r, b.r, rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(a.jacobian, b.jacobian, rtol=1e-10,
                                   atol=1e-12 * np.max(np.abs(b.jacobian)))
        np.testing.assert_allclose(a.d_omega, b.d_omega, rtol=1e-8,
                                   atol=1e-10 * np.max(np.abs(b.d_omega)))
        np.testing.assert_allclose(a.d_param, b.d_param, rtol=1e-6,
                                   atol=1e-8 * np.max(np.abs(b.d_param)))
        np.testing.assert_allclose(family.expand(x0, W, c), elements.expand(x0, W, c),
                                   rtol=1e-10, atol=1e-18)
    coarse = family.with_discretization(harmonics=2)
    assert coarse.harmonics == 2 and coarse.evaluate(
        coarse.restrict(family.expand(x0, W, 9e-6)[:5]), W, 9e-6).r.shape == (coarse.size,)


def test_the_damping_derivative_is_that_of_the_dynamic_stiffness():
    """d R / d c of a damper: the condensed residual changes by i h omega dC X, exactly
    linear in c, so the central difference equals the difference quotient over a wide
    step (independent of the step used inside)."""
    system = assemble(damped(5000.0))
    plan = plan_excitation(system.nonlinear.elements, unbalance=True, base=None,
                           varying_compliance=None, fundamental=None,
                           frequency_parameter=False)
    rp = build_problem(system, plan, speed0=W, fixed_speed=None, phi0=0.0,
                       unbalance=UNBALANCE, gravity=9.81, direction=(0, -1, 0), loads=[],
                       base=None, stats=Stats())
    family = parametric_residual(rp, system, damped, 4, None, 1000.0, 5000.0)
    x = np.random.default_rng(0).normal(scale=1e-6, size=family.size)
    d = family.evaluate(x, W, 5000.0, d_param=True).d_param
    wide = (family.evaluate(x, W, 5400.0).r - family.evaluate(x, W, 4600.0).r) / 800.0
    # the Schur complement makes R_c rational in c: the wide quotient differs at O(dc^2)
    np.testing.assert_allclose(d, wide, rtol=0, atol=2e-3 * np.max(np.abs(wide)))
    assert np.max(np.abs(d)) > 0


@pytest.mark.parametrize("vary, match", [
    (lambda c: jeffcott(damping=c).with_fixed([(1, "uz"), (1, "rz")]),
     "nodes or constraints"),
    (lambda c: jeffcott().linear_part(), "nonlinear DOFs"),
    (lambda c: jeffcott().linear_part().with_nonlinear(
        [RollingBearing(ball("fixed"), n=n) for n in (0, 1)]), "nonlinear DOFs"),
    (lambda c: jeffcott(cage="rotating" if c < 4000.0 else "fixed"),
     "varying-compliance orders"),
])
def test_a_vary_that_changes_the_structure_is_refused_with_the_value(vary, match):
    def changed_later(c):
        return jeffcott(damping=c) if c == 5000.0 else vary(c)

    with pytest.raises(InconsistentModelError, match=match):
        rs.periodic_parameter(jeffcott(), changed_later, speed=W, start=5000.0,
                              stop=3000.0, unbalance=UNBALANCE, harmonics=3,
                              continuation=rs.ContinuationOptions(max_points=20), stability=None)


def test_loads_mode_needs_loads():
    with pytest.raises(ModelError, match="nonzero point loads"):
        rs.periodic_parameter(jeffcott(), "loads", speed=W, start=0.0, stop=100.0,
                              unbalance=UNBALANCE, harmonics=3)
    with pytest.raises(ModelError, match="'loads' or 'forcing'"):
        rs.periodic_parameter(jeffcott(), "load", speed=W, start=0.0, stop=100.0)
