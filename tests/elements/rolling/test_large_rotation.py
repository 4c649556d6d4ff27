"""Large displacements and rotations of a 2-node bearing (seed 001 section 2.4)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import rotorsim as rs
from rotorsim.elements.rolling.large_rotation import (
    LargeRotationBearing,
    relative_motion,
    rotation_tensor,
    tangent_tensor,
)
from rotorsim.errors import ModelError

BALL = rs.BallBearing(n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794, Kn=8.5e9,
                      f_i=0.52, f_o=0.52, diametral_clearance=4e-6)


def _element(damping=False):
    kw = dict(contact_damping="proportional", damping_factor=2e-5) if damping else {}
    return rs.RollingBearing(BALL, n=0, n_link=1, **kw)


def test_rotation_tensor_matches_scipy_and_gamma_is_its_tangent():
    rng = np.random.default_rng(3)
    theta = rng.normal(size=(5, 3)) * [[0.1], [1.0], [2.0], [1e-5], [3.0]]
    np.testing.assert_allclose(rotation_tensor(theta),
                               Rotation.from_rotvec(theta).as_matrix(), atol=1e-14)
    d = rng.normal(size=3) * 1e-7  # delta(Q) Q^T = skew(Gamma delta theta)
    for th in theta:
        dQ = rotation_tensor(th + d) - rotation_tensor(th - d)
        W = dQ @ rotation_tensor(th).T / 2
        w = np.array([W[2, 1], W[0, 2], W[1, 0]])
        np.testing.assert_allclose(w, tangent_tensor(th) @ d, rtol=1e-6, atol=1e-18)


def test_small_rotations_give_the_small_rotation_element():
    rng = np.random.default_rng(0)
    y = np.zeros((4, 12))
    y[:, 0:3] = rng.normal(size=(4, 3)) * 5e-6
    y[:, 3:5] = rng.normal(size=(4, 2)) * 1e-6
    y[:, 6:9] = rng.normal(size=(4, 3)) * 5e-6
    y[:, 9:11] = rng.normal(size=(4, 2)) * 1e-6
    small = _element().force(y, 0 * y, 0.3, 100.0)
    big = LargeRotationBearing(_element()).force(y, 0 * y, 0.3, 100.0)
    keep = [0, 1, 2, 3, 4, 6, 7, 8, 9, 10]
    scale = np.abs(small.f).max()
    np.testing.assert_allclose(big.f[:, keep], small.f[:, keep], atol=2e-4 * scale)


@pytest.mark.parametrize("damping", [False, True])
def test_tangents_are_the_derivatives_of_the_force(damping):
    rng = np.random.default_rng(1)
    el = LargeRotationBearing(_element(damping))
    y = np.zeros((1, 12))
    y[0, 3:6] = [0.4, -0.7, 1.1]  # a large rotation of node A
    y[0, 9:12] = [0.4, -0.7, 1.1] + rng.normal(size=3) * 2e-5
    y[0, 0:3] = rng.normal(size=3) * 1e-3
    local = rotation_tensor(y[0, 3:6]) @ np.array([3e-6, -8e-6, 1e-6])
    y[0, 6:9] = y[0, 0:3] + local  # outer ring displaced in A's frame
    v = rng.normal(size=(1, 12)) * 1e-3 if damping else np.zeros((1, 12))
    out = el.force(y, v, 0.2, 300.0)
    for j in range(12):
        h = 1e-9 if j % 6 < 3 else 1e-8
        e = np.zeros((1, 12))
        e[0, j] = h
        fd = (el.force(y + e, v, 0.2, 300.0).f - el.force(y - e, v, 0.2, 300.0).f) / (2 * h)
        np.testing.assert_allclose(out.K[0, :, j], fd[0], rtol=1e-5,
                                   atol=1e-6 * np.abs(out.K).max())
        if damping:
            fdv = (el.force(y, v + e, 0.2, 300.0).f - el.force(y, v - e, 0.2, 300.0).f) / (2 * h)
            np.testing.assert_allclose(out.C[0, :, j], fdv[0], rtol=1e-5,
                                       atol=1e-6 * np.abs(out.C).max())


def test_a_rigid_rotation_of_the_assembly_leaves_the_bearing_state_unchanged():
    rng = np.random.default_rng(2)
    y = np.zeros((1, 12))
    y[0, 0:3] = [1e-5, -2e-5, 0.0]
    y[0, 6:9] = [-3e-6, 4e-6, 1e-6]
    y[0, 3:6] = rng.normal(size=3) * 1e-5
    y[0, 9:12] = rng.normal(size=3) * 1e-5
    R = Rotation.from_rotvec([0.9, -0.4, 1.3]).as_matrix()
    moved = y.copy()
    for a, t in ((0, 3), (6, 9)):
        moved[0, a:a + 3] = R @ y[0, a:a + 3]  # both nodes sit at the origin
        moved[0, t:t + 3] = Rotation.from_matrix(R @ rotation_tensor(y[0, t:t + 3])).as_rotvec()
    np.testing.assert_allclose(relative_motion(moved)[0], relative_motion(y)[0], atol=1e-14)
    el = LargeRotationBearing(_element())
    f, g = el.force(y, 0 * y, 0.0, 0.0).f[0], el.force(moved, 0 * y, 0.0, 0.0).f[0]
    np.testing.assert_allclose(g[0:3], R @ f[0:3], atol=1e-9 * np.abs(f).max())
    np.testing.assert_allclose(g[6:9], R @ f[6:9], atol=1e-9 * np.abs(f).max())


def test_a_bearing_to_ground_is_refused():
    with pytest.raises(ModelError, match="n_link"):
        LargeRotationBearing(rs.RollingBearing(BALL, n=0))


def test_flexible_ring_element_in_large_rotations_has_an_exact_tangent():
    from rotorsim.elements.rolling.flexible_ring.bearing import FlexibleRingRollerBearing

    ring = FlexibleRingRollerBearing(n_rollers=24, pitch_radius=75e-3, roller_radius=6.5e-3,
                                     effective_length=16e-3, shaft_radius=54e-3,
                                     housing_radius=97e-3, ring_width=30e-3,
                                     diametral_clearance=-40e-6, n_slices=4)
    big = LargeRotationBearing(rs.FlexibleRingBearingElement(ring, n=0, n_link=1))
    y = np.zeros((1, 12))
    y[0, 3:6] = y[0, 9:12] = [0.3, 0.5, -0.2]
    y[0, 6:9] = rotation_tensor(y[0, 3:6]) @ np.array([-4e-6, 2e-6, 0.0])
    out = big.force(y, 0 * y, 0.0, 1000.0)
    for j in (0, 1, 4, 6, 10):
        h = 1e-9 if j % 6 < 3 else 1e-8
        e = np.zeros((1, 12))
        e[0, j] = h
        fd = (big.force(y + e, 0 * y, 0.0, 1000.0).f
              - big.force(y - e, 0 * y, 0.0, 1000.0).f) / (2 * h)
        np.testing.assert_allclose(out.K[0, :, j], fd[0], rtol=0,
                                   atol=1e-7 * np.abs(out.K).max())
