"""ISO/TS 16281 reference life and its load-history form
(:mod:`rotorsim.elements.rolling.rating.iso16281`, :mod:`.load_history`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.rating.iso281 import BearingRating
from rotorsim.elements.rolling.rating.iso16281 import ReferenceRating, sjovall_integrals
from rotorsim.elements.rolling.rating.load_history import (
    RingDamage,
    combine_histories,
    history_from_arrays,
    history_life,
)
from rotorsim.errors import ModelError


def test_sjovall_integrals_match_the_published_load_zone_factors():
    """Half-loaded bearing (``eps = 1/2``): ``1/J_r = 4.37`` (point) and ``4.08`` (line),
    NSK's ``Q_max = 4.37 F_r / (Z cos a)`` and ``4.08 F_r / (Z cos a)`` (NSK technical
    catalogue E728, section 5.1); ``J_1 = 0.5625`` (point, Harris & Kotzalas Table 11.x).
    Published to 3-4 digits: compared to their last digit."""
    j_r, j_1, _ = sjovall_integrals(1.5, 3.0, 10 / 9)
    assert 1 / j_r == pytest.approx(4.37, abs=0.005)
    assert j_r == pytest.approx(0.2288, abs=5e-5)
    assert j_1 == pytest.approx(0.5625, abs=5e-5)
    assert 1 / sjovall_integrals(10 / 9, 4.0, 9 / 8)[0] == pytest.approx(4.08, abs=0.01)


def _uniform_reference(kind="ball", n=10):
    return ReferenceRating(BearingRating(kind, C=1e4), n, 8e-3, 50e-3,
                           n_laminae=1 if kind == "ball" else 5)


def test_equal_element_loads_give_the_capacity_law():
    """All elements equally loaded (pure axial load): both rings see ``Q`` at every point,
    so ``L_ring = (Q_c/Q)^p`` and ``L = (L_i^-e + L_e^-e)^(-1/e)`` exactly."""
    ref = _uniform_reference()
    q = 800.0
    life = ref.life(np.full((1, 10), q))
    qc = ref.nominal_capacities
    rings = (qc / q) ** 3
    assert life.ring_life[0] == pytest.approx(rings, rel=1e-12)
    assert life.L10r[0] == pytest.approx(np.sum(rings ** (-10 / 9)) ** -0.9, rel=1e-12)
    assert life.equivalent_load[0] == pytest.approx([q, q], rel=1e-12)


def test_laminae_of_a_uniform_line_load_give_the_whole_roller_life():
    """K laminae with ``q_ck = Q_c K^(-7/9)`` and ``q_k = Q / K``: the lamina sum equals
    the whole-roller life (the reason of the 7/9 exponent)."""
    whole = ReferenceRating(BearingRating("roller", C=3e4), 12, 8e-3, 50e-3, n_laminae=1)
    sliced = ReferenceRating(BearingRating("roller", C=3e4), 12, 8e-3, 50e-3, n_laminae=7)
    loads = np.linspace(0.0, 3000.0, 12)[None]
    a = whole.life(loads[..., None])
    b = sliced.life(np.repeat(loads[..., None] / 7, 7, axis=-1))
    assert b.L10r[0] == pytest.approx(a.L10r[0], rel=1e-12)


def test_rotating_ring_is_the_one_that_averages():
    ref = _uniform_reference()
    loads = np.zeros((1, 10))
    loads[0, :3] = [1000.0, 600.0, 600.0]
    inner = ref.life(loads, rotating_ring="inner")
    outer = ref.life(loads, rotating_ring="outer")
    u = loads[0] / ref.nominal_capacities[:, None]
    assert inner.ring_life[0, 0] == pytest.approx(1 / np.mean(u[0] ** 3), rel=1e-12)
    assert outer.ring_life[0, 0] == pytest.approx(np.mean(u[0] ** (10 / 3)) ** -0.9, rel=1e-12)
    assert outer.ring_life[0, 1] == pytest.approx(1 / np.mean(u[1] ** 3), rel=1e-12)


def test_history_of_a_fixed_load_reproduces_the_steady_rule():
    """A ball bearing under a fixed radial load, its cage turning for 40 shaft
    revolutions in 40 000 steps: the cell damage of the history gives the steady
    rotating/stationary rule within 0.5 % (the steady rule samples the load zone at the
    Z ball positions of one instant, the history at all positions: they differ by the
    varying compliance of a 9-ball bearing, measured 0.1 %)."""
    b = BallBearing.from_geometry(n_balls=9, pitch_diameter=39.04e-3, ball_diameter=7.94e-3,
                                  f_i=0.52, f_o=0.53)
    ref = ReferenceRating(BearingRating("ball", C=14e3), 9, 7.94e-3, 39.04e-3,
                          f_i=0.52, f_o=0.53)
    delta = np.array([12e-6, 0.0, 0.0, 0.0, 0.0])
    phi = np.linspace(0.0, 80.0 * math.pi, 40001)
    psi = b.element_angles(phi)
    st = b.state(np.broadcast_to(delta, (phi.size, 5)), psi)
    rings = np.stack([phi, np.zeros_like(phi)], axis=1)
    hist = history_from_arrays(ref, (st.element_load, st.contact_angle), psi, rings, b.kappa)
    steady = b.state(delta[None], b.element_angles(0.0))
    life = ref.life(steady.element_load, steady.contact_angle)
    assert hist.L10r[0] == pytest.approx(life.L10r[0], rel=5e-3)
    # a load turning with the shaft: the inner ring sees a fixed load zone
    turning = np.stack([12e-6 * np.cos(phi), 12e-6 * np.sin(phi)], axis=1)
    st = b.state(np.hstack([turning, np.zeros((phi.size, 3))]), psi)
    hist = history_from_arrays(ref, (st.element_load, st.contact_angle), psi, rings, b.kappa)
    life = ref.life(steady.element_load, steady.contact_angle, rotating_ring="outer")
    assert hist.L10r[0] == pytest.approx(life.L10r[0], rel=5e-3)


def test_coarse_steps_spread_the_damage_over_the_cells_they_sweep():
    """A sweep of several cells per step adds the same damage to each cell as a fine
    sampling (the overlap is exact for a density constant along the step)."""
    ref = _uniform_reference()
    u = np.full((3, 10, 2), 0.1)
    rings = np.zeros((3, 2))
    psi = np.linspace(0, 2 * math.pi, 10, endpoint=False)[None] + np.array([[0.0], [0.7],
                                                                              [1.4]])
    from rotorsim.elements.rolling.rating.load_history import ring_damage

    coarse = ring_damage(ref, u, psi, rings, 0.4, n_cells=90)
    fine_psi = np.linspace(0, 1.4, 141)[:, None] + psi[:1]
    fine = ring_damage(ref, np.full((141, 10, 2), 0.1), fine_psi, np.zeros((141, 2)), 0.4,
                       n_cells=90)
    np.testing.assert_allclose(coarse.damage, fine.damage, rtol=1e-9, atol=1e-15)


def test_duty_cycle_shares_and_errors():
    ref = _uniform_reference()
    a = RingDamage(np.full((1, 36, 2), 2e-3), 2.0)
    b = RingDamage(np.full((1, 36, 2), 4e-3), 1.0)
    mixed = history_life(ref, combine_histories([a, b], [0.25, 0.75]))
    expected = history_life(ref, RingDamage(np.full((1, 36, 2), 0.25e-3 + 3e-3), 1.0))
    assert mixed.L10r[0] == pytest.approx(expected.L10r[0], rel=1e-12)
    with pytest.raises(ModelError, match="shares"):
        combine_histories([a], [1.0, 2.0])
    with pytest.raises(ModelError, match="orbit"):
        history_from_arrays(ref, np.zeros((3, 10)), np.zeros((3, 10)), np.zeros((3, 2)), 0.0)
    with pytest.raises(ModelError, match=">= 0"):
        ref.life(-np.ones((1, 10)))
    with pytest.raises(ModelError, match="rotating_ring"):
        ref.life(np.ones((1, 10)), rotating_ring="cage")


def test_history_with_the_outer_ring_turning():
    """Rings at speed ratios (0, 1) (the outer ring turns with the shaft angle, the inner
    stands; an inter-shaft or hub bearing) under a load fixed in space: the outer ring now
    sees every load and the inner a fixed load zone, the steady rule with
    ``rotating_ring="outer"`` (within 0.5 %, as the inner-ring case above)."""
    from rotorsim.analyses.statics.bearing_history import history_life_result
    from rotorsim.elements.rolling.rating.options import RatingOptions

    b = BallBearing.from_geometry(n_balls=9, pitch_diameter=39.04e-3, ball_diameter=7.94e-3,
                                  f_i=0.52, f_o=0.53)

    class OuterTurning:  # the two speed ratios of a RollingBearing element
        bearing = b
        inner_speed_ratio, outer_speed_ratio = 0.0, 1.0

        def relative(self, u):
            return u

    delta = np.array([12e-6, 0.0, 0.0, 0.0, 0.0])
    phi = np.linspace(0.0, 80.0 * math.pi, 40001)
    hist = history_life_result(OuterTurning(), np.broadcast_to(delta, (phi.size, 5)), phi,
                               source="test", options=RatingOptions(C=14e3))
    ref = ReferenceRating(BearingRating("ball", C=14e3), 9, 7.94e-3, 39.04e-3,
                          f_i=0.52, f_o=0.53)
    steady = b.state(delta[None], b.element_angles(0.0))
    life = ref.life(steady.element_load, steady.contact_angle, rotating_ring="outer")
    assert hist.L10r == pytest.approx(float(life.L10r[0]), rel=5e-3)
    assert hist.stats["revolutions"] == pytest.approx(40.0)
