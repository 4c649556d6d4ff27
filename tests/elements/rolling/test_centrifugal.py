"""Centrifugal force of the rolling elements (issue 4): CentrifugalBearing and its element.

Contract (speed 0 = the rigid models bit for bit; force = gradient of the condensed
potential, stiffness = its Hessian, at speed, with elements riding on the outer race),
closed-form and independent-equation checks, the high-speed softening, warm starts.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium, linearize_at_load
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.centrifugal import CentrifugalBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.elements.rolling.geometry import cage_ratio
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.profile import CircularCrown, LogarithmicProfile
from rotorsim.errors import ModelError

STEEL = 7850.0  # kg/m^3
RPM = math.pi / 30.0
ROLLER = dict(n_rollers=14, pitch_diameter=42.5e-3, roller_diameter=7.5e-3,
              effective_length=7.5e-3, Kn=3.0e8)
BASES = {
    "deep_groove": BallBearing.from_geometry(
        n_balls=9, pitch_diameter=46e-3, ball_diameter=9.525e-3, f_i=0.515, f_o=0.525,
        diametral_clearance=10e-6),
    "angular_25deg": BallBearing.from_geometry(
        n_balls=12, pitch_diameter=40e-3, ball_diameter=8e-3, f_i=0.52, f_o=0.53,
        contact_angle=math.radians(25.0)),
    "cylindrical_tilt": RollerBearing(**ROLLER, radial_clearance=1.0e-6),
    "tapered_crowned_slices": RollerBearing(
        **ROLLER, contact_angle=math.radians(15.0), model="slices", n_slices=9,
        profile=CircularCrown(crown_drop=4e-6, crown_length=2e-3)),
    "log_slices": RollerBearing(**ROLLER, model="slices", n_slices=15,
                                profile=LogarithmicProfile.with_end_drop(2e-6, 8e-6)),
}
SCALE = np.array([12e-6, 12e-6, 12e-6, 6e-4, 6e-4])  # displacement sizes [m, rad]
SPEED = 30000.0 * RPM  # a high speed: Fc ~ 100 N on these 2-3 g elements


def _model(name: str, **kwargs) -> CentrifugalBearing:
    return CentrifugalBearing(BASES[name], element_density=STEEL, **kwargs)


def _states(model, n: int, seed: int, push: float = 0.5):
    rng = np.random.default_rng(seed)
    delta = rng.normal(size=(n, 5)) * SCALE
    delta[:, 2] += push * SCALE[2]  # towards the rings of the tapered bearing
    return delta, model.element_angles(rng.uniform(0.0, 2.0 * np.pi, n))


@pytest.mark.parametrize("name", BASES)
def test_zero_speed_is_the_rigid_model_bit_for_bit(name):
    model = _model(name)
    delta, psi = _states(model, 20, seed=1)
    base = BASES[name].state(delta, psi)
    for speeds in (0.0, np.where(np.arange(20) % 2 == 0, 0.0, SPEED)):
        st = model.state(delta, psi, speed=speeds)
        rest = np.asarray(speeds) == 0.0 if np.ndim(speeds) else np.ones(20, dtype=bool)
        for key in ("force", "stiffness", "energy", "element_load", "contact_angle",
                    "deflection", "contact_direction", "element_stiffness"):
            assert np.array_equal(getattr(st, key)[rest], getattr(base, key)[rest]), key
        assert np.array_equal(st.outer_load[rest], base.element_load[rest])
        assert np.isnan(st.internal[rest]).all()
    # the 2-node element too, whatever the speed it is given when the model has no Fc
    plain, spun = RollingBearing(BASES[name], n=0), RollingBearing(model, n=0)
    u = np.hstack([delta, np.zeros((20, 1))])
    a, b = plain.force(u, np.zeros_like(u), 0.3, 0.0), spun.force(u, np.zeros_like(u), 0.3, 0.0)
    assert np.array_equal(a.f, b.f) and np.array_equal(a.K, b.K)


@pytest.mark.parametrize("name", BASES)
def test_force_is_the_gradient_of_the_condensed_potential_at_speed(name):
    model = _model(name)
    delta, psi = _states(model, 30, seed=2)
    st = model.state(delta, psi, speed=SPEED)
    riding = (st.element_load == 0.0) & (st.outer_load > 0.0)
    assert st.loaded.mean() > 0.1 and np.all(st.outer_load >= st.element_load)
    # elements riding on the outer race are checked too, except in the angular-contact
    # bearing: there the inner groove keeps every ball pinched (next test)
    assert riding.mean() >= (0.0 if name == "angular_25deg" else 0.1)
    # step 1e-6 of the displacement size: the roller tangent ~ delta^(1/9) has no
    # derivative where a contact starts (test_roller.py); internal DOFs converged to 1e-10
    steps = 1e-6 * SCALE
    fd_force, fd_stiff = np.empty_like(st.force), np.empty_like(st.stiffness)
    for i in range(5):
        e = np.zeros(5)
        e[i] = steps[i]
        up, down = model.state(delta + e, psi, SPEED), model.state(delta - e, psi, SPEED)
        fd_force[:, i] = (up.energy - down.energy) / (2.0 * steps[i])
        fd_stiff[:, :, i] = (up.force - down.force) / (2.0 * steps[i])
    f_scaled = st.force * SCALE
    f_ref = np.maximum(np.abs(f_scaled).max(axis=1), 1e-30)
    assert np.all(np.abs(fd_force * SCALE - f_scaled).max(axis=1) <= 1e-6 * f_ref)
    k_scaled = st.stiffness * SCALE[:, None] * SCALE[None, :]
    k_ref = np.maximum(np.abs(k_scaled).max(axis=(1, 2)), 1e-30)
    err = np.abs(fd_stiff * SCALE[:, None] * SCALE[None, :] - k_scaled).max(axis=(1, 2))
    assert np.all(err <= 1e-6 * k_ref)
    assert np.array_equal(st.stiffness, st.stiffness.transpose(0, 2, 1))
    # force = sum_j Q_j g_j over the inner contacts
    assert np.allclose(np.einsum("sn,snk->sk", st.element_load, st.contact_direction),
                       st.force, rtol=0.0, atol=1e-9 * np.abs(st.force).max())


def dataclass_copy(bearing, **changes):
    return dataclasses.replace(bearing, **changes)


@pytest.mark.parametrize("name", [n for n in BASES if n != "angular_25deg"])
def test_unloaded_bearing_at_speed_carries_nothing_on_the_inner_ring(name):
    base = BASES[name]
    model = CentrifugalBearing(dataclass_copy(base, radial_clearance=0.0,
                                              diametral_clearance=None), element_density=STEEL)
    psi = model.element_angles([0.0, 0.4])
    st = model.state(np.zeros((2, 5)), psi, speed=SPEED)
    assert np.all(st.force == 0.0) and np.all(st.stiffness == 0.0)
    assert np.all(st.element_load == 0.0)
    # every element rests on the outer race with Fc along the normal (rollers: Fc cos a0)
    fc = model.centrifugal_force(SPEED) * (math.cos(base.contact_angle)
                                           if isinstance(base, RollerBearing) else 1.0)
    assert np.allclose(st.outer_load, fc, rtol=1e-9)


def test_angular_contact_balls_at_speed_are_pinched_by_the_inner_groove():
    """Without axial play a ball of an angular-contact bearing cannot roll down to the
    bottom of the outer groove (it would move away from the inner groove centre, into the
    inner race): at speed it stays pinched and pushes the inner ring towards -z (the
    bearing force, the load that holds the ring in place, points to +z)."""
    model = _model("angular_25deg")
    st = model.state(np.zeros((1, 5)), model.element_angles(), speed=SPEED)
    assert np.all(st.element_load > 0.0) and np.all(st.outer_load > st.element_load)
    assert st.force[0, 2] > 0.0
    assert np.allclose(st.force[0, [0, 1, 3, 4]], 0.0, atol=1e-12 * st.force[0, 2])
    assert np.all(st.outer_contact_angle < BASES["angular_25deg"].contact_angle)


@pytest.mark.validation
@pytest.mark.parametrize("approach", [0.3e-6, 2.0e-6, 8.0e-6, 25.0e-6])
def test_cylindrical_roller_against_the_series_law_solved_by_hand(approach):
    """One straight roller, pure radial approach V: K_c = 2^n Kn per contact,
    K_c d_o^n = K_c (V - d_o)^n + Fc (brentq), Q_i = K_c (V - d_o)^n, dQ_i/dV =
    k_i k_o / (k_i + k_o); below the Fc-only outer deflection the roller rides (Q_i = 0)."""
    kn, n = 3.0e8, 10.0 / 9.0
    base = RollerBearing(1, 42.5e-3, 7.5e-3, 7.5e-3, Kn=kn, cage="fixed")
    model = CentrifugalBearing(base, element_mass=0.01)
    fc = model.centrifugal_force(SPEED)
    kc = 2.0**n * kn
    d_o = brentq(lambda d: kc * d**n - kc * max(approach - d, 0.0) ** n - fc, 0.0,
                 approach + (fc / kc) ** (1.0 / n), xtol=1e-22, rtol=1e-15)
    q_i = kc * max(approach - d_o, 0.0) ** n
    st = model.state([[approach, 0.0, 0.0, 0.0, 0.0]], [[0.0]], speed=SPEED)
    assert st.force[0, 0] == pytest.approx(q_i, rel=1e-9, abs=1e-9 * fc)
    assert st.outer_load[0, 0] == pytest.approx(q_i + fc, rel=1e-9)
    assert st.internal[0, 0, 0] == pytest.approx(d_o, rel=1e-9)  # outer approach [m]
    if q_i > 0.0:
        k_i, k_o = n * q_i / (approach - d_o), n * (q_i + fc) / d_o
        assert st.stiffness[0, 0, 0] == pytest.approx(k_i * k_o / (k_i + k_o), rel=1e-8)
    else:  # V = 0.3 um < (Fc/K_c)^(1/n) = 0.33 um: riding on the outer race
        assert approach < (fc / kc) ** (1.0 / n) and st.stiffness[0, 0, 0] == 0.0


@pytest.mark.validation
@pytest.mark.parametrize("axial", [2e-6, 10e-6, 25e-6])
def test_thrust_loaded_ball_matches_the_jones_equations_without_gyroscopic_moment(axial):
    """Harris & Kotzalas (Rolling Bearing Analysis, 2007, ch. 3 'high-speed operation')
    write the ball equilibrium of a thrust-loaded angular-contact bearing in the ball-centre
    coordinates (X1 axial, X2 radial from the outer groove centre) and the two deflections;
    with the gyroscopic moment set to zero::

        (A1 - X1)^2 + (A2 - X2)^2 = (rho_i + d_i)^2,   X1^2 + X2^2 = (rho_o + d_o)^2
        Q_o sin(a_o) - Q_i sin(a_i) = 0,   Q_o cos(a_o) - Q_i cos(a_i) - Fc = 0

    solved here with fsolve, independently of the model's polar Newton and condensation."""
    base = BASES["angular_25deg"]
    model = CentrifugalBearing(base, element_density=STEEL)
    fc = model.centrifugal_force(SPEED)
    d, a0, kc = base.ball_diameter, base.contact_angle, 2.0**1.5 * base.Kn
    rho_i, rho_o = (base.f_i - 0.5) * d, (base.f_o - 0.5) * d
    a1, a2 = base.center_distance * math.sin(a0) + axial, base.center_distance * math.cos(a0)

    def equations(u):
        x1, x2, di, do = u
        ri, ro = rho_i + di, rho_o + do
        qi, qo = kc * max(di, 0.0) ** 1.5, kc * max(do, 0.0) ** 1.5
        return [((a1 - x1) ** 2 + (a2 - x2) ** 2 - ri**2) / rho_i**2,
                (x1**2 + x2**2 - ro**2) / rho_o**2,
                (qo * x1 / ro - qi * (a1 - x1) / ri) / fc,
                (qo * x2 / ro - qi * (a2 - x2) / ri - fc) / fc]

    alpha = math.atan2(a1, a2)
    half = 0.5 * (math.hypot(a1, a2) - base.center_distance)
    guess = [(rho_o + half) * math.sin(alpha), (rho_o + half) * math.cos(alpha), half, half]
    x1, x2, di, do = fsolve(equations, guess, xtol=1e-13)
    assert np.abs(equations([x1, x2, di, do])).max() < 1e-10
    st = model.state([[0.0, 0.0, axial, 0.0, 0.0]], base.element_angles(), speed=SPEED)
    q_i, q_o = kc * di**1.5, kc * do**1.5
    # both solve the same equations, fsolve to ~1e-13, the model's Newton to 1e-10 of the
    # largest load (measured: 1e-14 .. 5e-11)
    assert np.allclose(st.element_load, q_i, rtol=1e-9)
    assert np.allclose(st.outer_load, q_o, rtol=1e-9)
    assert np.allclose(st.contact_angle, math.atan2(a1 - x1, a2 - x2), rtol=0.0, atol=1e-9)
    assert np.allclose(st.outer_contact_angle, math.atan2(x1, x2), rtol=0.0, atol=1e-9)
    assert st.force[0, 2] == pytest.approx(base.n_balls * q_i * (a1 - x1) / (rho_i + di),
                                           rel=1e-9)
    # high-speed kinematics: the outer contact angle opens less than the inner one
    assert math.atan2(x1, x2) < math.atan2(a1 - x1, a2 - x2)


def test_high_speed_softening_at_constant_load():
    """At a constant load the inner-ring load zone shrinks with speed: an angular-contact
    bearing under thrust loses axial stiffness (its outer contact angle falls), a radially
    loaded cylindrical roller bearing deflects more (secant stiffness F/x falls) with fewer
    rollers on the inner ring, the most loaded one carrying more."""
    ball = CentrifugalBearing(dataclass_copy(BASES["angular_25deg"], cage="fixed"),
                              element_density=STEEL)
    k_axial, outer_angle = [], []
    for rpm in (0.0, 10000.0, 20000.0, 30000.0):
        eq = bearing_equilibrium(ball.at_speed(rpm * RPM), [0.0, 0.0, 1000.0, 0.0, 0.0])
        st = ball.state(eq.displacement[None], ball.element_angles(), speed=rpm * RPM)
        k_axial.append(eq.stiffness[2, 2])
        outer_angle.append(st.outer_contact_angle[0, 0])
    assert np.all(np.diff(k_axial) < 0.0) and k_axial[-1] < 0.75 * k_axial[0]
    assert np.all(np.diff(outer_angle) < 0.0)
    roller = CentrifugalBearing(RollerBearing(**ROLLER, cage="fixed", psi0=0.1),
                                element_density=STEEL)
    zone, secant, q_max = [], [], []
    for rpm in (0.0, 15000.0, 30000.0, 45000.0):
        eq = bearing_equilibrium(roller.at_speed(rpm * RPM), [200.0, 0.0, 0.0, 0.0, 0.0])
        st = roller.state(eq.displacement[None], roller.element_angles(), speed=rpm * RPM)
        zone.append(int(st.loaded.sum()))
        secant.append(200.0 / eq.displacement[0])
        q_max.append(st.element_load.max())
    assert zone == [7, 6, 5, 4]  # the rollers at the edge of the zone ride, one by one
    assert np.all(np.diff(secant) < 0.0) and secant[-1] < 0.5 * secant[0]
    assert np.all(np.diff(q_max) > 0.0)


def test_warm_start_reduces_the_iterations():
    for name in ("angular_25deg", "tapered_crowned_slices"):
        model = _model(name)
        delta, psi = _states(model, 50, seed=5)
        first = model.state(delta, psi, speed=SPEED)
        moved = delta * (1.0 + 1e-3)
        cold = model.state(moved, psi, speed=1.001 * SPEED)
        warm = model.state(moved, psi, speed=1.001 * SPEED, internal=first.internal)
        assert first.iterations >= 3 and warm.iterations < cold.iterations
        assert np.allclose(warm.force, cold.force, rtol=0.0,
                           atol=1e-9 * np.abs(cold.force).max())
        again = model.state(delta, psi, speed=SPEED, internal=first.internal)
        assert again.iterations <= 1


def test_element_passes_the_speed_and_returns_the_element_positions():
    model = _model("angular_25deg")
    element = RollingBearing(model, n=0, n_link=3)
    rng = np.random.default_rng(7)
    u = np.zeros((8, 12))
    u[:, :5] = rng.normal(size=(8, 5)) * SCALE
    u[:, 2] += 6e-6
    v, phi, speed = np.zeros_like(u), rng.uniform(0.0, 6.0, 8), np.full(8, SPEED)
    out = element.force(u, v, phi, speed)
    assert out.internal.shape == (8, 12, 2)
    st = model.state(u[:, :5] - u[:, 6:11], model.element_angles(phi), speed=speed)
    assert np.allclose(out.f[:, :5], st.force, rtol=1e-12, atol=1e-9)
    again = element.force(u, v, phi, speed, internal=out.internal)
    assert np.allclose(again.f, out.f, rtol=0.0, atol=1e-9 * np.abs(out.f).max())
    size = np.tile(np.append(SCALE, 1.0), 2)
    size[5::6] = 1e-6
    fd = np.empty_like(out.K)
    for j in range(12):
        e = np.zeros(12)
        e[j] = 1e-6 * size[j]
        fd[:, :, j] = (element.force(u + e, v, phi, speed).f
                       - element.force(u - e, v, phi, speed).f) / (2e-6 * size[j])
    scaled = (out.K - fd) * size[None, :, None] * size[None, None, :]
    ref = np.abs(out.K * size[None, :, None] * size[None, None, :]).max()
    assert np.abs(scaled).max() <= 1e-6 * ref
    lin = linearize_at_load(element, [300.0, 0.0, 800.0, 0.0, 0.0], speed=SPEED)
    eq = bearing_equilibrium(model.at_speed(SPEED), [300.0, 0.0, 800.0, 0.0, 0.0])
    assert np.allclose(lin.stiffness_matrix, eq.stiffness, rtol=1e-12)
    assert not np.allclose(lin.stiffness_matrix, linearize_at_load(
        element, [300.0, 0.0, 800.0, 0.0, 0.0]).stiffness_matrix, rtol=1e-3)


@pytest.mark.parametrize("name", ["deep_groove", "tapered_crowned_slices"])
def test_rotation_invariance_at_speed(name):
    model = _model(name)
    delta, psi = _states(model, 10, seed=3)
    theta = 0.7
    rot = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
    turned = delta.copy()
    turned[:, 0:2] = delta[:, 0:2] @ rot.T
    turned[:, 3:5] = delta[:, 3:5] @ rot.T
    a, b = model.state(delta, psi, SPEED), model.state(turned, psi + theta, SPEED)
    scale = np.abs(a.force).max()
    assert np.allclose(b.force[:, 0:2], a.force[:, 0:2] @ rot.T, rtol=0.0, atol=1e-9 * scale)
    assert np.allclose(b.force[:, 3:5], a.force[:, 3:5] @ rot.T, rtol=0.0, atol=1e-9 * scale)
    assert np.allclose(b.element_load, a.element_load, rtol=0.0, atol=1e-9 * scale)


def test_reversed_bearing_is_mirrored_at_speed():
    base = BASES["tapered_crowned_slices"]
    mirror = np.array([1.0, 1.0, -1.0, -1.0, -1.0])
    plain = CentrifugalBearing(base, element_density=STEEL)
    turned = CentrifugalBearing(ReversedBearing(base), element_density=STEEL)
    delta, psi = _states(plain, 6, seed=4)
    a, b = plain.state(delta * mirror, psi, SPEED), turned.state(delta, psi, SPEED)
    assert np.array_equal(b.force, a.force * mirror)
    assert np.array_equal(b.stiffness, a.stiffness * np.outer(mirror, mirror))
    with pytest.raises(ModelError, match="other way round"):
        RollingBearing(ReversedBearing(plain), n=0)


def test_mass_cage_ratio_and_centrifugal_force():
    ball = BASES["deep_groove"]
    model = CentrifugalBearing(ball, element_density=STEEL)
    assert model.mass == pytest.approx(STEEL * math.pi * ball.ball_diameter**3 / 6.0)
    kappa = cage_ratio(ball.ball_diameter, ball.pitch_diameter, 0.0)
    assert model.centrifugal_cage_ratio == pytest.approx(kappa)
    assert model.centrifugal_force(1000.0) == pytest.approx(
        model.mass * 0.5 * ball.pitch_diameter * (kappa * 1000.0) ** 2)
    fixed = CentrifugalBearing(dataclass_copy(ball, cage="fixed"), element_mass=0.004)
    assert fixed.centrifugal_cage_ratio == pytest.approx(kappa)  # kinematic, not frozen
    roller = CentrifugalBearing(BASES["cylindrical_tilt"], element_density=STEEL,
                                cage_ratio=0.5)
    assert roller.mass == pytest.approx(STEEL * math.pi * 7.5e-3**2 / 4.0 * 7.5e-3)
    assert roller.centrifugal_cage_ratio == 0.5 and roller.kappa == BASES[
        "cylindrical_tilt"].kappa  # other attributes are the wrapped model's
    thrust = CentrifugalBearing(RollerBearing(**ROLLER, contact_angle=0.5 * math.pi),
                                element_mass=0.003)
    d = np.array([[0.0, 0.0, 5e-6, 0.0, 0.0]])
    assert np.array_equal(thrust.state(d, thrust.element_angles(), SPEED).force,
                          thrust.bearing.state(d, thrust.element_angles()).force)


@pytest.mark.parametrize(("kwargs", "match"), [
    (dict(), "exactly one of element_mass"),
    (dict(element_mass=0.01, element_density=STEEL), "exactly one of element_mass"),
    (dict(element_mass=-1.0), "element_mass must be a positive"),
    (dict(element_density=float("nan")), "element_density must be a positive"),
    (dict(element_mass=0.01, cage_ratio=float("inf")), "cage_ratio must be a finite"),
    (dict(element_mass=0.01, tol=0.0), "tol must be in"),
    (dict(element_mass=0.01, max_iter=0), "max_iter must be an integer"),
])
def test_bad_input(kwargs, match):
    with pytest.raises(ModelError, match=match):
        CentrifugalBearing(BASES["deep_groove"], **kwargs)


def test_bad_models_states_and_combinations():
    with pytest.raises(ModelError, match="BallBearing or RollerBearing"):
        CentrifugalBearing(object(), element_mass=0.01)
    model = _model("deep_groove")
    psi = model.element_angles([0.0, 1.0])
    with pytest.raises(ModelError, match="internal must have shape"):
        model.state(np.zeros((2, 5)), psi, SPEED, internal=np.zeros((1, 9, 2)))
    with pytest.raises(ModelError, match="speed must be finite"):
        model.state(np.zeros((2, 5)), psi, speed=[1.0, np.nan])
    with pytest.raises(ModelError, match="delta must have shape"):
        model.state(np.zeros((2, 4)), psi, SPEED)
    from rotorsim.elements.rolling.lubrication import Lubricant

    with pytest.raises(ModelError, match="not implemented with the centrifugal"):
        RollingBearing(model, n=0, contact_damping="ehl",
                       lubricant=Lubricant(eta0=0.01, alpha=2e-8))
    with pytest.raises(AttributeError, match="ignores the centrifugal force"):
        _ = _model("cylindrical_tilt").roller_loads
