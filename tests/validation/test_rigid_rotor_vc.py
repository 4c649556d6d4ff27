"""The textbook varying-compliance case: a rigid rotor of 1 kg under 50 N in an 8-ball bearing
with 10 um radial clearance (``models/rigid_rotor_vc.toml``), started from the centred
position inside the clearance.

Reference: the Hertz point-contact load-deflection of the loaded balls,
``W = sum_j Kn (d cos(psi_j - psi_W) - c)^1.5 cos(psi_j - psi_W)`` over the balls in contact
(Harris & Kotzalas, *Rolling Bearing Analysis*, the radial load distribution), solved for the
deflection ``d`` along the load with ``brentq`` from the bearing's constant ``Kn``, clearance
``c`` and ball angles ``psi_j`` only: independent of rotorsim's solvers.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import rotorsim as rs
from rotorsim.analyses.statics.nonlinear_static import nonlinear_equilibrium
from rotorsim.analyses.statics.static_start import static_start
from rotorsim.assembly.loads import nodal_load
from rotorsim.assembly.system import assemble
from rotorsim.solvers.stats import Stats

MODEL = Path(__file__).resolve().parents[2] / "models" / "rigid_rotor_vc.toml"
LOAD = 50.0  # N along -y
STATIC_TOL = 1e-10
"""Relative force residual of the static Newton iterations (rs.static and the HB start)."""


def textbook() -> tuple[rs.Rotor, rs.BallBearing]:
    """The model file's rotor with its rolling bearing."""
    model = rs.load_model(MODEL)
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    return rotor, model.rolling_bearings[0].bearing


def hertz_deflection(bearing: rs.BallBearing, load: float, phi: float = 0.0) -> float:
    """Deflection [m] along a load pointing to -y from the loaded balls' Hertz law."""
    psi = np.asarray(bearing.element_angles(phi), dtype=float).ravel() + 0.5 * math.pi
    kn, c, n = float(bearing.Kn), float(bearing.clearance), float(bearing.exponent)

    def imbalance(d: float) -> float:
        delta = d * np.cos(psi) - c
        loaded = delta > 0
        return float(np.sum(kn * delta[loaded] ** n * np.cos(psi[loaded]))) - load

    return brentq(imbalance, c, c + 1e-3, xtol=1e-20, rtol=4 * np.finfo(float).eps)


def test_the_model_file_is_the_textbook_case():
    rotor, bearing = textbook()
    assert rotor.shaft_elements == () and rotor.n_nodes == 1
    assert rotor.m == pytest.approx(1.0, rel=1e-15)
    assert bearing.n_balls == 8 and bearing.clearance == pytest.approx(10e-6, rel=1e-15)
    model = rs.load_model(MODEL)
    assert model.loads.gravity is None and model.loads.point_loads == ((0, "uy", -LOAD),)


@pytest.mark.validation  # against the Hertz law solved in this file
def test_static_from_the_centred_start_balances_the_load_and_matches_hertz():
    rotor, bearing = textbook()
    s = rs.static(rotor, gravity=None, loads=[(0, "uy", -LOAD)])
    # force balance to the Newton tolerance (relative force residual 1e-10; x10 for the
    # reaction being recomputed from the tangent at the solution)
    assert s.bearing_forces[0, 1] == pytest.approx(LOAD, rel=10 * STATIC_TOL)
    assert abs(s.bearing_forces[0, 0]) <= 10 * STATIC_TOL * LOAD
    d_ref = hertz_deflection(bearing, LOAD)
    assert d_ref == pytest.approx(13.07e-6, rel=1e-3)  # 3.07 um of contact beyond 10 um
    # deflection: W ~ (d - c)^1.5 turns a 1e-10 force residual into ~1e-11 of d; 1e-6 is
    # far above that and far below any modelling difference
    assert -s.displacement[1] == pytest.approx(d_ref, rel=1e-6)
    loads = s.element_loads["B"]
    assert float(np.sum(loads > 0)) == 1  # only the ball under the load touches
    assert float(loads.max()) == pytest.approx(LOAD, rel=10 * STATIC_TOL)


def _system_and_load(fixed: tuple[tuple[int, str], ...] | None = None):
    rotor, _ = textbook()
    if fixed is not None:
        rotor = rs.Rotor([], rotor.disk_elements, fixed=fixed,
                         nonlinear_elements=rotor.nonlinear_elements)
    system = assemble(rotor)
    return rotor, system, nodal_load(system, 0, "uy", -LOAD)


@pytest.mark.validation  # against the Hertz law solved in this file
def test_newton_from_the_centred_start_falls_back_to_the_energy_minimum():
    # the path that failed (issue 12): Newton from inside the clearance, then 64 load
    # steps, each ending in a line-search failure; now the energy minimum takes over
    _, bearing = textbook()
    _, system, f = _system_and_load()
    eq = nonlinear_equilibrium(system, f, q0=np.zeros(system.n_free))
    assert eq.method == "energy" and eq.residual <= STATIC_TOL
    assert -eq.q[1] == pytest.approx(hertz_deflection(bearing, LOAD), rel=1e-6)


@pytest.mark.validation  # against the Hertz law solved in this file
@pytest.mark.parametrize("fixed", [None, ((0, "rz"),), ()],
                         ids=["radial 2-DOF", "5 DOF", "6 DOF"])
def test_periodic_static_start_converges_from_the_centred_start(fixed):
    # with tilt and axial motion free the rocking about the loaded ball has no stiffness,
    # so the static position is set in y only: the y force balance is what must hold
    _, bearing = textbook()
    _, system, f = _system_and_load(fixed)
    q, _ = static_start(system, system.matrices(100.0).K, f, 100.0, 0.0, Stats())
    assert np.all(np.isfinite(q))
    y = system.dofs_of(0, ("uy",))[0]
    assert -q[y] == pytest.approx(hertz_deflection(bearing, LOAD), rel=1e-6)


@pytest.mark.validation  # against the Hertz law solved in this file
def test_periodic_runs_from_the_centred_start_over_a_short_speed_range():
    rotor, bearing = textbook()
    clock = time.perf_counter()
    res = rs.periodic(rotor, start=100.0, stop=110.0,
                      excitation=rs.Excitation(gravity=None, loads=[(0, "uy", -LOAD)]),
                      continuation=rs.ContinuationOptions(max_step=0.2, max_points=40),
                      stability=rs.StabilityOptions(bifurcations=False), harmonics=4)
    assert time.perf_counter() - clock < 10.0
    assert res.parameter[0] == pytest.approx(100.0, rel=1e-12)
    assert res.parameter[-1] == pytest.approx(110.0, rel=1e-9)
    assert res.order == pytest.approx(bearing.n_balls * bearing.kappa, rel=1e-12)  # VC
    mean_y = res.amplitude(0, "uy", "mean")
    # the mean over a ball pass stays within the deflections of the ball positions: between
    # the one-ball (phi = 0) and the two-ball (ball pass half-way) Hertz deflections
    half_pass = math.pi / (bearing.n_balls * bearing.kappa)
    bounds = sorted([hertz_deflection(bearing, LOAD, 0.0),
                     hertz_deflection(bearing, LOAD, half_pass)])
    assert np.all(-mean_y >= bounds[0]) and np.all(-mean_y <= bounds[1])
    assert np.all(res.amplitude(0, "uy", "peak_to_peak") > 0)  # the VC vibration


@pytest.mark.validation  # against the Hertz law solved in this file
def test_every_analysis_of_the_model_file_runs():
    from rotorsim.io.model_file import run_analysis

    model = rs.load_model(MODEL)
    static = run_analysis(model, "static")
    assert -static.displacement[1] == pytest.approx(
        hertz_deflection(model.rolling_bearings[0].bearing, LOAD), rel=1e-6)
    # one ball in contact at the static load: k_y = 1.5 Kn (d - c)^0.5 (Hertz tangent)
    bearing = model.rolling_bearings[0].bearing
    k_y = 1.5 * bearing.Kn * (hertz_deflection(bearing, LOAD) - bearing.clearance) ** 0.5
    wn = run_analysis(model, "modes").wn
    assert wn == pytest.approx([math.sqrt(k_y / 1.0)], rel=1e-9)
    branch = run_analysis(model, "vc")
    assert branch.parameter[-1] == pytest.approx(1100 * math.pi / 30, rel=1e-9)


def test_the_periodic_static_start_uses_a_given_start():
    _, system, f = _system_and_load()
    K = system.matrices(100.0).K
    centred, given = Stats(), Stats()
    q, _ = static_start(system, K, f, 100.0, 0.0, centred)
    again, _ = static_start(system, K, f, 100.0, 0.0, given, q)
    assert given.iterations == 0 < centred.iterations  # Newton stops at once from there
    assert again[1] == pytest.approx(q[1], rel=1e-12)


@pytest.mark.validation  # against the Hertz law solved in this file
def test_the_issue_reproduction_with_a_stub_shaft_starts():
    # issue 12 as reported (before rotors without shaft existed): the rigid rotor on a
    # massless, nearly stiffless stub element to a fixed node, tilt and axial motion free;
    # the HB static start failed with a line-search failure at all 64 load steps
    rotor, bearing = textbook()
    ghost = rs.Material(name="ghost", E=1.0, G_s=0.4, rho=1e-9)
    stub = rs.Rotor([rs.ShaftElement(L=0.01, idl=0.0, odl=0.01, material=ghost)],
                    rotor.disk_elements, nonlinear_elements=rotor.nonlinear_elements,
                    fixed=[(1, d) for d in rs.DOF_NAMES])
    system = assemble(stub)
    f = nodal_load(system, 0, "uy", -LOAD)
    q, _ = static_start(system, system.matrices(100.0).K, f, 100.0, 0.0, Stats())
    y = system.dofs_of(0, ("uy",))[0]
    assert -q[y] == pytest.approx(hertz_deflection(bearing, LOAD), rel=1e-6)
    res = rs.periodic(stub, start=100.0, stop=101.0,
                      excitation=rs.Excitation(gravity=None, loads=[(0, "uy", -LOAD)]),
                      continuation=rs.ContinuationOptions(max_points=3),
                      stability=rs.StabilityOptions(None, bifurcations=False), harmonics=3)
    assert len(res) >= 2


def hertz_stiffness(bearing: rs.BallBearing, load: float, phi: float) -> float:
    """``dW/dd = sum_j 1.5 Kn (d cos psi_j - c)^0.5 cos^2 psi_j`` over the loaded balls
    (load along -y, the deflection d of :func:`hertz_deflection`) [N/m]."""
    d = hertz_deflection(bearing, load, phi)
    psi = np.asarray(bearing.element_angles(phi), dtype=float).ravel() + 0.5 * math.pi
    delta = d * np.cos(psi) - float(bearing.clearance)
    on = delta > 0
    return float(np.sum(1.5 * bearing.Kn * delta[on] ** 0.5 * np.cos(psi[on]) ** 2))


@pytest.mark.validation  # against the Hertz law solved in this file
def test_stiffness_over_a_ball_pass_of_the_textbook_bearing():
    # the VC stiffness variation itself: the warm start from the previous position fails
    # where a second ball comes into contact, and the ray guess or the energy method takes
    # over (it raised ConvergenceError in `rotorsim bearing` before)
    _, bearing = textbook()
    v = rs.stiffness_over_pass(bearing, [0.0, -LOAD, 0.0, 0.0, 0.0], n_points=24)
    assert v.stiffness[0, 1, 1] == pytest.approx(hertz_stiffness(bearing, LOAD, 0.0),
                                                 rel=1e-6)
    half = v.shaft_angle[12]  # half a ball pass: two balls at +-22.5 deg from the load
    assert v.stiffness[12, 1, 1] == pytest.approx(hertz_stiffness(bearing, LOAD, half),
                                                  rel=1e-6)
    assert -v.displacement[12, 1] == pytest.approx(hertz_deflection(bearing, LOAD, half),
                                                   rel=1e-6)
    # the ring moves sideways symmetrically about the half pass (mirror image positions)
    np.testing.assert_allclose(v.displacement[1:12, 0], -v.displacement[23:12:-1, 0],
                               atol=1e-6 * 13e-6)
