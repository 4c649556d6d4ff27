"""RollingBearing 2-node element: contract (tangents = FD Jacobians, action = -reaction),
linearisation, and linearised bearings in a rotor (critical speed vs bearing load)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.analyses.linear.modal import modal
from rotorsim.analyses.statics.bearing_statics import (
    bearing_equilibrium,
    linearize_at_load,
    linearized_bearings,
)
from rotorsim.analyses.statics.static import static
from rotorsim.elements.disk import DiskElement
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import ElementForce, RollingBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

BALL = BallBearing.from_geometry(n_balls=9, pitch_diameter=46e-3, ball_diameter=9.525e-3,
                                 f_i=0.515, f_o=0.525, contact_angle=math.radians(25.0),
                                 diametral_clearance=10e-6, tag="6206")
ROLLERS = {
    "tapered_slices": RollerBearing(14, 42.5e-3, 7.5e-3, 10e-3, Kn=3.0e8, model="slices",
                                    contact_angle=math.radians(15.0), n_slices=9),
    "cylindrical": RollerBearing(14, 42.5e-3, 7.5e-3, 10e-3, Kn=3.0e8,
                                 radial_clearance=1.75e-6),
}
MODELS = {"ball": BALL, **ROLLERS}
SIZE = np.array([15e-6, 15e-6, 15e-6, 7e-4, 7e-4, 1.0])  # per node DOF: m, rad (rz unused)


def _states(element: RollingBearing, n_samples: int, seed: int):
    rng = np.random.default_rng(seed)
    per_node = np.tile(SIZE, len(element.nodes))
    u = rng.normal(size=(n_samples, element.n_dofs)) * per_node
    u[:, 2] += 10e-6  # push towards the rings (tapered, angular contact)
    v = rng.normal(size=(n_samples, element.n_dofs)) * per_node * 50.0  # ~1 mm/s
    return u, v, rng.uniform(0.0, 2 * math.pi, n_samples)


def _fd_jacobian(fun, x: np.ndarray, steps: np.ndarray) -> np.ndarray:
    jac = np.empty((x.shape[0], x.shape[1], x.shape[1]))
    for j in range(x.shape[1]):
        e = np.zeros(x.shape[1])
        e[j] = steps[j]
        jac[:, :, j] = (fun(x + e) - fun(x - e)) / (2 * steps[j])
    return jac


def _assert_close_scaled(a, b, scale, rel):
    """Compare (S, n, n) tangents in scaled DOFs (force x size: energy units)."""
    sa = a * scale[None, :, None] * scale[None, None, :]
    sb = b * scale[None, :, None] * scale[None, None, :]
    ref = np.abs(sb).max(axis=(1, 2), keepdims=True)
    assert np.all(np.abs(sa - sb) <= rel * ref)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("link", [None, 7])
def test_tangent_is_the_fd_jacobian_and_action_equals_reaction(model, link):
    element = RollingBearing(MODELS[model], n=2, n_link=link, tag=model)
    u, v, phi = _states(element, 12, seed=4)
    out = element.force(u, v, phi, 100.0)
    assert isinstance(out, ElementForce) and out.internal is None
    n = element.n_dofs
    assert out.f.shape == u.shape == (12, n) and out.K.shape == out.C.shape == (12, n, n)
    loaded = (np.abs(out.f[:, :3]).max(axis=1) > 0).mean()
    assert 0.2 < loaded <= 1.0
    scale = np.tile(SIZE, len(element.nodes))
    scale[5::6] = 1e-6  # rz carries nothing; any step works
    # step 1e-6 of the displacement size (roller tangent ~ delta^(1/9); see test_roller.py)
    fd = _fd_jacobian(lambda x: element.force(x, v, phi, 100.0).f, u, 1e-6 * scale)
    _assert_close_scaled(out.K, fd, scale, 1e-6)
    assert np.all(out.C == 0.0) and np.array_equal(out.K, out.K.transpose(0, 2, 1))
    if link is not None:
        assert np.array_equal(out.f[:, 6:], -out.f[:, :6])
        assert np.array_equal(out.K[:, 6:, 6:], out.K[:, :6, :6])
        assert np.array_equal(out.K[:, :6, 6:], -out.K[:, :6, :6])
    assert np.all(out.f[:, 5::6] == 0) and np.all(out.K[:, 5::6] == 0)


@pytest.mark.parametrize("link", [None, 3])
def test_proportional_damping_tangents(link):
    """C = beta K exactly; K includes beta (dK/d delta) delta' (central difference of the
    exact tangent): compared with FD of f in u and v."""
    beta = 2e-5
    element = RollingBearing(BALL, n=0, n_link=link, contact_damping="proportional",
                             damping_factor=beta)
    plain = RollingBearing(BALL, n=0, n_link=link)
    u, v, phi = _states(element, 10, seed=9)
    out, ref = element.force(u, v, phi, 0.0), plain.force(u, v, phi, 0.0)
    delta = plain.relative(v)
    k5 = ref.K[:, :5, :5]
    assert np.allclose(out.f[:, :5], ref.f[:, :5] + beta * np.einsum("sij,sj->si", k5, delta),
                       rtol=1e-12, atol=1e-9)
    assert np.array_equal(out.C, beta * ref.K)
    scale = np.tile(SIZE, len(element.nodes))
    scale[5::6] = 1e-6
    fd_u = _fd_jacobian(lambda x: element.force(x, v, phi, 0.0).f, u, 1e-6 * scale)
    _assert_close_scaled(out.K, fd_u, scale, 1e-5)
    fd_v = _fd_jacobian(lambda x: element.force(u, x, phi, 0.0).f, v, 1e-3 * scale)
    _assert_close_scaled(out.C, fd_v, scale, 1e-7)  # f is linear in v: round-off only
    assert np.abs(out.K - ref.K).max() > 0  # the velocity term is present


def test_scalar_and_per_sample_angles_agree():
    element = RollingBearing(ROLLERS["cylindrical"], n=1)
    u, v, _ = _states(element, 5, seed=2)
    a = element.force(u, v, 0.3, 0.0)
    b = element.force(u, v, np.full(5, 0.3), np.zeros(5))
    assert np.array_equal(a.f, b.f) and np.array_equal(a.K, b.K)
    one = element.force(u[0], v[0], 0.3, 0.0)  # (n,) input is one sample
    assert np.array_equal(one.f, a.f[:1])


@pytest.mark.parametrize("link", [None, 5])
def test_linearize_at_a_load_and_at_a_displacement(link):
    element = RollingBearing(BALL, n=1, n_link=link, tag="B1", contact_damping="proportional",
                             damping_factor=1e-5)
    load = [800.0, -300.0, 1200.0, 2.0, -1.0]
    lin = linearize_at_load(element, load, phi=0.4)
    eq = bearing_equilibrium(BALL, load, phi=0.4)
    model_k = BALL.state(eq.displacement[None], BALL.element_angles(0.4)).stiffness[0]
    assert isinstance(lin, BearingElement) and lin.tag == "B1" and lin.nodes == element.nodes
    assert np.array_equal(lin.stiffness_matrix, eq.stiffness)
    assert np.allclose(lin.stiffness_matrix, model_k, rtol=1e-13, atol=0.0)
    assert np.allclose(lin.damping_matrix, 1e-5 * model_k, rtol=1e-13, atol=0.0)
    k_elem = lin.matrices().K
    assert np.allclose(k_elem[:5, :5], model_k) and k_elem[5, 5] == 0.0
    if link is not None:
        assert np.allclose(k_elem[6:11, :5], -model_k)
    # the element tangent at the equilibrium displacement is the same matrix
    u = np.zeros((1, element.n_dofs))
    u[0, :5] = eq.displacement
    assert np.allclose(element.force(u, np.zeros_like(u), 0.4, 0.0).K[0, :5, :5], model_k)
    by_disp = element.linearize(displacement=eq.displacement, phi=0.4)
    assert np.allclose(by_disp.stiffness_matrix, model_k, rtol=1e-13, atol=0.0)
    assert linearize_at_load(RollingBearing(BALL, n=1), load, phi=0.4).damping_matrix is None


def test_bad_input():
    with pytest.raises(ModelError, match="n must"):
        RollingBearing(BALL, n=-1)
    with pytest.raises(ModelError, match="differ"):
        RollingBearing(BALL, n=2, n_link=2)
    with pytest.raises(ModelError, match="rolling-bearing model"):
        RollingBearing(object(), n=0)
    with pytest.raises(TypeError, match=r"unknown contact_damping 'magic'; valid: .*'ehl'"):
        RollingBearing(BALL, n=0, contact_damping="magic")
    with pytest.raises(TypeError, match=r"contact_damping='ehl' needs lubricant"):
        RollingBearing(BALL, n=0, contact_damping="ehl")
    with pytest.raises(ModelError, match="damping_factor"):
        RollingBearing(BALL, n=0, damping_factor=1e-5)
    with pytest.raises(ModelError, match="damping_factor"):
        RollingBearing(BALL, n=0, contact_damping="proportional", damping_factor=-1.0)
    element = RollingBearing(BALL, n=0, n_link=1)
    with pytest.raises(ModelError, match="shape"):
        element.force(np.zeros((2, 6)), np.zeros((2, 6)), 0.0, 0.0)
    with pytest.raises(ModelError, match="finite"):
        element.force(np.full((1, 12), np.nan), np.zeros((1, 12)), 0.0, 0.0)
    with pytest.raises(TypeError, match="displacement"):  # a state, not a load
        element.linearize()
    with pytest.raises(TypeError):
        element.linearize([800.0, 0.0, 0.0, 0.0, 0.0])  # a load given as before: refused
    with pytest.raises(ModelError, match=r"tangent must have shape \(5, 5\)"):
        element.linearize(displacement=np.zeros(5), tangent=np.eye(4))


# ------------------------------------------------------- linearised bearings in a rotor
STEEL = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def _rotor(bearings) -> Rotor:
    shaft = [ShaftElement(L=0.1, idl=0.0, odl=0.03, material=STEEL) for _ in range(6)]
    return Rotor(shaft, [DiskElement(n=3, m=8.0, Id=0.03, Ip=0.05)], list(bearings))


def _deep_groove(tag: str) -> BallBearing:
    return BallBearing.from_geometry(n_balls=9, pitch_diameter=46e-3, ball_diameter=9.525e-3,
                                     f_i=0.515, f_o=0.525, diametral_clearance=10e-6, tag=tag)


def _first_forward_lateral(rotor: Rotor) -> float:
    crit = critical_speeds(rotor, num_modes=6, whirl="forward")
    return float(crit.speed[crit.kind == "lateral"][0])


def test_rotor_on_bearings_linearised_at_their_static_loads():
    rolling = [RollingBearing(_deep_groove("A"), n=0, tag="A"),
               RollingBearing(_deep_groove("B"), n=6, tag="B")]
    placeholder = _rotor([BearingElement(n=0, kxx=1e8), BearingElement(n=6, kxx=1e8)])
    reactions = static(placeholder)
    loads = [-np.concatenate([f, m[:2]]) for f, m in
             zip(reactions.bearing_forces, reactions.bearing_moments, strict=True)]
    assert loads[0][1] < 0  # gravity pushes the inner rings down
    rotor = _rotor(linearized_bearings(rolling, loads))
    # a statically determinate support: the reactions do not depend on the stiffness
    again = static(rotor)
    assert np.allclose(again.bearing_forces[:, :2], reactions.bearing_forces[:, :2],
                       rtol=1e-8, atol=1e-8)
    k = rotor.bearing_elements[0].stiffness_matrix
    assert k[1, 1] > k[0, 0] > 0  # stiffer along the load (y) than across it
    m = modal(rotor, speed=0.0, num_modes=6)
    assert np.all(m.wn > 0) and np.all(np.isfinite(m.wn))
    assert _first_forward_lateral(rotor) > 0


def test_critical_speed_rises_with_bearing_load():
    """Hertz stiffening: K ~ Fr^(1/3) for a ball bearing, so the first critical speed of a
    rotor on two bearings grows monotonically with the radial load (preload)."""
    rolling = [RollingBearing(_deep_groove("A"), n=0), RollingBearing(_deep_groove("B"), n=6)]
    speeds, radial = [], []
    for fr in (50.0, 200.0, 800.0, 3200.0):
        lin = linearized_bearings(rolling, [[0, -fr, 0, 0, 0]] * 2)
        radial.append(lin[0].stiffness_matrix[1, 1])
        speeds.append(_first_forward_lateral(_rotor(lin)))
    assert np.all(np.diff(radial) > 0) and np.all(np.diff(speeds) > 0)
    # x4 load -> radial stiffness x 4^(1/3) = 1.587 once the clearance is taken up
    assert radial[-1] / radial[-2] == pytest.approx(4 ** (1 / 3), rel=0.05)
