"""``RollerBearing(slice_model="influence")``: half-space slice loads normalised to the
bearing's own roller loads (rotorsim.elements.rolling.roller.slice_influence)."""

from __future__ import annotations

import dataclasses
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rotorsim.elements.rolling.rating.hertz_pressure import contact_pressures
from rotorsim.elements.rolling.rating.iso16281 import lamina_loads
from rotorsim.elements.rolling.rating.options import RatingOptions
from rotorsim.elements.rolling.rating.rated_bearing import RatedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.half_space import (
    HalfSpaceLineContact,
    roller_pressure_field,
)
from rotorsim.elements.rolling.roller.profile import LogarithmicProfile
from rotorsim.elements.rolling.roller.slice_influence import influence_slice_loads
from rotorsim.io.model_file import load_model, model_from_dict, save_model

E_STAR = 1.13e11
BASE = RollerBearing(n_rollers=14, pitch_diameter=0.0425, roller_diameter=0.0075,
                     effective_length=0.0075, model="slices", n_slices=20)
INFL = dataclasses.replace(BASE, slice_model="influence")
DELTA = np.array([[20e-6, 5e-6, 0.0, 1e-4, 0.0], [15e-6, 0.0, 0.0, 0.0, 0.0]])
PSI = np.tile(BASE.element_angles(), (2, 1))


def test_default_is_the_independent_law():
    assert BASE.slice_model == "independent"
    dk = np.maximum(BASE.slice_deflections(DELTA, PSI), 0.0)
    expected = BASE.kn / BASE.n_slices * dk**BASE.exponent
    np.testing.assert_array_equal(BASE.slice_loads(DELTA, PSI), expected)
    np.testing.assert_array_equal(lamina_loads(BASE, DELTA, PSI), expected)


def test_influence_keeps_roller_loads_and_raises_the_ends():
    q_inf, q_ind = INFL.slice_loads(DELTA, PSI), BASE.slice_loads(DELTA, PSI)
    # normalisation (seed 002 section 2.3.2): the roller loads of the Kn law, to rounding
    np.testing.assert_allclose(q_inf.sum(axis=-1), q_ind.sum(axis=-1), rtol=1e-12)
    straight = q_inf[1, 0]  # roller 0 of the pure radial case: uniform deflection
    assert straight[0] > 1.2 * straight[10] and straight[-1] == pytest.approx(straight[0])
    loads_inf, loads_ind = INFL.roller_loads(DELTA, PSI), BASE.roller_loads(DELTA, PSI)
    np.testing.assert_allclose(loads_inf.load, loads_ind.load, rtol=1e-12)
    assert loads_inf.slice_load is not None
    # a tilted roller: the half-space concentrates its load further at the loaded end
    assert abs(loads_inf.eccentricity[0, 1]) > 1.1 * abs(loads_ind.eccentricity[0, 1])
    # forces (statics, transients) are the independent law's
    np.testing.assert_array_equal(INFL.state(DELTA, PSI).force, BASE.state(DELTA, PSI).force)


@pytest.mark.parametrize("crowned", [False, True])
def test_slice_model_against_the_sliced_half_space(crowned):
    # the bearing's 1-D slice model (uniform Hertz-width strips read on the centre line,
    # seed 002 eq 2.29) against the 2-D half-space solution (slices x strips) of the same
    # roller: the same load shape to 7 % of the largest slice load (measured 5.6 %
    # straight, 0.6 % Lundberg)
    q, length, radius, k = 10_000.0, 0.02, 0.005, 20
    profile = LogarithmicProfile.lundberg(q, length, 2 * E_STAR) if crowned else None
    c = HalfSpaceLineContact.for_load(q, length, radius, E_STAR, profile, n_slices=k,
                                      n_strips=12)
    s = c.solve_load(q)
    drop = c.profile.drop(c.y / length, length)
    one_d = influence_slice_loads((s.approach - drop)[None], 1e9, 10 / 9, length, (radius,),
                                  E_STAR)[0]
    a, b = one_d / one_d.sum(), s.slice_load / s.load
    assert np.abs(a - b).max() < (0.07 if not crowned else 0.01) * b.max()
    assert (a[0] > a[k // 2]) != crowned


def test_life_and_pressures_use_the_influence_slices():
    options = RatingOptions()
    life_ind = RatedBearing(BASE, options).life(DELTA, PSI).L10r
    life_inf = RatedBearing(INFL, options).life(DELTA, PSI).L10r
    assert (life_inf < life_ind).all()  # edge-loaded laminae shorten the life
    dens_inf = RatedBearing(INFL, options).damage_density(DELTA, PSI)[1]
    assert dens_inf[1, 0, 0] > dens_inf[1, 0, 10]
    p_ind = contact_pressures(BASE, DELTA, PSI).max_pressure
    p_inf = contact_pressures(INFL, DELTA, PSI).max_pressure
    assert p_inf.max() > p_ind.max()


def test_unknown_slice_model_is_rejected():
    with pytest.raises(TypeError, match="slice_model"):
        dataclasses.replace(BASE, slice_model="winkler")


def test_model_file_key_round_trips(tmp_path):
    models = Path(__file__).resolve().parents[4] / "models"
    with open(models / "rolling_tapered.toml", "rb") as stream:
        data = tomllib.load(stream)
    data["rolling_bearings"][0]["slice_model"] = "influence"
    model = model_from_dict(data)
    assert model.rolling_bearings[0].bearing.slice_model == "influence"
    assert model.rolling_bearings[1].bearing.bearing.slice_model == "independent"
    again = load_model(save_model(model, tmp_path / "copy.toml"))
    assert again.rolling_bearings[0].bearing.slice_model == "influence"


def test_pressure_field_of_a_tilted_roller():
    crowned = dataclasses.replace(BASE, profile=LogarithmicProfile.lundberg(
        2000.0, BASE.effective_length, 2 * E_STAR))
    tilt = np.array([20e-6, 0.0, 0.0, 0.0, 4e-4])  # ry: roller 0 at psi = 0 tilted
    dk = crowned.slice_deflections(tilt[None], PSI[:1])[0, 0]
    s = roller_pressure_field(crowned, tilt, PSI[0], 0, race="outer")
    assert s.load == pytest.approx(crowned.roller_loads(tilt[None], PSI[:1]).load[0, 0],
                                   rel=1e-12)
    assert s.tilt == pytest.approx((dk[-1] - dk[0]) / (crowned.effective_length * 19 / 20),
                                   rel=1e-9)  # the fit of the linear part is exact
    assert np.argmax(s.peak) == crowned.n_slices - 1 and not s.truncated
    with pytest.raises(TypeError, match="race"):
        roller_pressure_field(crowned, tilt, PSI[0], 0, race="middle")
