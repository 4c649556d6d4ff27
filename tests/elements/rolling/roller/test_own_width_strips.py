"""Slices of a roller by strips of their own Hertz width, against the 2-D half-space."""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.elements.rolling.roller.half_space import HalfSpaceLineContact
from rotorsim.elements.rolling.roller.own_width_strips import (
    own_width_slice_loads,
    strip_average_compliance,
)
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    slice_centres,
)
from rotorsim.errors import ModelError

E_STAR, RADIUS, LENGTH, LOAD = 1.13e11, 0.005, 0.02, 10e3


@pytest.mark.parametrize("crown", ["straight", "lundberg", "circular"])
def test_tilted_roller_against_the_two_dimensional_half_space(crown):
    # a tilted roller at a given load: load centre e = M/Q and slice loads against the 2-D
    # half-space (slices x strips, HalfSpaceLineContact). Measured (K = 20, tilt 4e-4):
    # e 1.014, 1.014, 1.012 of the 2-D e (straight, Lundberg, circular), slice loads within
    # 1.0 %, 0.7 %, 0.8 % of the largest; the fixed-width centre-line strips of eq 2.29 give
    # 0.912, 0.928, 0.959 (tests/elements/rolling/roller/test_influence_model.py). Bounds:
    # 3 % on e and 2 % on the loads, the 2-D grid's own convergence being 0.1 %.
    profile = {"straight": CircularCrown(0.0),
               "lundberg": LogarithmicProfile.lundberg(LOAD, LENGTH, 2 * E_STAR),
               "circular": CircularCrown(10e-6, 4e-3)}[crown]
    k, tilt = 20, 4e-4
    two_d = HalfSpaceLineContact.for_load(
        LOAD, LENGTH, RADIUS, E_STAR, None if crown == "straight" else profile, n_slices=k,
        n_strips=12, width_factor=2.0).solve_load(LOAD, tilt)
    assert not two_d.truncated
    xi = slice_centres(k)
    q, iterations = own_width_slice_loads(tilt * xi * LENGTH - profile.drop(xi, LENGTH),
                                          LOAD, LENGTH, (RADIUS,), E_STAR)
    assert q.sum() == pytest.approx(LOAD, rel=1e-12)
    assert (q >= 0.0).all() and iterations < 20
    e_ratio = float(q @ xi) * LENGTH / two_d.moment
    assert abs(e_ratio - 1.0) < 0.03
    assert np.abs(q - two_d.slice_load).max() < 0.02 * two_d.slice_load.max()


def test_straight_roller_edge_and_symmetry():
    # untilted straight roller: even loads with the edge rise of the 2-D half-space (end
    # slice 1.338 of the mean at K = 20; own-width strips 1.346)
    k = 20
    q, _ = own_width_slice_loads(np.zeros(k), LOAD, LENGTH, (RADIUS,), E_STAR)
    np.testing.assert_allclose(q, q[::-1], rtol=1e-9)
    two_d = HalfSpaceLineContact.for_load(LOAD, LENGTH, RADIUS, E_STAR, n_slices=k,
                                          n_strips=14).solve_load(LOAD)
    assert q[0] * k / LOAD == pytest.approx(two_d.slice_load[0] * k / LOAD, abs=0.02)
    # the constant part of the deflection is the unknown approach: it does not matter
    q2, _ = own_width_slice_loads(np.full(k, 3e-6), LOAD, LENGTH, (RADIUS,), E_STAR)
    np.testing.assert_allclose(q2, q, rtol=1e-9)


def test_equal_width_compliance_is_symmetric_toeplitz():
    # the general (per-slice width) path at equal widths: symmetric, Toeplitz, positive
    # definite, and equal to the one-row shortcut of a scalar width
    y = slice_centres(8) * LENGTH
    c = strip_average_compliance(y, LENGTH / 8, np.full(8, 1.7e-4), E_STAR)
    np.testing.assert_allclose(c, c.T, rtol=1e-12)
    np.testing.assert_allclose(np.diag(c, 1), c[0, 1], rtol=1e-12)
    assert np.all(np.linalg.eigvalsh(c) > 0.0)
    np.testing.assert_allclose(strip_average_compliance(y, LENGTH / 8, 1.7e-4, E_STAR), c,
                               rtol=1e-12)


def test_bad_input_is_refused():
    with pytest.raises(ModelError, match="load"):
        own_width_slice_loads(np.zeros(5), -1.0, LENGTH, (RADIUS,), E_STAR)
    with pytest.raises(ModelError, match="deflection"):
        own_width_slice_loads(np.zeros((2, 5)), LOAD, LENGTH, (RADIUS,), E_STAR)
