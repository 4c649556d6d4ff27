"""Issue 18 item 8, conventions: diameters and either clearance for every bearing class,
the ISO/TS 16281 spring constant as an option of ``from_geometry`` and of model files, and
``roller_diameter`` only where it is used."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model

GEOMETRY = {"n_balls": 7, "pitch_diameter": 43.5e-3, "ball_diameter": 11.5e-3, "f_i": 0.52,
            "f_o": 0.53}


def test_the_iso16281_spring_constant_is_an_option_of_from_geometry():
    iso = rs.BallBearing.from_geometry(**GEOMETRY, E_ball=2.1e11, method="iso16281")
    assert iso.Kn == rs.iso16281_ball_constant(11.5e-3, 43.5e-3, 0.0, 0.52, 0.53, E=2.1e11)
    exact = rs.BallBearing.from_geometry(**GEOMETRY, E_ball=2.1e11)
    # 1.48 / (pi / sqrt(4.5)), to the solvers' 1e-10 (validation case 34)
    assert iso.Kn / exact.Kn == pytest.approx(1.48 / (math.pi / math.sqrt(4.5)), rel=1e-9)
    with pytest.raises(ModelError, match="one material"):
        rs.BallBearing.from_geometry(**GEOMETRY, E_ring=1.9e11, method="iso16281")


_BALL = """
[model]
name = "m"

[[disks]]
node = 0
m = "10 kg"
Id = "0.1 kg*m^2"
Ip = "0.2 kg*m^2"

[[rolling_bearings]]
type = "ball"
node = 0
n_balls = 7
pitch_diameter = "43.5 mm"
ball_diameter = "11.5 mm"
f_i = 0.52
f_o = 0.53
{extra}
"""


def test_the_spring_constant_key_of_model_files(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(_BALL.format(extra='spring_constant = "iso16281"'))
    kn = load_model(path).rolling_bearings[0].bearing.Kn
    assert kn == rs.BallBearing.from_geometry(**GEOMETRY, method="iso16281").Kn
    path.write_text(_BALL.format(extra='spring_constant = "iso16281"\nKn = "9e9 N/m^1.5"'))
    with pytest.raises(ModelError, match="spring_constant"):
        load_model(path)


def test_the_flexible_ring_bearing_takes_diameters_and_either_clearance():
    radii = rs.FlexibleRingRollerBearing(n_rollers=24, pitch_radius=0.075,
                                         roller_radius=0.0065, effective_length=0.016,
                                         diametral_clearance=-40e-6, shaft_radius=0.054,
                                         housing_radius=0.097, ring_width=0.030)
    for clearance in ({"diametral_clearance": -40e-6}, {"radial_clearance": -20e-6}):
        diam = rs.FlexibleRingRollerBearing.from_diameters(
            n_rollers=24, pitch_diameter=0.15, roller_diameter=0.013, effective_length=0.016,
            shaft_diameter=0.108, housing_diameter=0.194, ring_width=0.030, **clearance)
        assert (diam.pitch_radius, diam.roller_radius, diam.shaft_radius,
                diam.housing_radius) == pytest.approx((0.075, 0.0065, 0.054, 0.097))
        assert diam.diametral_clearance == pytest.approx(-40e-6, rel=1e-12)
        d = [[20e-6, 0.0, 0.0, 0.0, 0.0]]
        np.testing.assert_allclose(diam.state(d, diam.element_angles()).force,
                                   radii.state(d, radii.element_angles()).force, rtol=1e-9)
    with pytest.raises(ModelError, match="not both"):
        rs.FlexibleRingRollerBearing.from_diameters(
            n_rollers=24, pitch_diameter=0.15, roller_diameter=0.013, effective_length=0.016,
            diametral_clearance=1e-6, radial_clearance=5e-7)


def test_roller_diameter_only_where_it_is_used():
    """Statics do not need the diameter (ISO Kn depends on L only): the same equilibrium, to
    the Newton tolerance (the solver scales deflections by the diameter, or by L without
    it); every use of the diameter names it."""
    full = rs.RollerBearing(14, 65e-3, 10e-3, 9.6e-3, model="slices", n_slices=10,
                            diametral_clearance=10e-6)
    bare = rs.RollerBearing(n_rollers=14, pitch_diameter=65e-3, effective_length=9.6e-3,
                            model="slices", n_slices=10, diametral_clearance=10e-6)
    load = [8000.0, 0.0, 0.0, 0.0, 2.0]
    a, b = rs.bearing_equilibrium(full, load), rs.bearing_equilibrium(bare, load)
    scale = np.abs(a.displacement).max()
    np.testing.assert_allclose(b.displacement, a.displacement, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(b.stiffness, a.stiffness, rtol=1e-7,
                               atol=1e-9 * np.abs(a.stiffness).max())
    state = (b.displacement[None], b.element_angles[None])
    for use, call in (("cage ratio", lambda: bare.element_angles(0.3)),
                      ("ratings", lambda: rs.bearing_life(bare, load)),
                      ("contact pressures", lambda: rs.contact_pressures(bare, *state))):
        with pytest.raises(ModelError, match=f"roller_diameter is needed for .*{use}"):
            call()
    fixed = rs.RollerBearing(n_rollers=14, pitch_diameter=65e-3, effective_length=9.6e-3,
                             cage="fixed")
    assert fixed.kappa == 0.0 and fixed.element_angles(0.3).shape == (1, 14)
    with pytest.raises(ModelError, match="effective_length is required"):
        rs.RollerBearing(n_rollers=14, pitch_diameter=65e-3, roller_diameter=10e-3)


def test_a_model_file_roller_without_its_diameter_is_linearised(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(_BALL.format(extra="").replace(
        'type = "ball"', 'type = "roller"').replace("n_balls = 7", "n_rollers = 14").replace(
        'ball_diameter = "11.5 mm"\nf_i = 0.52\nf_o = 0.53\n',
        'effective_length = "9.6 mm"\ndiametral_clearance = "10 um"\n'))
    model = load_model(path)
    assert model.rolling_bearings[0].bearing.roller_diameter is None
    assert model.linearized().bearings[0].stiffness_matrix[0, 0] > 0.0


def test_a_model_file_sets_the_influence_models_reference_pressure(tmp_path):
    """``model = "influence"`` with its strip width's reference pressure from a model file,
    kept by a save and reload; a non-positive pressure is refused by key."""
    from rotorsim.io.model_file import save_model

    path = tmp_path / "m.toml"
    roller = _BALL.format(extra="").replace('type = "ball"', 'type = "roller"').replace(
        "n_balls = 7", "n_rollers = 14").replace(
        'ball_diameter = "11.5 mm"\nf_i = 0.52\nf_o = 0.53\n',
        'roller_diameter = "10 mm"\neffective_length = "9.6 mm"\n'
        'diametral_clearance = "10 um"\nmodel = "influence"\ninfluence_pressure = "2 GPa"\n')
    path.write_text(roller)
    bearing = load_model(path).rolling_bearings[0].bearing
    assert bearing.model == "influence" and bearing.influence_pressure == 2e9
    again = load_model(save_model(load_model(path), tmp_path / "saved.toml"))
    assert again.rolling_bearings[0].bearing.influence_pressure == 2e9
    path.write_text(roller.replace('"2 GPa"', '"-1 GPa"'))
    with pytest.raises(ModelError, match="influence_pressure"):
        load_model(path)
