"""ISO 281 ratings, X/Y tables and the life modification factor
(:mod:`rotorsim.elements.rolling.rating.iso281`, :mod:`.life_factor`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.elements.rolling.rating import iso281
from rotorsim.elements.rolling.rating.iso281 import (
    BearingRating,
    dynamic_load_rating,
    fc_factor,
)
from rotorsim.elements.rolling.rating.life_factor import (
    life_modification_factor,
    reliability_factor,
)
from rotorsim.errors import ModelError


def test_roller_fc_table_is_the_closed_form_of_iso_tr_1281_1():
    """Table 7 equals ``207.9 lambda nu gamma^(2/9) ...`` with ``lambda nu = 0.83``
    (ISO/TR 1281-1, Harris & Kotzalas ch. 11): a check of the transcription. The table is
    printed to 0.1, so its entries may differ by half a unit of that digit (0.05)."""
    g = iso281._GAMMA_FC_ROLLER
    closed = (207.9 * 0.83 * g ** (2 / 9) * (1 - g) ** (29 / 27) / (1 + g) ** 0.25
              * (1 + (1.04 * ((1 - g) / (1 + g)) ** (143 / 108)) ** 4.5) ** (-2 / 9))
    np.testing.assert_allclose(iso281._FC_ROLLER, closed, rtol=0, atol=0.05 + 1e-9)


def test_ball_fc_table_is_smooth_against_the_lundberg_palmgren_shape():
    """Table 2 over the Lundberg-Palmgren expression (``f_i = 0.52``, ``f_e = 0.53``) is a
    smooth function of gamma (the reduction factor ISO folds in): no entry jumps, so no
    entry was mistyped. The entries are rounded to 0.1 (at most 0.05 / 48.4 = 0.1 % each),
    so a second difference of the ratio can reach 4 x 0.1 %; a digit mistyped by 1 in the
    units (2 % of an entry) gives at least 2 % there. Bound: 0.5 %."""
    g, table = iso281._GAMMA_FC, iso281._FC_BALL
    fi, fe = 0.52, 0.53
    shape = ((1 + (1.04 * ((1 - g) / (1 + g)) ** 1.72
                   * (fi * (2 * fe - 1) / (fe * (2 * fi - 1))) ** 0.41) ** (10 / 3)) ** -0.3
             * g**0.3 * (1 - g) ** 1.39 / (1 + g) ** (1 / 3) * (2 * fi / (2 * fi - 1)) ** 0.41)
    ratio = table / shape
    split = int(np.flatnonzero(np.isclose(g, 0.10))[0])  # steps 0.01 up to 0.10, then 0.02
    for part in (ratio[: split + 1], ratio[split:]):
        assert np.abs(np.diff(part, 2)).max() < 0.005 * ratio.mean()


def test_interpolation_and_range():
    assert fc_factor("ball", 0.21) == pytest.approx(59.75)
    with pytest.raises(ModelError, match="outside the ISO table"):
        fc_factor("ball", 0.45)
    with pytest.raises(ModelError, match="unknown bearing kind 'needle'"):
        fc_factor("needle", 0.1)


def test_large_balls_use_the_d_power_1_4_branch():
    """Above 25.4 mm, ``C = 3.647 b_m f_c ... D^1.4``: continuous at 25.4 mm within the
    rounding of the constant 3.647 = 25.4^0.4 (to 4 digits)."""
    kw = {"n_elements": 10, "pitch_diameter": 200e-3}
    below = dynamic_load_rating("ball", element_diameter=25.4e-3 - 1e-9, **kw)
    above = dynamic_load_rating("ball", element_diameter=25.4e-3 + 1e-9, **kw)
    assert above == pytest.approx(below, rel=2e-4)


def test_equivalent_load_tables():
    r = BearingRating("ball", C=14000.0, C0=7800.0, f0=14.0)
    # below e: P = F_r; above e: X = 0.56 with Y interpolated
    assert float(r.equivalent_load(1000.0, 100.0)) == 1000.0
    rel = 14.0 * 500.0 / 7800.0
    y = np.interp(rel, iso281._F0FA_C0, iso281._Y_DEEP)
    assert float(r.equivalent_load(1000.0, 500.0)) == pytest.approx(560.0 + y * 500.0)
    ac = BearingRating("ball", C=1e4, contact_angle=math.radians(40.0))
    assert float(ac.equivalent_load(1000.0, 2000.0)) == pytest.approx(0.35e3 + 0.57 * 2e3)
    taper = BearingRating("roller", C=1e4, contact_angle=math.radians(15.0))
    e = 1.5 * math.tan(math.radians(15.0))
    assert float(taper.equivalent_load(1000.0, 1000.0 * e * 1.01)) == pytest.approx(
        400.0 + 0.4 / math.tan(math.radians(15.0)) * 1010.0 * e)
    with pytest.raises(ModelError, match="no X, Y table"):
        BearingRating("ball", C=1e4, contact_angle=math.radians(10.0)).equivalent_load(1, 1)
    with pytest.raises(ModelError, match=">= 0"):
        r.equivalent_load(-1.0, 0.0)


def test_bad_ratings_are_refused():
    with pytest.raises(ModelError, match="C must be positive"):
        BearingRating("ball", C=-5.0)
    with pytest.raises(ModelError, match="unknown bearing kind"):
        BearingRating("thrust", C=5.0)
    with pytest.raises(ModelError, match="effective_length is required"):
        dynamic_load_rating("roller", n_elements=12, element_diameter=0.01,
                            pitch_diameter=0.06)
    with pytest.raises(ModelError, match="45 deg"):
        dynamic_load_rating("ball", n_elements=12, element_diameter=0.01,
                            pitch_diameter=0.06, contact_angle=1.2)


def test_life_modification_factor_limits():
    """``a_ISO`` is 0.1 [1 - ...]^(-c6): 0.1 at e_C = 0 (no fatigue load limit effect),
    capped at 50, monotone in the load."""
    assert float(life_modification_factor("ball", 1.0, 0.0, 300.0, 1000.0)) == \
        pytest.approx(0.1)
    assert float(life_modification_factor("roller", 4.0, 1.0, 3e4, 1000.0)) == 50.0
    values = life_modification_factor("ball", 2.0, 0.5, 500.0, [500.0, 1000.0, 4000.0])
    assert np.all(np.diff(values) < 0)
    with pytest.raises(ModelError, match="kappa"):
        life_modification_factor("ball", 0.05, 0.5, 500.0, 1000.0)
    with pytest.raises(ModelError, match="e_C"):
        life_modification_factor("ball", 1.0, 1.5, 500.0, 1000.0)
    assert reliability_factor(95.0) == 0.64
    with pytest.raises(ModelError, match="reliability"):
        reliability_factor(80.0)
