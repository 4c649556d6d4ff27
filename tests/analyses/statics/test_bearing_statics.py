"""Bearing statics: methods agree, degenerate DOFs, errors, load zone, element-pass variation,
and a non-convex case whose every minimum the global search must find."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorsim.analyses.statics.bearing_statics import (
    bearing_equilibrium,
    linearize_at_load,
    linearized_bearings,
    stiffness_over_pass,
)
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.errors import ModelError

# seed 000 Table 1 (see examples/seed000_load_cases.py for the interpretation)
BALL = dict(n_balls=12, pitch_diameter=39.3e-3, ball_diameter=7.9e-3, Kn=8.5e9, A0=0.05e-3,
            radial_clearance=5e-8, groove_center_radius=19.65e-3, cage="fixed")
ROLLER = dict(n_rollers=14, pitch_diameter=42.5e-3, roller_diameter=7.5e-3,
              effective_length=10e-3, Kn=3.0e8, radial_clearance=1.75e-6, cage="fixed")
CASES = {  # seed 000 load cases (i)-(vi): bearing, [Fx, Fy, Fz, Mx, My], angles [deg]
    "i": ("ball", [0, 0, 3000, 0, 0], [0, 20, 45, 70, 90]),
    "ii": ("ball", [1000, 0, 3000, 0, 5.0], [0, 20, 45, 70, 90]),
    "iii": ("ball", [0, 0, 5000, 3.0, 10.0], [0, 20, 45, 70, 90]),
    "iv": ("roller", [0, 0, 10000, 0, 0], [10, 30, 60, 90]),
    "v": ("roller", [3000, 0, 10000, 0, 10.0], [10, 20, 30]),
    "vi": ("roller", [5000, 0, 0, 5.0, 10.0], [0]),
}


def _bearing(kind: str, alpha_deg: float, **extra):
    if kind == "ball":
        return BallBearing(**{**BALL, **extra}, contact_angle=math.radians(alpha_deg))
    return RollerBearing(**{**ROLLER, **extra}, contact_angle=math.radians(alpha_deg))


def _scaled(delta, arm):
    return np.asarray(delta) * np.array([1.0, 1.0, 1.0, arm, arm])


@pytest.mark.parametrize("case", CASES)
def test_newton_energy_and_global_agree_on_seed_cases(case):
    kind, load, angles = CASES[case]
    for alpha in angles:
        bearing = _bearing(kind, alpha)
        arm = 19.65e-3 if kind == "ball" else 21.25e-3
        results = {m: bearing_equilibrium(bearing, load, method=m)
                   for m in ("newton", "energy", "global")}
        ref = _scaled(results["newton"].displacement, arm)
        for method, res in results.items():
            assert res.residual <= 1e-10, (case, alpha, method)
            free = [i for i, d in enumerate("x y z rx ry".split()) if d not in res.held_dofs]
            assert np.allclose(res.force[free], np.asarray(load, float)[free], rtol=0,
                               atol=1e-9 * np.abs(load).max())
            # tol 1e-10 on the force; the scaled tangent is >= 1e-3 of its largest entry
            assert np.abs(_scaled(res.displacement, arm) - ref).max() <= 1e-7 * np.abs(
                ref).max(), (case, alpha, method)
        glob = results["global"]
        assert len(glob.minima) == 1 and glob.minima[0].positive_definite  # convex energy
        # every converged start found it; the others (balls only) began beyond the groove,
        # where the far-side switch of the ball model makes the energy discontinuous
        assert glob.minima[0].hits == glob.search["converged"] >= 0.75 * 66
        assert glob.search["saddles"] == glob.search["escaped"] == 0
        if kind == "roller":
            assert glob.search["converged"] == 66


def test_strain_energy_is_convex_within_the_contact_range():
    """Midpoint convexity of U along 2000 random chords (the basis of a unique minimum)."""
    rng = np.random.default_rng(5)
    bearings = [BallBearing.from_geometry(n_balls=9, pitch_diameter=46e-3,
                                          ball_diameter=9.525e-3, f_i=0.515, f_o=0.525,
                                          contact_angle=math.radians(a),
                                          diametral_clearance=20e-6) for a in (0, 25, 90)]
    bearings += [_bearing("roller", a, model=m) for a in (0, 20) for m in ("tilt_integral",
                                                                           "slices")]
    scale = np.array([40e-6, 40e-6, 40e-6, 2e-3, 2e-3])
    for bearing in bearings:
        a, b = (rng.uniform(-1, 1, (2000, 5)) * scale for _ in range(2))
        psi = bearing.element_angles(0.0)
        mid = bearing.energy(0.5 * (a + b), psi)
        chord = 0.5 * (bearing.energy(a, psi) + bearing.energy(b, psi))
        assert np.all(mid <= chord * (1 + 1e-12) + 1e-18)


def _thrust(alpha, cos0, fa):
    """Closed-form thrust of the Table 1 ball bearing at the loaded contact angle ``alpha``
    minus ``fa``; ``cos0 = A0 cos(alpha0) - r_L`` over ``A0``."""
    a0, kn, z_count = 0.05e-3, 8.5e9, 12
    return z_count * kn * max(a0 * cos0 / math.cos(alpha) - a0, 0.0) ** 1.5 * math.sin(
        alpha) - fa


def test_pure_axial_load_matches_closed_form():
    """All balls carry Fa / (Z sin a) at the loaded angle of
    Fa = Z Kn (A0 (cos a0 / cos a - 1))^1.5 sin a (Harris & Kotzalas, pure thrust)."""
    a0 = 0.05e-3
    for alpha0 in (0.0, 25.0, 60.0):
        bearing = _bearing("ball", alpha0)
        cos0 = math.cos(math.radians(alpha0)) - 5e-8 / a0  # clearance reduces A0 cos a0
        for fa in (300.0, 3000.0, 20000.0):
            alpha = brentq(_thrust, 1e-9, 1.5, args=(cos0, fa), xtol=1e-15)
            res = bearing_equilibrium(bearing, [0, 0, fa, 0, 0])
            assert np.allclose(res.element_load, fa / (12 * math.sin(alpha)), rtol=1e-9)
            assert np.allclose(res.contact_angle, alpha, rtol=1e-9)
            z = a0 * cos0 * math.tan(alpha) - a0 * math.sin(math.radians(alpha0))
            assert res.displacement[2] == pytest.approx(z, rel=1e-9)
            assert res.load_zone.size == 12 and res.load_zone_extent == pytest.approx(
                2 * math.pi)


@pytest.mark.parametrize(("kind", "alpha", "held"), [
    ("roller", 0.0, ("z",)), ("roller", 90.0, ("x", "y")), ("roller", 30.0, ()),
    ("ball", 0.0, ()), ("ball", 90.0, ())])
def test_held_dofs_follow_the_model_stiffness(kind, alpha, held):
    load = {("roller", 0.0): [3000, 0, 0, 0, 2.0], ("roller", 90.0): [0, 0, 5000, 1.0, 0]}.get(
        (kind, alpha), [500, 0, 3000, 0, 0])
    res = bearing_equilibrium(_bearing(kind, alpha), load)
    assert res.held_dofs == held and len(res.hold_reasons) == len(held)
    for name, reason in zip(res.held_dofs, res.hold_reasons, strict=True):
        assert name in reason and "held at 0" in reason
        assert res.displacement["x y z rx ry".split().index(name)] == 0.0
    if held:
        assert ("axial" if held == ("z",) else "radial") in res.hold_reasons[0]


@pytest.mark.parametrize("method", ["newton", "energy", "global"])
def test_loads_that_cannot_be_carried_raise_specific_errors(method):
    with pytest.raises(ModelError, match="cannot carry the load component Fz"):
        bearing_equilibrium(_bearing("roller", 0.0), [1000, 0, 10, 0, 0], method=method)
    with pytest.raises(ModelError, match=r"cannot carry the load component Fx.*radial"):
        bearing_equilibrium(_bearing("roller", 90.0), [10, 0, 1000, 0, 0], method=method)
    # clearance larger than A0: the grooves of a deep-groove bearing no longer hold an axial
    # load (the balls lose contact)
    loose = _bearing("ball", 0.0, radial_clearance=0.06e-3)
    with pytest.raises(ModelError, match=r"no equilibrium.*clearance 6e-05"):
        bearing_equilibrium(loose, [0, 0, 1000, 0, 0], method=method)
    # thrust ball bearing pulled apart, tapered roller bearing with reversed thrust
    with pytest.raises(ModelError, match="no equilibrium"):
        bearing_equilibrium(_bearing("ball", 90.0), [0, 0, -1000, 0, 0], method=method)
    with pytest.raises(ModelError, match="no equilibrium"):
        bearing_equilibrium(_bearing("roller", 20.0), [0, 0, -1000, 0, 0], method=method)
    # seed 000 case (v) at 40 deg: x = 2.29 mm, "impractical" (outside the physical range)
    with pytest.raises(ModelError, match="physical range"):
        bearing_equilibrium(_bearing("roller", 40.0), CASES["v"][1], method=method)


def test_bad_input():
    b = _bearing("ball", 20.0)
    with pytest.raises(ModelError, match="load must be 5"):
        bearing_equilibrium(b, [1.0, 2.0])
    with pytest.raises(ModelError, match="load must be 5"):
        bearing_equilibrium(b, [0, 0, math.nan, 0, 0])
    with pytest.raises(TypeError, match="newton"):
        bearing_equilibrium(b, [0, 0, 1, 0, 0], method="bisection")
    with pytest.raises(ModelError, match="tol"):
        bearing_equilibrium(b, [0, 0, 1, 0, 0], tol=-1.0)
    with pytest.raises(ModelError, match="phi"):
        bearing_equilibrium(b, [0, 0, 1, 0, 0], phi=math.inf)
    with pytest.raises(ModelError, match="symmetric"):
        bearing_equilibrium(b, [0, 0, 1, 0, 0], load_stiffness=np.triu(np.ones((5, 5))))
    with pytest.raises(ModelError, match="max_displacement"):
        bearing_equilibrium(b, [0, 0, 1, 0, 0], max_displacement=0.0)
    with pytest.raises(ModelError, match="x0"):
        bearing_equilibrium(b, [0, 0, 1, 0, 0], x0=[0, 0, math.nan, 0, 0])
    with pytest.raises(ModelError):
        linearized_bearings([], [[0, 0, 1, 0, 0]])


def test_linearize_at_load_is_the_element_at_the_equilibrium():
    """The analysis solves the equilibrium (options passed on) and the element evaluates
    the state found: the same matrices as linearising the element at that displacement."""
    b = _bearing("ball", 20.0)
    element = RollingBearing(b, n=0, contact_damping="proportional", damping_factor=2e-5)
    load = [400.0, -100.0, 3000.0, 0.0, 2.0]
    lin = linearize_at_load(element, load, phi=0.2, method="energy")
    eq = bearing_equilibrium(b, load, phi=0.2, method="energy")
    assert np.array_equal(lin.stiffness_matrix, eq.stiffness)
    assert np.array_equal(lin.damping_matrix, 2e-5 * eq.stiffness)
    at = element.linearize(displacement=eq.displacement, phi=0.2)
    assert np.allclose(at.stiffness_matrix, lin.stiffness_matrix, rtol=1e-13, atol=0.0)
    with pytest.raises(TypeError, match="bearing_equilibrium: unknown keyword 'tolerance'"):
        linearize_at_load(element, load, tolerance=1e-8)
    with pytest.raises(TypeError, match=r"expected a 2-node rolling-bearing element .* "
                                        r"got BallBearing; a bare bearing model goes to "
                                        r"bearing_equilibrium"):
        linearize_at_load(b, load)


def test_zero_load():
    res = bearing_equilibrium(_bearing("ball", 20.0), np.zeros(5))
    assert np.all(res.displacement == 0) and res.load_zone.size == 0
    assert any("no rolling element is loaded" in n for n in res.notes)
    preloaded = bearing_equilibrium(_bearing("ball", 0.0, radial_clearance=-2e-6), np.zeros(5))
    assert np.abs(preloaded.displacement).max() < 1e-15 and preloaded.load_zone.size == 12
    assert preloaded.notes == () and np.all(np.linalg.eigvalsh(preloaded.stiffness[:3, :3]) > 0)
    # a single preloaded tapered bearing pushes its inner ring out until the rollers just
    # touch: V = cos a0 (-r_L) + sin a0 z = 0
    tapered = bearing_equilibrium(_bearing("roller", 20.0, radial_clearance=-2e-6), np.zeros(5))
    assert tapered.displacement[2] == pytest.approx(-2e-6 / math.tan(math.radians(20)),
                                                    rel=1e-6)


def test_random_loads_give_finite_results():
    """Never a NaN: 40 random combined loads on a 25 deg angular-contact bearing."""
    rng = np.random.default_rng(11)
    bearing = _bearing("ball", 25.0)
    for _ in range(40):
        load = np.concatenate([rng.uniform(-2000, 2000, 2), rng.uniform(100, 6000, 1),
                               rng.uniform(-8, 8, 2)])
        res = bearing_equilibrium(bearing, load)
        fields = (res.displacement, res.stiffness, res.element_load, res.contact_angle)
        assert all(np.all(np.isfinite(f)) for f in fields) and res.residual <= 1e-10


def test_radial_load_zone_of_a_deep_groove_bearing():
    """Zero clearance: balls within +-90 deg of the load carry it (psi = 0, +-30, +-60)."""
    bearing = _bearing("ball", 0.0, radial_clearance=0.0)
    res = bearing_equilibrium(bearing, [1200.0, 0, 0, 0, 0])
    assert sorted(res.load_zone.tolist()) == [0, 1, 2, 10, 11]
    assert res.load_zone_extent == pytest.approx(math.radians(150))
    # Stribeck: Qmax = 4.3645 Fr / Z for 12 balls (tests/elements/rolling/ball/test_ball.py)
    assert res.max_element_load * 12 / 1200 == pytest.approx(4.3645, abs=2e-4)
    assert res.displacement[2] == pytest.approx(0.0, abs=1e-15)
    assert "loaded elements 5/12" in res.table()


def test_stiffness_over_pass_matches_shifted_bearings():
    bearing = _bearing("roller", 0.0)
    load = CASES["vi"][1]
    var = stiffness_over_pass(bearing, load, n_points=6)
    assert var.held_dofs == ("z",) and np.all(np.isnan(var.shaft_angle))
    for k, cage in enumerate(var.cage_angle):
        shifted = dataclasses.replace(bearing, psi0=float(cage))
        ref = bearing_equilibrium(shifted, load)
        got, want = _scaled(var.displacement[k], 21.25e-3), _scaled(ref.displacement, 21.25e-3)
        assert np.abs(got - want).max() <= 1e-8 * np.abs(want).max()  # force tol 1e-10
        assert np.allclose(var.stiffness[k], ref.stiffness, rtol=1e-8,
                           atol=1e-9 * np.abs(ref.stiffness).max())
        assert np.allclose(var.force[k, [0, 1, 3, 4]], np.take(load, [0, 1, 3, 4]), rtol=0,
                           atol=1e-9 * max(load))
    # prescribed displacement: one pitch later the same state (periodicity)
    d = var.displacement[0]
    fixed = stiffness_over_pass(bearing, displacement=d, n_points=4)
    turned = dataclasses.replace(bearing, psi0=2 * math.pi / 14)
    k_turned = turned.state(d[None], turned.element_angles(0.0)).stiffness[0]
    assert np.allclose(fixed.stiffness[0], k_turned, rtol=1e-12, atol=1e-6)
    assert fixed.load is None and fixed.mean_stiffness.shape == (5, 5)
    rotating = stiffness_over_pass(dataclasses.replace(bearing, cage="rotating"),
                                   displacement=d, n_points=4)
    kappa = dataclasses.replace(bearing, cage="rotating").kappa
    assert np.allclose(rotating.shaft_angle * kappa, rotating.cage_angle)
    with pytest.raises(ModelError, match="exactly one"):
        stiffness_over_pass(bearing)
    with pytest.raises(ModelError, match="n_points"):
        stiffness_over_pass(bearing, load, n_points=0)


# ------------------------------------------------------------ a non-convex case
def _motor_bearing(n_balls: int) -> BallBearing:
    """Deep-groove bearing with 10 um radial clearance in a motor whose unbalanced magnetic
    pull acts as a negative radial stiffness of 1e8 N/m (load_stiffness)."""
    return BallBearing(n_balls=n_balls, pitch_diameter=0.04, ball_diameter=0.008, Kn=8e9,
                       f_i=0.52, f_o=0.52, radial_clearance=10e-6, cage="fixed")


PULL = np.diag([1e8, 1e8, 0.0, 0.0, 0.0])


def _polar_minima(bearing: BallBearing, n_theta: int = 720) -> np.ndarray:
    """Independent check: angles of the local minima of min_rho Pi(rho, theta) on a grid
    (z = rx = ry = 0 by the mirror symmetry of a deep-groove bearing)."""
    rho = np.linspace(0.0, 200e-6, 401)
    theta = np.linspace(0.0, 2 * math.pi, n_theta, endpoint=False)
    r, t = np.meshgrid(rho, theta, indexing="ij")
    d = np.zeros((r.size, 5))
    d[:, 0], d[:, 1] = (r * np.cos(t)).ravel(), (r * np.sin(t)).ravel()
    pot = bearing.energy(d, bearing.element_angles(0.0)) - 0.5e8 * (d[:, 0]**2 + d[:, 1]**2)
    best = pot.reshape(r.shape).min(axis=0)
    lower = (best < np.roll(best, 1)) & (best < np.roll(best, -1))
    return np.degrees(theta[lower])


def _circular_mismatch(found_deg: np.ndarray, expected_deg: np.ndarray) -> float:
    """Largest angular distance [deg], modulo 360, between each expected angle and the nearest
    found one, and back (so a missing or an extra angle shows up as a large mismatch)."""
    diff = np.abs(np.asarray(found_deg)[:, None] - np.asarray(expected_deg)[None, :]) % 360.0
    dist = np.minimum(diff, 360.0 - diff)
    return float(max(dist.min(axis=0).max(), dist.min(axis=1).max()))


@pytest.mark.parametrize(("n_balls", "offset"), [(8, 22.5), (6, 0.0)])
def test_global_search_finds_every_minimum_of_a_non_convex_case(n_balls, offset):
    bearing = _motor_bearing(n_balls)
    res = bearing_equilibrium(bearing, np.zeros(5), method="global", load_stiffness=PULL)
    angles = np.degrees([math.atan2(m.displacement[1], m.displacement[0])
                         for m in res.minima])
    assert len(res.minima) == n_balls  # one per ball pitch
    expected = offset + 360 / n_balls * np.arange(n_balls)
    # Angles are compared modulo 360 deg: a minimum at 0 deg may come out as 359.9999999
    # on one BLAS kernel and 1e-9 on another. 1e-6 deg: the minimiser's stationarity
    # tolerance resolves the direction to ~1e-9 rad.
    assert _circular_mismatch(angles, expected) < 1e-6
    assert _circular_mismatch(_polar_minima(bearing), expected) < 0.5  # grid 0.5 deg
    energies = np.array([m.energy for m in res.minima])
    assert np.ptp(energies) <= 1e-9 * np.abs(energies).max()  # symmetric copies
    for m in res.minima:
        assert m.positive_definite and m.hessian_eigenvalues.size == 5
        assert np.abs(m.displacement[2:]).max() < 1e-12  # mirror symmetry
        local = bearing_equilibrium(bearing, np.zeros(5), x0=m.displacement,
                                    load_stiffness=PULL)
        assert np.allclose(local.displacement, m.displacement, rtol=0, atol=1e-12)
    # Newton from the default start stays on the unstable centre and says so
    centre = bearing_equilibrium(bearing, np.zeros(5), load_stiffness=PULL)
    assert np.all(centre.displacement == 0) and centre.notes


def test_small_load_selects_the_minimum_nearest_its_direction():
    bearing = _motor_bearing(8)
    load = 200.0 * np.array([math.cos(math.radians(22.5)), math.sin(math.radians(22.5)),
                             0, 0, 0])
    res = bearing_equilibrium(bearing, load, method="global", load_stiffness=PULL)
    assert len(res.minima) >= 2
    first = res.minima[0].displacement
    assert math.degrees(math.atan2(first[1], first[0])) == pytest.approx(22.5, abs=1e-6)
    assert all(m.energy > res.minima[0].energy for m in res.minima[1:])
    assert np.allclose(res.displacement, first) and res.energy == pytest.approx(
        res.minima[0].energy, rel=1e-9)


def test_auto_falls_back_from_newton_and_names_the_method():
    """A deep-groove bearing with clearance under a small moment: Newton stalls (the tilt
    stiffness is tiny), the energy method converges; "auto" returns that solution and notes
    the Newton failure. A load without equilibrium still gives the specific ModelError."""
    import math

    import rotorsim as rs

    ball = rs.BallBearing(n_balls=9, pitch_diameter=38.5e-3, ball_diameter=7.94e-3, Kn=8.5e9,
                          f_i=0.52, f_o=0.52, radial_clearance=5e-6)
    load = [15.0, -35.34, 0.0, 1e-3, 0.0]
    auto = bearing_equilibrium(ball, load)
    energy = bearing_equilibrium(ball, load, method="energy")
    assert auto.method == "energy" and any("newton" in n for n in auto.notes)
    np.testing.assert_allclose(auto.displacement, energy.displacement, rtol=1e-9)
    np.testing.assert_allclose(auto.force, load, atol=1e-6)
    tapered = rs.RollerBearing(n_rollers=17, pitch_diameter=0.06, roller_diameter=0.008,
                               effective_length=0.012, contact_angle=math.radians(15),
                               radial_clearance=-2e-6)
    with pytest.raises(rs.ModelError, match="no equilibrium for the load"):
        bearing_equilibrium(tapered, [0.0, -2000.0, 0.0, 0.0, 0.0])
