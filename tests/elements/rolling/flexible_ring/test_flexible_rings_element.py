"""FlexibleRingBearingElement (NonlinearElement protocol) and input validation of the
flexible-ring bearing."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium, linearize_at_load
from rotorsim.assembly.nonlinear import NonlinearAssembly
from rotorsim.elements.base import NonlinearElement
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.rolling.flexible_ring.bearing import FlexibleRingRollerBearing
from rotorsim.elements.rolling.flexible_ring.element import FlexibleRingBearingElement
from rotorsim.elements.rolling.flexible_ring.geometry import RingSection
from rotorsim.errors import ModelError

SEED = dict(n_rollers=24, pitch_radius=75e-3, roller_radius=6.5e-3, effective_length=16e-3,
            shaft_radius=54e-3, housing_radius=97e-3, ring_width=30e-3, n_slices=4,
            diametral_clearance=-40e-6)
BEARING = FlexibleRingRollerBearing(**SEED)
SPEED = 1000.0
SIZE = np.array([6e-6, 6e-6, 6e-6, 8e-5, 8e-5, 1.0])  # per node DOF [m, rad]


def _u(element: FlexibleRingBearingElement, n: int, seed: int) -> np.ndarray:
    """``n`` random element states whose slices all sit at least 50 nm from contact onset:
    there the force is smooth (``delta^(10/9)`` has an unbounded second derivative at
    ``delta = 0``, where a 1e-9 m finite difference is not accurate)."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        u = rng.normal(size=(4 * n, element.n_dofs)) * np.tile(SIZE, len(element.nodes))
        st = element.state(u, 0.0, SPEED)
        delta = element.relative(u)
        psi = BEARING.element_angles()
        c, s = np.cos(psi), np.sin(psi)
        z = np.stack([-(delta[:, :1] * c + delta[:, 1:2] * s),
                      delta[:, 3:4] * s - delta[:, 4:5] * c]).reshape(2, -1)
        y = np.moveaxis(st.internal, -1, 0).reshape(4, -1)
        d = BEARING.potential.deflections(y, z)  # (2, S*N, K)
        margin = np.abs(d).min(axis=(0, 2)).reshape(-1, 24).min(axis=1)
        out.extend(u[margin > 50e-9])
    return np.array(out[:n])


@pytest.mark.parametrize("link", [None, 1])
def test_tangent_is_the_fd_jacobian_and_action_equals_reaction(link):
    el = FlexibleRingBearingElement(BEARING, n=0, n_link=link)
    assert isinstance(el, NonlinearElement) and el.nodes == ((0,) if link is None else (0, 1))
    u = _u(el, 5, 1)
    phi = np.zeros(5)
    out = el.force(u, np.zeros_like(u), phi, SPEED)
    assert out.f.shape == (5, el.n_dofs) and out.K.shape == (5, el.n_dofs, el.n_dofs)
    assert np.all(out.C == 0.0) and out.internal.shape == (5, 24, 4)
    if link is not None:
        assert np.allclose(out.f[:, :6], -out.f[:, 6:], rtol=0, atol=0)
    assert np.all(out.f[:, [2, 5]] == 0.0)  # no axial force, no torque
    length = 1.0 / np.tile([1.0, 1.0, 1.0, 75e-3, 75e-3, 75e-3], len(el.nodes))
    steps = 1e-9 * length  # 1e-9 m, tilts 1e-9 m at the pitch radius
    # compare in scaled DOFs (rows and columns times their length): energy units
    scaled = out.K * length[None, :, None] * length[None, None, :]
    scale = np.abs(scaled).max()
    for j in range(el.n_dofs):
        e = np.zeros(el.n_dofs)
        e[j] = steps[j]
        fd = (el.force(u + e, u * 0, phi, SPEED).f - el.force(u - e, u * 0, phi, SPEED).f) \
            / (2 * steps[j])
        # central differences: truncation ~ (h/delta)^2 ~ 1e-8, see test_flexible_rings
        err = np.abs((fd - out.K[:, :, j]) * length[None, :] * length[j]).max()
        assert err <= 1e-6 * scale, (j, err / scale)


def test_warm_start_round_trip_and_assembly():
    el = FlexibleRingBearingElement(BEARING, n=0, n_link=1)
    u = _u(el, 3, 2)
    first = el.force(u, u * 0, 0.3, SPEED)
    again = el.force(u, u * 0, 0.3, SPEED, internal=first.internal)
    assert np.allclose(again.f, first.f, rtol=0, atol=1e-12 * np.abs(first.f).max())
    st = el.state(u, 0.3, SPEED, internal=first.internal)
    assert st.iterations == 0 and st.inner is not None and st.inner.failures == 0
    # the assembly of nonlinear elements passes internal states through
    full_to_free = np.arange(12)
    asm = NonlinearAssembly.build([el], full_to_free, 2)
    res = asm.evaluate(u, u * 0, 0.3, SPEED)
    assert np.allclose(res.f, first.f) and res.internal[0].shape == (3, 24, 4)


def test_linearize_at_a_load_and_at_a_displacement():
    el = FlexibleRingBearingElement(BEARING, n=2, n_link=5, tag="B1")
    load = [5000.0, 0.0, 0.0, 0.0, 13.7]
    lin = linearize_at_load(el, load, speed=SPEED)
    eq = bearing_equilibrium(BEARING.at_speed(SPEED), load)
    assert isinstance(lin, BearingElement) and lin.n == 2 and lin.n_link == 5
    assert np.allclose(lin.stiffness_matrix, eq.stiffness, rtol=1e-12)
    lin_d = el.linearize(displacement=eq.displacement, speed=SPEED)
    assert np.allclose(lin_d.stiffness_matrix, eq.stiffness, rtol=1e-7,
                       atol=1e-9 * np.abs(eq.stiffness).max())
    with pytest.raises(TypeError, match="displacement"):  # a state, not a load
        el.linearize()
    with pytest.raises(ModelError, match=r"tangent must have shape \(5, 5\)"):
        el.linearize(displacement=np.zeros(5), tangent=np.eye(3))


@pytest.mark.parametrize("change, match", [
    (dict(shaft_radius=68.5e-3), r"shaft_radius R_s = 0.0685 m must be smaller than the "
                                 r"inner raceway radius"),
    (dict(shaft_radius=70e-3), "must be smaller than the inner raceway radius"),
    (dict(housing_radius=81.5e-3), r"housing_radius R_h = 0.0815 m must exceed the outer "
                                   r"raceway radius"),
    (dict(n_rollers=0), "n_rollers must be an integer >= 1"),
    (dict(slice_widths=(4e-3, 4e-3, 4e-3)), "slice widths add up to 0.012 m, not the "
                                            "effective length L = 0.016 m"),
    (dict(slice_widths=(8e-3, -1e-3, 9e-3)), "slice widths must be positive"),
    (dict(inner_ring=RingSection(4e-4, 1e-9, 0.06)), "give inner_ring or shaft_radius"),
    (dict(ring_width=None), "ring_width b is needed"),
    (dict(roller_radius=80e-3), "must be smaller than pitch_radius"),
    (dict(diametral_clearance=-40.0), "check the units"),
    (dict(E=-1.0), "E must be a positive"),
    (dict(tol=0.5), "tol must be in"),
])
def test_bad_input_names_the_culprit(change, match):
    with pytest.raises(ModelError, match=match) as info:
        FlexibleRingRollerBearing(**{**SEED, **change, "tag": "B7"})
    assert info.value.where == "FlexibleRingRollerBearing 'B7'"


def test_missing_ring_geometry_unless_rigid_and_bad_state_input():
    base = {k: v for k, v in SEED.items() if k not in ("shaft_radius", "housing_radius")}
    with pytest.raises(ModelError, match="inner ring needs shaft_radius"):
        FlexibleRingRollerBearing(**base)
    rigid = FlexibleRingRollerBearing(**base, rigid_rings=True)
    assert rigid.sections == (None, None)
    psi = BEARING.element_angles()
    with pytest.raises(ModelError, match=r"delta must have shape \(S, 5\)"):
        BEARING.state(np.zeros((2, 4)), psi)
    with pytest.raises(ModelError, match=r"internal must have shape \(S, 24, 4\)"):
        BEARING.state(np.zeros((2, 5)), psi, internal=np.zeros((2, 24, 3)))
    with pytest.raises(ModelError, match="speed must be finite"):
        BEARING.state(np.zeros((2, 5)), psi, speed=[1.0, 2.0, 3.0])
    with pytest.raises(ModelError, match="n_link must differ"):
        FlexibleRingBearingElement(BEARING, n=1, n_link=1)
    with pytest.raises(TypeError, match="unknown cage"):
        FlexibleRingRollerBearing(**SEED, cage="spinning")


def test_geometry_of_the_seed_case():
    """Seed 001 Fig. 3a / section 3.1: ring sections, roller mass, cage speed."""
    inner, outer = BEARING.sections
    assert inner is not None and outer is not None
    assert inner.area == pytest.approx((68.5e-3 - 54e-3) * 30e-3, rel=1e-12)
    assert outer.mean_radius == pytest.approx(0.5 * (81.5e-3 + 97e-3), rel=1e-12)
    assert outer.inertia == pytest.approx(30e-3 * 15.5e-3**3 / 12, rel=1e-12)
    assert BEARING.mass == pytest.approx(7850 * math.pi * 6.5e-3**2 * 16e-3, rel=1e-12)
    assert BEARING.centrifugal_cage_ratio == pytest.approx(0.5 * (1 - 6.5 / 75), rel=1e-12)
    assert BEARING.clearance == -20e-6 and BEARING.kappa == BEARING.centrifugal_cage_ratio
