"""Torque-driven speed: the rigid spin against closed forms and an independent solve_ivp,
the polar inertia from the model, standstill and bad input (issue 14, part 5)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import rotorsim as rs
from rotorsim.analyses.transient.torsion_loads import (
    TorsionLoad,
    bind_speed,
    element_polar_inertia,
    model_polar_inertia,
)
from rotorsim.assembly.system import assemble
from rotorsim.errors import ModelError

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
D, L, N_EL, IP_DISK = 0.05, 0.25, 4, 0.1
NO_GRAVITY = rs.Excitation(gravity=None)
SPIN_TOL = 1e-8
"""Relative accuracy of W and phi: the spin equation is integrated at rtol 1e-10 (DOP853,
dense output of order 7); 1e-8 leaves room for the error growth over the run."""


def _rotor(**shaft_keys: float) -> rs.Rotor:
    shaft = [rs.ShaftElement(L=L, idl=0.0, odl=D, material=STEEL, **shaft_keys)
             for _ in range(N_EL)]
    bearings = [rs.BearingElement(n=0, kxx=1e7, cxx=1e3),
                rs.BearingElement(n=N_EL, kxx=1e7, cxx=1e3)]
    return rs.Rotor(shaft, [rs.DiskElement(n=2, m=10.0, Id=0.05, Ip=IP_DISK)], bearings,
                    fixed=[(0, "uz")])


def _closed_form_inertia() -> float:
    """``rho pi d^4 / 32 L`` of the shaft plus the disk [kg m^2]."""
    return STEEL.rho * math.pi * D**4 / 32.0 * L * N_EL + IP_DISK


def test_polar_inertia_from_mass_matrix_equals_elements_and_closed_form():
    rotor = _rotor()
    J = _closed_form_inertia()
    assert model_polar_inertia(assemble(rotor)) == pytest.approx(J, rel=1e-12)
    assert element_polar_inertia(rotor) == pytest.approx(J, rel=1e-12)
    tapered = rs.Rotor([rs.ShaftElement(L=0.3, idl=0.01, odl=0.04, idr=0.02, odr=0.07,
                                        material=STEEL),
                        rs.ShaftElement(L=0.2, idl=0.0, odl=0.07, material=STEEL)],
                       [rs.DiskElement(n=1, m=5.0, Id=0.02, Ip=0.04)])
    # the mass matrix integrates rho J(z) by the shaft module's own quadrature, the
    # element sum by a 3-point Gauss rule: both exact for the quartic of a linear taper
    assert model_polar_inertia(assemble(tapered)) == pytest.approx(
        element_polar_inertia(tapered), rel=1e-12)


@pytest.mark.verification
def test_spin_up_under_constant_torque_matches_closed_form():
    """(a) W = W0 + T t / J_p, phi = W0 t + T t^2 / (2 J_p), J_p from the model."""
    T, W0, t_end = 40.0, 20.0, 0.2
    res = rs.transient(_rotor(), t_end, 1e-3, speed=rs.TorqueDrive(motor=T, initial_speed=W0),
                       excitation=NO_GRAVITY, initial="zero", nodes=[2])
    J = _closed_form_inertia()
    assert res.options["speed"]["inertia"] == pytest.approx(J, rel=1e-12)
    t = res.t
    np.testing.assert_allclose(res.speed, W0 + T * t / J, rtol=SPIN_TOL)
    np.testing.assert_allclose(res.angle, W0 * t + T * t**2 / (2 * J), rtol=SPIN_TOL,
                               atol=SPIN_TOL)
    np.testing.assert_allclose(res.acceleration, T / J, rtol=1e-12)


@pytest.mark.verification
def test_coast_down_under_quadratic_drag_matches_closed_form():
    """(b) W = W0 / (1 + c W0 t / J_p), phi = (J_p / c) ln(1 + c W0 t / J_p)."""
    c, W0, t_end = 2e-4, 600.0, 0.5
    drive = rs.TorqueDrive(motor=0.0, loads=[(N_EL, rs.QuadraticTorque(c))],
                           initial_speed=W0)
    res = rs.transient(_rotor(), t_end, 1e-3, speed=drive, excitation=NO_GRAVITY,
                       initial="zero", nodes=[2])
    J, t = _closed_form_inertia(), res.t
    np.testing.assert_allclose(res.speed, W0 / (1 + c * W0 * t / J), rtol=SPIN_TOL)
    np.testing.assert_allclose(res.angle, J / c * np.log1p(c * W0 * t / J), rtol=SPIN_TOL,
                               atol=SPIN_TOL)
    assert res.speed[-1] < 0.7 * W0  # the drag did slow it down


def _kloss(W: float, Tb: float, sb: float, Ws: float) -> float:
    s = (Ws - W) / Ws
    return 2 * Tb / (s / sb + sb / s) if s != 0 else 0.0


@pytest.mark.verification
def test_induction_motor_start_against_fan_matches_independent_solve_ivp():
    """(d) Kloss motor against a fan load c W^2, against Radau on the scalar ODE written
    here (rtol 1e-12)."""
    Tb, sb, Ws, c, J = 50.0, 0.15, 157.0, 1e-3, 0.2
    drive = rs.TorqueDrive(motor=rs.InductionMotor(Tb, sb, Ws),
                           loads=[(0, rs.QuadraticTorque(c))], inertia=J)
    bound = drive.bind(0.0, 3.0)
    ref = solve_ivp(lambda t, y: [(_kloss(y[0], Tb, sb, Ws) - c * y[0] ** 2) / J, y[0]],
                    (0.0, 3.0), [0.0, 0.0], method="Radau", rtol=1e-12, atol=1e-12,
                    dense_output=True)
    t = np.linspace(0.0, 3.0, 301)
    W_ref, phi_ref = ref.sol(t)
    W = np.array([bound.speed(x) for x in t])
    phi = np.array([bound.angle(x) for x in t])
    np.testing.assert_allclose(W, W_ref, rtol=SPIN_TOL, atol=SPIN_TOL * Ws)
    np.testing.assert_allclose(phi, phi_ref, rtol=SPIN_TOL, atol=SPIN_TOL * Ws)
    # it runs up to the operating point where Kloss meets the fan: slip below breakdown
    assert 1 - W[-1] / Ws < sb
    assert abs(_kloss(W[-1], Tb, sb, Ws) - c * W[-1] ** 2) < 1e-3 * Tb


def test_friction_coast_down_stops_and_stays_stopped():
    J, W0, Tf = 0.1, 100.0, 1.0
    drive = rs.TorqueDrive(motor=0.0, friction=[(0, rs.ConstantTorque(Tf))],
                           initial_speed=W0, inertia=J)
    bound = drive.bind(0.0, 20.0)
    t_stop = J * W0 / Tf
    assert bound.history.stops == pytest.approx([t_stop], rel=1e-9)
    assert bound.speed(15.0) == 0.0 and bound.acceleration(15.0) == 0.0
    assert bound.angle(15.0) == pytest.approx(W0 * t_stop / 2, rel=1e-9)
    _, torques = bound.node_torques(15.0)
    assert torques.sum() == 0.0
    assert bound.describe()["stops"] == bound.history.stops


def test_motor_breaks_away_when_its_torque_exceeds_the_friction():
    """A ramped motor torque 2 t [N m] against 1 N m of friction: at rest until 0.5 s,
    then J W' = 2 t - 1."""
    bound = rs.TorqueDrive(motor=lambda W, t: 2.0 * t, friction=[(0, 1.0)],
                           inertia=0.1).bind(0.0, 2.0)
    assert bound.history.segments[0].t_end == pytest.approx(0.5, abs=1e-6)
    assert bound.speed(0.4) == 0.0
    assert bound.speed(1.5) == pytest.approx((1.5**2 - 1.5 + 0.25) / 0.1, rel=1e-6)


def test_torsional_loads_sum_to_zero_so_the_rigid_mode_stays_at_rest():
    system = assemble(_rotor())
    M = system.matrices().M
    drive = rs.TorqueDrive(motor=rs.PulsatingTorque(rs.InductionMotor(80.0, 0.2, 300.0),
                                                    5.0, 3),
                           loads=[(N_EL, rs.QuadraticTorque(1e-4)), (2, 3.0)])
    for inertia in (None, 2.0 * _closed_form_inertia()):
        bound = bind_speed(rs.TorqueDrive(**{**_fields(drive), "inertia": inertia}), system,
                           None, (0.0, 0.5), 4096)
        load = TorsionLoad.build(system, bound, M)
        assert load is not None
        for t in (0.0, 0.1, 0.37):
            f = load(t)
            scale = np.abs(f).max()
            assert abs(f.sum()) < 1e-12 * scale * f.size  # rounding of the sum only


def _fields(drive: rs.TorqueDrive) -> dict:
    keys = ("motor", "drive_node", "loads", "friction", "initial_speed", "phi0", "inertia")
    return {k: getattr(drive, k) for k in keys}


@pytest.mark.parametrize(("make", "match"), [
    (lambda: rs.TorqueDrive(motor=-1.0, initial_speed=10.0, inertia=0.1).bind(0.0, 5.0),
     "turn backwards"),
    (lambda: rs.TorqueDrive(motor=lambda W, t: math.nan, inertia=0.1).bind(0.0, 1.0),
     r"TorqueDrive\.motor: torque is nan"),
    (lambda: rs.TorqueDrive(motor=1.0).bind(0.0, 1.0), r"TorqueDrive\.inertia"),
    (lambda: rs.TorqueDrive(motor=1.0, initial_speed=-1.0), "initial_speed"),
    (lambda: rs.TorqueDrive(motor=1.0, loads=[3.0]), r"TorqueDrive\.loads\[0\]"),
    (lambda: rs.TorqueDrive(motor="fast"), r"TorqueDrive\.motor"),
    (lambda: rs.InductionMotor(10.0, 1.5, 100.0), "breakdown_slip"),
    (lambda: rs.TorqueCurve([0.0, 0.0], [1.0, 2.0]), "strictly increasing"),
    (lambda: rs.QuadraticTorque(-1.0), "coefficient"),
])
def test_bad_drives_raise_model_errors_naming_the_culprit(make, match):
    with pytest.raises(ModelError, match=match):
        make()


def test_drive_node_must_be_on_the_shaft():
    drive = rs.TorqueDrive(motor=1.0, loads=[(9, rs.ViscousTorque(0.1))])
    with pytest.raises(ModelError, match=r"TorqueDrive\.loads\[0\]: node 9 is not a shaft"):
        rs.transient(_rotor(), 0.01, 1e-3, speed=drive, initial="zero")


def test_torque_curve_interpolates_and_holds_its_ends():
    curve = rs.TorqueCurve([0.0, 100.0, 200.0], [10.0, 30.0, 0.0])
    assert curve.torque(50.0, 0.0, 0.0) == 20.0
    assert curve.torque(300.0, 0.0, 0.0) == 0.0
    assert curve.slope(150.0, 0.0, 0.0) == pytest.approx(-0.3)


def test_law_slopes_match_finite_differences():
    laws = [rs.InductionMotor(50.0, 0.2, 150.0), rs.QuadraticTorque(2e-3),
            rs.ViscousTorque(0.3), rs.TorqueFunction(lambda W, t: 3.0 * W**1.5 + t)]
    for law in laws:
        for W in (10.0, 100.0, 140.0):
            h = 1e-5 * W
            fd = (law.torque(W + h, 0.5, 0.0) - law.torque(W - h, 0.5, 0.0)) / (2 * h)
            assert law.slope(W, 0.5, 0.0) == pytest.approx(fd, rel=1e-6)


def test_joined_local_tangents_equal_their_dense_sum():
    from rotorsim.analyses.transient.loads import _joined
    from rotorsim.time_integration.local_tangent import LocalMatrix

    rng = np.random.default_rng(3)
    a = LocalMatrix(8, np.array([0, 2, 5]), rng.normal(size=(3, 3)))
    for dofs in (np.array([3, 7]), np.array([5, 6])):  # disjoint, overlapping
        b = LocalMatrix(8, dofs, np.diag(rng.normal(size=2)))
        np.testing.assert_array_equal(_joined(a, b).toarray(), a.toarray() + b.toarray())


def test_drive_on_rolling_bearings_adds_its_damping_to_the_bearing_tangents():
    """A Kloss motor on the rolling-bearing model: the drive's torsional damping joins the
    bearings' local tangents (one restoring force); the run converges as without it."""
    model = rs.load_model("models/rolling_ball.toml")
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    runs = [rs.transient(rotor, 2e-3, 2e-5, speed=rs.TorqueDrive(
                motor=rs.InductionMotor(20.0, 0.2, 600.0), initial_speed=300.0,
                loads=[(rotor.n_shaft_nodes - 1, rs.QuadraticTorque(1e-5))],
                torque_damping=damped), nodes=[0]) for damped in (True, False)]
    for run in runs:
        assert run.status == rs.Status.OK
        assert run.stats["iterations_per_step"] <= 3
    twist = [run.q[:, run.column(0, "rz")] for run in runs]
    assert not np.array_equal(twist[0], twist[1])  # the damping acts on the drive node
