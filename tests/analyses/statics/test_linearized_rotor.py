"""Rotors on rolling bearings linearised at their static loads: the static equilibrium is the
nonlinear one, the loads follow statics, the stiffness is the bearing's tangent, and the
critical speeds respond to load and preload as Hertz contact says."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.analyses.linear.modal import modal
from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium
from rotorsim.analyses.statics.linearized_rotor import (
    LinearizationPoint,
    linearize_rolling_bearings,
)
from rotorsim.assembly.loads import STANDARD_GRAVITY, gravity_load
from rotorsim.assembly.system import assemble
from rotorsim.elements.disk import DiskElement
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

STEEL = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
SCALE = np.array([1.0, 1.0, 1.0, 1.0 / 0.02, 1.0 / 0.02])  # moments over ~ the pitch radius


def ball(clearance: float = 5e-6) -> BallBearing:
    """6205-like deep-groove bearing (9 balls, 7.94 mm, f = 0.52, Kn of Hertz theory)."""
    return BallBearing(n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794, Kn=9.3e9,
                       f_i=0.52, f_o=0.52, radial_clearance=clearance)


def disk_rotor(n: int = 10) -> Rotor:
    """0.5 m, 25 mm shaft with a 200 mm disk in the middle, symmetric about z = 0.25 m."""
    shaft = [ShaftElement(L=0.5 / n, idl=0.0, odl=0.025, material=STEEL) for _ in range(n)]
    return Rotor(shaft, [DiskElement.from_geometry(n // 2, STEEL, 0.03, 0.025, 0.2)])


def pair(bearing, n: int = 10) -> list[RollingBearing]:
    return [RollingBearing(bearing, n=0, tag="A"), RollingBearing(bearing, n=n, tag="B")]


@pytest.fixture(scope="module")
def symmetric():
    rotor = disk_rotor()
    return rotor, linearize_rolling_bearings(rotor, pair(ball()))


def test_symmetric_rotor_puts_half_its_weight_on_each_bearing(symmetric):
    rotor, lin = symmetric
    half = STANDARD_GRAVITY * rotor.m / 2
    # the loads are F(d) at the converged displacement; the rotor balances the tangent
    # forces P exactly, and |F - P| <= tol |F| (tol = 1e-6, the convergence criterion)
    np.testing.assert_allclose(lin.loads[:, 1], -half, rtol=1e-6)
    assert np.abs(lin.loads[:, 0]).max() < 1e-6 * half
    # mirror symmetry about midspan: equal and opposite axial loads and moments Mx
    np.testing.assert_allclose(lin.loads[0, [2, 3]], -lin.loads[1, [2, 3]], rtol=1e-6)
    assert lin.iterations <= 8 and lin.residual <= 1e-6
    assert [b.n for b in lin.rotor.bearing_elements] == [0, 10]


def test_linearised_stiffness_is_the_bearing_stiffness_at_that_load(symmetric):
    _, lin = symmetric
    for element, load in zip(lin.bearings, lin.loads, strict=True):
        # an independent equilibrium solve from the default start (tol 1e-10)
        k = bearing_equilibrium(ball(), load).stiffness
        scaled = (element.stiffness_matrix - k) * np.outer(1 / SCALE, 1 / SCALE)
        assert np.abs(scaled).max() <= 1e-7 * np.abs(k).max()
        assert element.damping_matrix is None


def test_static_result_is_the_nonlinear_equilibrium(symmetric):
    """Independent residual: K_s q + r(q) - f with the element's own force (DESIGN 3)."""
    rotor, lin = symmetric
    q = lin.static.displacement
    system = assemble(rotor)
    K = system.matrices(0.0).K
    f = gravity_load(system, STANDARD_GRAVITY, (0.0, -1.0, 0.0))
    r = K @ q[system.dof_map.free] - f
    for rb in pair(ball()):
        dofs = np.concatenate([np.arange(6 * n, 6 * n + 6) for n in rb.nodes])
        force = rb.force(q[dofs][None, :], np.zeros((1, dofs.size)), 0.0, 0.0).f[0]
        np.add.at(r, system.dof_map.full_to_free[dofs], force)
    # 1e-6 relative: the convergence criterion on the bearing forces (the rotor part is
    # solved to round-off); rz of node 0 is held (free torsion) and carries no load
    assert np.abs(r).max() <= 1e-6 * np.abs(f).max()
    # the reactions reported are the bearings' forces on the shaft and balance the weight
    np.testing.assert_allclose(lin.static.bearing_forces.sum(axis=0),
                               [0.0, STANDARD_GRAVITY * rotor.m, 0.0], atol=1e-6 * rotor.m)
    np.testing.assert_allclose(lin.static.bearing_forces, -lin.loads[:, :3], rtol=0,
                               atol=1e-6 * np.abs(lin.loads).max())
    assert lin.static.load.reshape(-1, 6)[:, 1].sum() == pytest.approx(
        -STANDARD_GRAVITY * rotor.m, rel=1e-12)


def test_lever_rule_for_an_off_centre_load():
    """Two supports: the radial loads follow statics, whatever the bearing stiffness; the
    small bearing moments (tilt stiffness) enter the moment balance."""
    rotor, load = disk_rotor(), 1500.0
    lin = linearize_rolling_bearings(rotor, pair(ball()), gravity=None,
                                     loads=[(2, "ux", load)])  # node 2 at z = 0.1 m
    fx = lin.loads[:, 0]
    assert fx.sum() == pytest.approx(load, rel=1e-6)
    # moments about the y axis through z = 0 (M_y = z F_x): the shaft gets -F and -M from
    # each bearing (the load on an inner ring is what the shaft applies to it)
    moment = 0.5 * fx[1] + lin.loads[:, 4].sum()
    assert moment == pytest.approx(0.1 * load, rel=1e-6)
    assert fx[0] == pytest.approx(0.8 * load, rel=2e-2)  # moments are < 2 % here


def test_critical_speed_rises_with_radial_load_and_with_preload():
    rotor = disk_rotor()

    def lowest_lateral(bearing, point_load=0.0):
        lin = linearize_rolling_bearings(rotor, pair(bearing),
                                         loads=[(5, "uy", -point_load)] if point_load else ())
        m = modal(lin.rotor, speed=0.0, num_modes=6)
        return float(m.wn[np.asarray(m.kind) == "lateral"][0]), lin

    by_load = [lowest_lateral(ball(), p)[0] for p in (0.0, 500.0, 2000.0)]
    by_preload = [lowest_lateral(ball(c)) for c in (5e-6, 0.0, -2e-6, -5e-6)]
    assert np.all(np.diff(by_load) > 0), by_load
    assert np.all(np.diff([w for w, _ in by_preload]) > 0), by_preload
    # Hertz: the contact stiffness grows with preload; measured kyy 3.4e7 -> 1.4e8 N/m
    kyy = [lin.bearings[0].stiffness_matrix[1, 1] for _, lin in by_preload]
    assert np.all(np.diff(kyy) > 0) and kyy[-1] > 3 * kyy[0]


@pytest.mark.validation
def test_preloaded_back_to_back_pair_matches_the_closed_form():
    """No external load: two tapered bearings, O arrangement, interference r_L < 0. By
    symmetry every roller of a bearing carries Q = Kn (|r_L| cos a - s sin a)^n, the bearing
    F_z = Z Q sin a, where s is how far the shaft end moved out; the shaft carries F_z in
    tension, F_z = (EA/L) 2 s (closed forms of the rigid-ring model, seed 000 eqs 6-7)."""
    alpha, clearance, n = math.radians(14.0), -2e-6, 6
    roller = RollerBearing(17, 0.046, 0.0075, 0.012, contact_angle=alpha,
                           radial_clearance=clearance)
    shaft = [ShaftElement(L=0.05, idl=0.0, odl=0.03, material=STEEL) for _ in range(n)]
    rolling = [RollingBearing(roller, n=0), RollingBearing(ReversedBearing(roller), n=n)]
    lin = linearize_rolling_bearings(Rotor(shaft), rolling, gravity=None)
    uz = lin.static.deflection("uz")
    s = 0.5 * (uz[n] - uz[0])
    fz = lin.loads[0, 2]
    q = roller.kn * (abs(clearance) * math.cos(alpha) - s * math.sin(alpha)) ** roller.exponent
    assert fz == pytest.approx(17 * q * math.sin(alpha), rel=1e-9)
    axial = STEEL.E * math.pi * 0.03**2 / 4 / 0.3
    assert fz == pytest.approx(axial * 2 * s, rel=1e-6)  # residual tol 1e-6 on the loads
    assert lin.loads[1, 2] == pytest.approx(-fz, rel=1e-9)
    assert s > 0 and fz > 1000.0  # ~1.5 kN of preload
    np.testing.assert_allclose(lin.loads[:, [0, 1, 3, 4]], 0.0, atol=1e-9 * fz)


def test_reversed_bearing_is_the_mirror_image():
    base = RollerBearing(14, 0.0425, 0.0075, 0.01, Kn=3.0e8, contact_angle=0.3,
                         model="slices", n_slices=8)
    rev = ReversedBearing(base)
    mirror = np.array([1.0, 1.0, -1.0, -1.0, -1.0])
    rng = np.random.default_rng(0)
    d = rng.normal(size=(6, 5)) * [8e-6, 8e-6, 8e-6, 3e-4, 3e-4]
    d[:, 2] -= 10e-6  # towards the reversed bearing's rings
    psi = base.element_angles()
    a, b = rev.state(d, psi), base.state(d * mirror, psi)
    np.testing.assert_array_equal(a.force, b.force * mirror)
    np.testing.assert_array_equal(a.stiffness, b.stiffness * np.outer(mirror, mirror))
    np.testing.assert_array_equal(rev.energy(d, psi), base.energy(d * mirror, psi))
    if getattr(a, "contact_direction", None) is not None:  # unit-load directions: F = sum Q g
        np.testing.assert_allclose(np.einsum("sn,snk->sk", a.element_load,
                                             a.contact_direction), a.force,
                                   rtol=1e-10, atol=1e-10 * np.abs(a.force).max())
    # equilibrium under a thrust towards -z mirrors the base under +z
    e1 = bearing_equilibrium(rev, [500.0, 0.0, -3000.0, 0.0, 4.0])
    e0 = bearing_equilibrium(base, [500.0, 0.0, 3000.0, 0.0, -4.0])
    np.testing.assert_allclose(e1.displacement, e0.displacement * mirror, rtol=1e-9,
                               atol=1e-15)
    assert rev.n_elements == 14 and rev.clearance == base.clearance
    with pytest.raises(AttributeError, match="not mirrored"):
        rev.roller_loads  # noqa: B018


def test_given_load_and_displacement_points():
    rotor = disk_rotor()
    load = (0.0, -800.0, 50.0, 0.0, 0.0)
    eq = bearing_equilibrium(ball(), load)
    points = [LinearizationPoint("load", load), LinearizationPoint("displacement",
                                                                   eq.displacement)]
    lin = linearize_rolling_bearings(rotor, pair(ball()), points=points)
    assert lin.iterations == 0
    for element, equilibrium in zip(lin.bearings, lin.equilibria, strict=True):
        np.testing.assert_allclose(equilibrium.load, load, rtol=1e-8, atol=1e-8)
        np.testing.assert_allclose(element.stiffness_matrix, eq.stiffness, rtol=1e-6,
                                   atol=1e-6 * np.abs(eq.stiffness).max())


def test_errors():
    rotor = disk_rotor()
    with pytest.raises(ModelError, match="carries no load"):
        linearize_rolling_bearings(rotor, pair(ball()), gravity=None)
    with pytest.raises(ModelError, match="one LinearizationPoint per rolling bearing"):
        linearize_rolling_bearings(rotor, pair(ball()), points=[LinearizationPoint()])
    with pytest.raises(ModelError, match="kind must be one of"):
        LinearizationPoint("preload")
    with pytest.raises(ModelError, match="5 finite numbers"):
        LinearizationPoint("load", (1.0, 2.0))
    with pytest.raises(ConvergenceError, match="did not converge"):
        linearize_rolling_bearings(rotor, pair(ball()), max_iter=1)
    # a thrust that only a reversed tapered bearing could carry
    roller = RollerBearing(17, 0.046, 0.0075, 0.012, contact_angle=0.25)
    shaft = [ShaftElement(L=0.05, idl=0.0, odl=0.03, material=STEEL) for _ in range(4)]
    with pytest.raises(ModelError, match="rolling bearing 'A'"):
        linearize_rolling_bearings(Rotor(shaft), pair(roller, 4), loads=[(2, "uz", -500.0)])
    with pytest.raises(ModelError, match="Rotor"):
        linearize_rolling_bearings(assemble(rotor), pair(ball()))  # type: ignore[arg-type]
    # issue 12: speed and phi went unchecked (NaN reached the Newton iteration)
    for speed in (-100.0, float("nan")):
        with pytest.raises(ModelError, match="linearize_rolling_bearings: speed must be"):
            linearize_rolling_bearings(rotor, pair(ball()), speed=speed)
    with pytest.raises(ModelError, match="phi must be a finite angle"):
        linearize_rolling_bearings(rotor, pair(ball()), phi=float("inf"))


def test_load_on_the_housing_node_side():
    """Node-to-node bearing: the outer ring on a housing node on a linear support; the
    housing carries the same load back to ground."""
    from rotorsim.elements.disk import PointMass
    from rotorsim.elements.linear_bearing import BearingElement

    base = disk_rotor()
    housing = base.n_nodes
    rotor = Rotor(base.shaft_elements, base.disk_elements,
                  [BearingElement(n=housing, kxx=5e8, kzz=5e8, krr=1e6)],
                  [PointMass(n=housing, m=2.0)], fixed=[(housing, "rz")])
    rolling = [RollingBearing(ball(), n=0, n_link=housing, tag="A"),
               RollingBearing(ball(), n=10, tag="B")]
    lin = linearize_rolling_bearings(rotor, rolling)
    weight = STANDARD_GRAVITY * base.m
    # bearing A carries about half the rotor's weight; its housing adds its own weight to
    # the ground support
    assert lin.loads[:, 1].sum() == pytest.approx(-weight, rel=1e-6)
    ground = lin.static.bearing_forces[0]  # the linear support under the housing
    assert ground[1] == pytest.approx(-lin.loads[0, 1] + 2.0 * STANDARD_GRAVITY, rel=1e-6)
