"""RollerBearing: contract (gradients, symmetry, invariance, errors) and references."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from rotorsim.elements.rolling.contact.hertz_line import (
    constant_to_si,
    iso_roller_constant,
    tilted_line_integrals,
)
from rotorsim.elements.rolling.geometry import cage_ratio
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.profile import CircularCrown, LogarithmicProfile
from rotorsim.errors import ModelError

# Seed 000 Table 1 roller bearing (Kn for the whole roller, N/m^(10/9)), L chosen 7.5 mm.
BASE = dict(n_rollers=14, pitch_diameter=42.5e-3, roller_diameter=7.5e-3,
            effective_length=7.5e-3, Kn=3.0e8)
SCALE = np.array([20e-6, 20e-6, 20e-6, 2e-3, 2e-3])  # typical displacement sizes [m, rad]

CASES = {
    "cylindrical_tilt": dict(contact_angle=0.0, radial_clearance=1.75e-6),
    "tapered_tilt": dict(contact_angle=math.radians(15.0), radial_clearance=1.0e-6),
    "thrust_tilt": dict(contact_angle=0.5 * math.pi),
    "preloaded_tilt": dict(contact_angle=math.radians(30.0), radial_clearance=-3e-6),
    "cylindrical_slices": dict(model="slices", radial_clearance=1.75e-6),
    "tapered_slices": dict(model="slices", contact_angle=math.radians(15.0), n_slices=7),
    "crowned_slices": dict(model="slices", contact_angle=math.radians(10.0),
                           profile=CircularCrown(crown_drop=4e-6, crown_length=2e-3)),
    "log_slices": dict(model="slices", n_slices=31,
                       profile=LogarithmicProfile.with_end_drop(2e-6, 8e-6)),
}


def _bearing(name: str) -> RollerBearing:
    return RollerBearing(**BASE, **CASES[name])


def _random_states(bearing: RollerBearing, n: int, seed: int):
    rng = np.random.default_rng(seed)
    delta = rng.normal(size=(n, 5)) * SCALE
    psi = bearing.element_angles(rng.uniform(0.0, 2.0 * np.pi, n))
    return delta, psi


@pytest.mark.parametrize("name", CASES)
def test_force_is_energy_gradient_and_stiffness_its_hessian(name):
    bearing = _bearing(name)
    delta, psi = _random_states(bearing, 40, seed=1)
    state = bearing.state(delta, psi)
    limits = bearing.roller_loads(delta, psi).contact_limits
    edge_loaded = limits[..., 1] - limits[..., 0] < 0.99  # NaN (unloaded) compares False
    assert 0.0 < state.loaded.mean() < 1.0 and edge_loaded.sum() >= 10
    # relative step 1e-6: round-off ~1e-10; smaller than the distance of a contact from its
    # start except by chance (the tangent ~ delta^(1/9) has no derivative there)
    steps = 1e-6 * SCALE
    fd_force = np.empty_like(state.force)
    fd_stiff = np.empty_like(state.stiffness)
    for i in range(5):
        e = np.zeros(5)
        e[i] = steps[i]
        fd_force[:, i] = (bearing.energy(delta + e, psi) - bearing.energy(delta - e, psi)) / (
            2 * steps[i])
        fd_stiff[:, :, i] = (bearing.state(delta + e, psi).force
                             - bearing.state(delta - e, psi).force) / (2 * steps[i])
    # compare in the scaled variables (force * size = energy units) so all 5 DOFs count equally
    f_scaled = state.force * SCALE
    f_ref = np.abs(f_scaled).max(axis=1)
    assert np.all(np.abs(fd_force * SCALE - f_scaled).max(axis=1) <= 1e-6 * f_ref)
    k_scaled = state.stiffness * SCALE[:, None] * SCALE[None, :]
    k_ref = np.abs(k_scaled).max(axis=(1, 2))
    err = np.abs(fd_stiff * SCALE[:, None] * SCALE[None, :] - k_scaled).max(axis=(1, 2))
    assert np.all(err <= 1e-6 * k_ref)
    assert np.array_equal(state.stiffness, state.stiffness.transpose(0, 2, 1))
    assert np.allclose(bearing.energy(delta, psi), state.energy, rtol=1e-13, atol=0.0)


@pytest.mark.parametrize("name", CASES)
def test_stiffness_is_positive_semidefinite(name):
    bearing = _bearing(name)
    delta, psi = _random_states(bearing, 30, seed=2)
    k = bearing.state(delta, psi).stiffness
    scaled = k * SCALE[:, None] * SCALE[None, :]
    eig = np.linalg.eigvalsh(scaled)
    assert np.all(eig >= -1e-12 * np.abs(eig).max(axis=1, keepdims=True))


@pytest.mark.parametrize("name", CASES)
def test_rotation_invariance(name):
    bearing = _bearing(name)
    delta, psi = _random_states(bearing, 10, seed=3)
    theta = 0.7
    rot = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
    turned = delta.copy()
    turned[:, 0:2] = delta[:, 0:2] @ rot.T
    turned[:, 3:5] = delta[:, 3:5] @ rot.T
    a, b = bearing.state(delta, psi), bearing.state(turned, psi + theta)
    scale = np.abs(a.force).max()
    assert np.allclose(b.force[:, 0:2], a.force[:, 0:2] @ rot.T, atol=1e-12 * scale)
    assert np.allclose(b.force[:, 3:5], a.force[:, 3:5] @ rot.T, atol=1e-12 * scale)
    assert np.allclose(b.force[:, 2], a.force[:, 2], atol=1e-12 * scale)
    assert np.allclose(b.element_load, a.element_load, rtol=1e-11, atol=1e-9 * scale)


@pytest.mark.parametrize("model", ["tilt_integral", "slices"])
def test_zero_displacement_zero_clearance_gives_zero(model):
    bearing = RollerBearing(**BASE, contact_angle=0.3, model=model)
    state = bearing.state(np.zeros((3, 5)), bearing.element_angles([0.0, 1.0, 2.0]))
    assert np.all(state.force == 0.0) and np.all(state.stiffness == 0.0)
    assert np.all(state.energy == 0.0) and not state.loaded.any()


def test_uniform_slices_reproduce_the_whole_roller():
    """``q_k = (Kn/K) delta^n``: K slices equal the whole roller for a uniform deflection."""
    delta = np.array([[12e-6, -5e-6, 3e-6, 0.0, 0.0]])
    whole = RollerBearing(**BASE, contact_angle=0.2)
    psi = whole.element_angles(0.3)
    ref = whole.state(delta, psi)
    for k in (1, 7, 20):
        sliced = RollerBearing(**BASE, contact_angle=0.2, model="slices", n_slices=k)
        got = sliced.state(delta, psi)
        assert np.allclose(got.element_load, ref.element_load, rtol=1e-12, atol=0.0)
        assert np.allclose(got.force[:, :3], ref.force[:, :3], rtol=1e-12,
                           atol=1e-12 * np.abs(ref.force).max())


def test_tilt_integral_closed_form_matches_quadrature():
    """Eqs 7-9, 22-23 in closed form vs scipy quad, incl. partial contact and tiny tilts."""
    v = np.array([[1.0, 1.0, 1.0, 0.2, 0.0, -0.3, 1.0, 1.0]])
    lw = np.array([[0.0, 1e-9, 0.09, 1.5, 2.0, 1.0, -0.11, -3.0]])
    n = 10.0 / 9.0
    got = tilted_line_integrals(v, lw, n)
    for j in range(v.shape[1]):
        def d(x, j=j):
            return max(v[0, j] + x * lw[0, j], 0.0)
        for value, (p, m) in zip(got[1:6], [(0, n), (1, n), (0, n - 1), (1, n - 1),
                                            (2, n - 1)], strict=True):
            ref = quad(lambda x, p=p, m=m: x**p * d(x) ** m, -0.5, 0.5, epsabs=1e-14,
                       epsrel=1e-12, limit=200)[0]
            assert value[0, j] == pytest.approx(ref, rel=1e-9, abs=1e-12)
        e_ref = quad(lambda x: d(x) ** (n + 1) / (n + 1), -0.5, 0.5, epsabs=1e-14)[0]
        assert got[0][0, j] == pytest.approx(e_ref, rel=1e-9, abs=1e-12)


def test_edge_loaded_roller_load_and_eccentricity():
    """Roller touching at its centre, tilted: contact on half the length (eq 8),
    ``Q = Kn (L w)^n 2^-(n+1)/(n+1)``, ``e = L (n+1) / (2 (n+2))`` (eq 9)."""
    bearing = RollerBearing(**{**BASE, "n_rollers": 1}, cage="fixed")
    n, length, tilt = bearing.exponent, bearing.effective_length, 1e-3
    loads = bearing.roller_loads([0.0, 0.0, 0.0, 0.0, tilt], [[0.0]])  # omega = ry at psi=0
    q_ref = bearing.kn * (length * tilt) ** n * 0.5 ** (n + 1) / (n + 1)
    assert loads.load[0, 0] == pytest.approx(q_ref, rel=1e-12)
    assert loads.eccentricity[0, 0] == pytest.approx(length * (n + 1) / (2 * (n + 2)),
                                                     rel=1e-12)
    assert np.allclose(loads.contact_limits[0, 0], [0.0, 0.5], atol=1e-15)


@pytest.mark.parametrize("model", ["tilt_integral", "slices"])
@pytest.mark.validation
def test_stribeck_line_contact(model):
    """Zero clearance, pure radial load: Qmax = 4.085 Fr / Z for n = 10/9 (reference README)
    in the continuous limit 1/Jr(0.5) (quadrature below); Z = 100 rollers."""
    n = 10.0 / 9.0
    j_r = quad(lambda p: math.cos(p) ** (n + 1), -math.pi / 2, math.pi / 2)[0] / (2 * math.pi)
    assert 1.0 / j_r == pytest.approx(4.085, abs=5e-4)  # README value, 3 decimals
    bearing = RollerBearing(100, 0.2, 0.005, 0.01, Kn=1e9, model=model, cage="fixed")
    psi = bearing.element_angles(0.0)
    fr = 5000.0
    x = brentq(lambda x: bearing.state([x, 0, 0, 0, 0], psi).force[0, 0] - fr, 1e-9, 1e-3,
               xtol=1e-16, rtol=1e-14)
    ratio = bearing.state([x, 0, 0, 0, 0], psi).element_load.max() * 100 / fr
    assert ratio == pytest.approx(4.085, abs=5e-4)
    assert ratio == pytest.approx(1.0 / j_r, abs=1e-5)  # Z = 100: sum vs integral ~3e-6


SJOVALL_11 = {0.1: (0.1268, 0.1319), 0.3: (0.2055, 0.2334), 0.5: (0.2453, 0.3090),
              0.8: (0.2658, 0.4099), 1.0: (0.2523, 0.4817), 2.5: (0.1075, 0.7837)}


@pytest.mark.parametrize("model", ["tilt_integral", "slices"])
@pytest.mark.validation
def test_sjovall_integrals_n_1_1(model):
    """Jr(eps), Ja(eps) for n = 1.1 (README table, run with ``exponent=1.1``; the table
    is not for 10/9). Tolerance: half a unit of the 4th decimal (5e-5) plus 1e-5 for the
    Z = 360 sum replacing the integral (measured < 2e-6 against quadrature)."""
    alpha, z = math.radians(20.0), 360
    angular = RollerBearing(z, 0.2, 0.005, 0.01, Kn=1e9, exponent=1.1, contact_angle=alpha,
                            model=model, n_slices=3, cage="fixed")
    psi = angular.element_angles(0.0)
    dr = 10e-6
    for eps, (jr_ref, ja_ref) in SJOVALL_11.items():
        # zero clearance, combined radial dr and axial dz: eps = (1 + dz tan a / dr) / 2
        state = angular.state([dr, 0, (2 * eps - 1) * dr / math.tan(alpha), 0, 0], psi)
        q_max = state.element_load.max()
        assert state.force[0, 0] / (z * q_max * math.cos(alpha)) == pytest.approx(
            jr_ref, abs=6e-5)
        assert state.force[0, 2] / (z * q_max * math.sin(alpha)) == pytest.approx(
            ja_ref, abs=6e-5)
        # cylindrical, radial clearance r_L: eps = (1 - r_L / dr) / 2
        cyl = RollerBearing(z, 0.2, 0.005, 0.01, Kn=1e9, exponent=1.1, model=model,
                            radial_clearance=dr * (1 - 2 * eps), cage="fixed")
        state = cyl.state([dr, 0, 0, 0, 0], psi)
        assert state.force[0, 0] / (z * state.element_load.max()) == pytest.approx(
            jr_ref, abs=6e-5)


REBM_FA = [4000.0, 20000.0, 40000.0, 60000.0, 85000.0, 98000.0]
REBM_KXX = [3.84, 4.67, 4.83, 5.03, 5.21, 5.29]  # MN/mm; 4.67 is a misprint (README)
REBM_KZZ = [2.80, 3.29, 3.53, 3.67, 3.80, 3.86]


@pytest.mark.parametrize("model", ["tilt_integral", "slices"])
@pytest.mark.validation
def test_tapered_pure_axial_load_rebm_table(model):
    """Kumar (2005) Table 3.1 (Lim-Singh REBM): Z = 20, r_p = 40.5 mm, L = 18.251 mm,
    alpha = 31.128 deg, Kn = 7.86e4 L^(8/9) N/mm^(10/9) whole roller. Tolerance: half a
    unit of the printed 3 digits (0.005 MN/mm) plus 0.06 % for Kn printed to 3 digits."""
    length = 18.251
    alpha = math.radians(31.128)
    bearing = RollerBearing(20, 0.081, 0.01, length * 1e-3,
                            Kn=constant_to_si(7.86e4 * length ** (8 / 9)),
                            contact_angle=alpha, model=model, n_slices=5)
    psi = bearing.element_angles(0.0)
    for fa, kxx_ref, kzz_ref in zip(REBM_FA, REBM_KXX, REBM_KZZ, strict=True):
        z = brentq(lambda z, fa=fa: bearing.state([0, 0, z, 0, 0], psi).force[0, 2] - fa,
                   1e-9, 1e-3, xtol=1e-16, rtol=1e-14)
        state = bearing.state([0, 0, z, 0, 0], psi)
        assert np.allclose(state.element_load, fa / (20 * math.sin(alpha)), rtol=1e-12)
        k = state.stiffness[0] / 1e9  # MN/mm
        assert k[0, 0] / k[2, 2] == pytest.approx(0.5 / math.tan(alpha) ** 2, rel=1e-12)
        assert k[1, 1] == pytest.approx(k[0, 0], rel=1e-12)
        assert abs(k[2, 2] - kzz_ref) <= 0.005 + 6e-4 * kzz_ref
        if fa == 20000.0:  # misprint: cot^2(a)/2 * 3.29 = 4.51
            assert abs(k[0, 0] - 4.51) <= 0.005 + 6e-4 * 4.51
            assert abs(k[0, 0] - kxx_ref) > 0.1
        else:
            assert abs(k[0, 0] - kxx_ref) <= 0.005 + 6e-4 * kxx_ref


def _misaligned_states(bearing: RollerBearing):
    delta = np.array([[15e-6, 2e-6, 0.0, 0.4e-3, 1.5e-3],
                      [5e-6, 0.0, 0.0, 0.0, 3e-3],
                      [8e-6, -6e-6, 0.0, -2e-3, 0.5e-3]])
    return delta, bearing.element_angles([0.0, 0.1, 0.2])


def test_misaligned_cylindrical_bearing_carries_moment_with_edge_loading():
    bearing = RollerBearing(**BASE, radial_clearance=1e-6)
    delta, psi = _misaligned_states(bearing)
    state = bearing.state(delta, psi)
    limits = bearing.roller_loads(delta, psi).contact_limits
    width = limits[..., 1] - limits[..., 0]
    assert np.any(width < 0.99)  # partially loaded (edge-loaded) rollers
    # a tilt ry > 0 is resisted: the moment does positive work (energy grows with tilt)
    assert state.force[1, 4] > 0.0 and state.stiffness[1, 4, 4] > 0.0


def test_slices_converge_to_tilt_integral():
    """Midpoint rule over K slices: O(K^-2) where the deflection is smooth, O(K^-(n+1))
    at the end of the loaded zone of an edge-loaded roller."""
    exact = RollerBearing(**BASE, radial_clearance=1e-6)
    delta, psi = _misaligned_states(exact)
    ref = exact.state(delta, psi)
    errors = []
    for k in (25, 50, 100, 200, 400):
        st = RollerBearing(**BASE, radial_clearance=1e-6, model="slices",
                           n_slices=k).state(delta, psi)
        errors.append(np.abs(st.force - ref.force).max() / np.abs(ref.force).max())
    errors_arr = np.array(errors)
    orders = np.log2(errors_arr[:-1] / errors_arr[1:])
    assert np.all(orders > 1.5) and errors_arr[-1] < 1e-6
    st = RollerBearing(**BASE, radial_clearance=1e-6, model="slices",
                       n_slices=400).state(delta, psi)
    # the tangent contains delta^(1/9), whose midpoint error at the contact edge is
    # O(K^-(10/9)): 1e-3 at K = 400
    assert np.abs(st.stiffness - ref.stiffness).max() < 1e-3 * np.abs(ref.stiffness).max()


def test_crowned_roller_against_quadrature():
    """Fully crowned roller without tilt: ``Q = Kn int (V - c(xi))^n dxi``."""
    crown = CircularCrown(crown_drop=6e-6)
    bearing = RollerBearing(**{**BASE, "n_rollers": 1}, model="slices", n_slices=400,
                            profile=crown, cage="fixed")
    v = 3e-6  # contact over the middle ~70 % of the length
    got = bearing.roller_loads([v, 0, 0, 0, 0], [[0.0]]).load[0, 0]

    def drop(x):
        return float(crown.drop(np.array([x]), bearing.effective_length)[0])

    ref = bearing.kn * quad(lambda x: max(v - drop(x), 0.0) ** bearing.exponent,
                            -0.5, 0.5, limit=200)[0]
    assert got == pytest.approx(ref, rel=1e-5)  # midpoint rule, K = 400


def test_logarithmic_profile_removes_edge_loading():
    """Tilted roller (omega L = 3.75 um): the straight roller peaks at its end slice,
    the logarithmic one (end drop 10 um) inside the length."""
    straight = RollerBearing(**BASE, model="slices", n_slices=40)
    log = RollerBearing(**BASE, model="slices", n_slices=40,
                        profile=LogarithmicProfile.with_end_drop(2e-6, 10e-6))
    delta = [[10e-6, 0.0, 0.0, 0.0, 0.5e-3]]
    psi = straight.element_angles(0.0)
    s_load = straight.roller_loads(delta, psi).slice_load[0, 0]
    l_load = log.roller_loads(delta, psi).slice_load[0, 0]
    assert s_load.argmax() == 39  # straight roller: peak at the end (edge loading)
    assert 20 <= l_load.argmax() < 35 and l_load[-1] < 0.6 * l_load.max()


def test_thrust_bearing_has_no_radial_stiffness_and_cylindrical_no_axial():
    thrust = RollerBearing(**BASE, contact_angle=0.5 * math.pi)
    cyl = RollerBearing(**BASE)
    delta = np.array([[1e-6, 2e-6, 5e-6, 1e-4, 0.0]])
    k_t = thrust.state(delta, thrust.element_angles(0.0)).stiffness[0]
    k_c = cyl.state(delta, cyl.element_angles(0.0)).stiffness[0]
    assert np.all(np.abs(k_t[:2]) <= 1e-12 * np.abs(k_t).max())
    assert np.all(k_c[2] == 0.0)


def test_defaults_and_conversions():
    b = RollerBearing(14, 0.05, 0.008, 0.012, diametral_clearance=10e-6, cage="rotating",
                      contact_angle=0.2)
    assert b.clearance == 5e-6 and b.kn == iso_roller_constant(0.012)
    assert b.kappa == pytest.approx(cage_ratio(0.008, 0.05, 0.2))
    fixed = RollerBearing(**BASE, cage="fixed", psi0=0.1)
    assert np.allclose(fixed.element_angles([0.0, 5.0]),
                       0.1 + 2 * np.pi * np.arange(14) / 14)
    s1 = fixed.state(np.zeros(5), fixed.element_angles(0.0)[0])  # (5,) and (N,) inputs
    assert s1.force.shape == (1, 5) and s1.stiffness.shape == (1, 5, 5)
    for model in ("tilt_integral", "slices"):  # several sample blocks, concatenated
        b = RollerBearing(**BASE, cage="fixed", model=model)
        delta = np.full((5000, 5), 1e-6)
        big = b.state(delta, b.element_angles(np.zeros(5000)))
        assert big.force.shape == (5000, 5)
        assert np.allclose(big.force, big.force[0], rtol=1e-13, atol=0.0)  # BLAS rounding
        assert np.allclose(b.energy(delta, b.element_angles(np.zeros(5000))), big.energy,
                           rtol=1e-13, atol=0.0)


@pytest.mark.parametrize("kwargs, match", [
    (dict(n_rollers=0), "n_rollers"),
    (dict(n_rollers=-3), "n_rollers"),
    (dict(n_rollers=2.5), "n_rollers"),
    (dict(contact_angle=-0.01), "contact_angle"),
    (dict(contact_angle=math.radians(91.0)), "contact_angle"),
    (dict(contact_angle=float("nan")), "contact_angle"),
    (dict(Kn=0.0), "Kn"),
    (dict(Kn=-1e8), "Kn"),
    (dict(exponent=0.0), "exponent"),
    (dict(exponent=0.9), "exponent"),
    (dict(roller_diameter=0.05), "roller_diameter"),
    (dict(effective_length=-1.0), "effective_length"),
    (dict(radial_clearance=2e-6, diametral_clearance=2e-6), "diametral"),
    (dict(radial_clearance=5e-3), "clearance"),
    (dict(profile=CircularCrown(5e-6)), "tilt-integral"),
    (dict(model="slices", n_slices=0), "n_slices"),
    (dict(model="slices", profile=CircularCrown(5e-6, crown_length=0.01)), "crown length"),
    (dict(model="slices", profile=LogarithmicProfile(1e-6, 1.5)), "shape"),
])
def test_bad_input(kwargs, match):
    with pytest.raises(ModelError, match=match):
        RollerBearing(**{**BASE, "tag": "B7", **kwargs})


def test_bad_options_and_states():
    with pytest.raises(TypeError, match="tilt_integral"):
        RollerBearing(**BASE, model="rigid")
    with pytest.raises(TypeError, match="rotating"):
        RollerBearing(**BASE, cage="free")
    b = RollerBearing(**BASE, tag="B1")
    psi = b.element_angles(0.0)
    with pytest.raises(ModelError, match=r"B1.*delta"):
        b.state(np.zeros((2, 4)), psi)
    with pytest.raises(ModelError, match="psi"):
        b.state(np.zeros((2, 5)), np.zeros((2, 13)))
    with pytest.raises(ModelError, match="finite"):
        b.state(np.full((1, 5), np.nan), psi)
