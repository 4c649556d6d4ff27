"""Argument checks and result notes of the linear analyses (issue 12)."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.linear.critical_speed_map import critical_speed_map
from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.errors import ModelError
from rotorsim.model.lines import ShaftLine

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def small_rotor(n_elements: int = 4, k: float = 1e6) -> rs.Rotor:
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=STEEL)
             for _ in range(n_elements)]
    return rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=k),
                                rs.BearingElement(n=n_elements, kxx=k)])


VERBS = {
    "modal": lambda r, n: rs.modal(r, 0.0, n),
    "campbell": lambda r, n: rs.campbell(r, [0.0, 100.0], n),
    "critical_speeds": lambda r, n: critical_speeds(r, 1, n),
    "critical_speed_map": lambda r, n: critical_speed_map(r, num_points=2, num_modes=n),
}


@pytest.mark.parametrize("verb", sorted(VERBS))
@pytest.mark.parametrize("num_modes", [2.5, 0, -3, True, "4", None, np.float64(2.0)])
def test_num_modes_must_be_a_positive_integer(verb, num_modes):
    # 2.5 used to reach ARPACK and raise SystemError from its Fortran wrapper
    with pytest.raises(ModelError, match=f"{verb}: num_modes must be a positive integer"):
        VERBS[verb](small_rotor(), num_modes)


def test_numpy_integer_num_modes_is_accepted():
    assert rs.modal(small_rotor(), 0.0, np.int64(3)).num_modes == 3


@pytest.mark.parametrize("sparse", [False, True])
def test_num_modes_above_what_exists_is_noted(sparse):
    rotor = small_rotor(2)  # 18 DOFs, 2 rigid: 16 elastic modes
    result = rs.modal(rotor, 0.0, 100, sparse=sparse)
    assert result.num_modes == 16 and result.rigid_body_modes == 2
    assert len(result.notes) == 1
    assert "num_modes = 100 asked, but the model has only 16 elastic modes" in result.notes[0]
    assert rs.modal(rotor, 0.0, 16, sparse=sparse).notes == ()


def test_penalty_modes_left_out_are_noted():
    """With 1e20 N/m supports the dense solver cannot resolve the 4 support (penalty) mode
    pairs near sqrt(1e20 / m): asking for every mode says which were left out."""
    result = rs.modal(small_rotor(2, k=1e20), 0.0, 100, sparse=False)
    assert result.num_modes == 12  # 16 elastic minus the 4 penalty modes at the supports
    assert "only 12 elastic modes are resolved: 8 eigenvalues" in result.notes[0]
    assert np.all(result.damping_ratio > -1e-9)  # none of them shows up as unstable


def test_campbell_notes_missing_tracks():
    result = rs.campbell(small_rotor(2), [0.0, 50.0], num_modes=20)
    assert np.isnan(result.wd[:, 16:]).all() and np.isfinite(result.wd[:, :16]).all()
    assert "num_modes = 20 asked, but the model has only 16 elastic modes" in result.notes[0]
    assert rs.campbell(small_rotor(2), [0.0, 50.0], num_modes=4).notes == ()


NEGATIVE = {
    "modal": lambda r: rs.modal(r, speed=-100.0),
    "campbell": lambda r: rs.campbell(r, [-100.0, 0.0, 100.0]),
    "static": lambda r: rs.static(r, speed=-100.0),
    "frequency_response": lambda r: rs.frequency_response(r, [10.0], [(2, "ux")],
                                                          speed=-100.0),
    "critical_speed_map": lambda r: critical_speed_map(r, num_points=2, num_modes=1,
                                                       speeds=[-10.0, 10.0]),
    "transient": lambda r: rs.transient(r, 0.01, 1e-3, speed=-100.0, initial="zero"),
    "run-down": lambda r: rs.transient(r, 0.01, 1e-3, initial="zero",
                                       speed=rs.LinearSpeed(100.0, -100.0, 0.0, 0.01)),
}


@pytest.mark.parametrize("verb", sorted(NEGATIVE))
def test_negative_speeds_are_refused_everywhere(verb):
    """One rule for every analysis: spin is about +z at W >= 0 (issue 12: modal, static
    and transients accepted negative speeds, Campbell refused them)."""
    with pytest.raises(ModelError, match=r"must be >= 0.*rotors spin about \+z"):
        NEGATIVE[verb](small_rotor())


def test_unbalance_response_refuses_negative_speeds():
    with pytest.raises(ModelError, match="not finite and >= 0"):
        rs.unbalance_response(small_rotor(), [-10.0, 10.0], [(2, 1e-4, 0.0)])


@pytest.mark.parametrize("speed", [np.nan, np.inf, "fast", True])
def test_modal_speed_must_be_a_finite_number(speed):
    with pytest.raises(ModelError, match="modal: speed must be"):
        rs.modal(small_rotor(), speed=speed)


def test_explicit_rigid_tol_and_sigma_are_honoured():
    rotor = small_rotor()
    default = rs.modal(rotor, 0.0, 4)
    explicit = rs.modal(rotor, 0.0, 4, sigma=-1.0, rigid_tol=1e-3)
    np.testing.assert_allclose(explicit.wn, default.wn, rtol=1e-9)  # solver accuracy
    assert explicit.options["sigma"] == -1.0 and explicit.options["rigid_tol"] == 1e-3
    assert default.options["sigma"] < 0  # scale-aware default, recorded
    with pytest.raises(ModelError, match="sigma must be finite"):
        rs.modal(rotor, 0.0, 4, sigma=np.nan)


def _two_disk(material: rs.Material, k_bearing: float) -> rs.Rotor:
    shaft = [rs.ShaftElement(L=1.5 / 24, idl=0.0, odl=0.05, material=material)
             for _ in range(24)]
    disks = [rs.DiskElement(n=8, m=32.6, Id=0.18, Ip=0.33),
             rs.DiskElement(n=16, m=65.6, Id=0.5, Ip=1.0)]
    return rs.Rotor(shaft, disks, [rs.BearingElement(n=0, kxx=k_bearing),
                                   rs.BearingElement(n=24, kxx=k_bearing)])


@pytest.mark.parametrize("sparse", [False, True])
def test_absurdly_soft_material_is_solved_at_its_own_scale(sparse):
    """E = 1 Pa (a unit slip for 1 GPa) made ARPACK search about the fixed shift -1 rad/s,
    far above every mode: 16 s, then "ARPACK found 0 of 20 eigenvalues" (issue 12). The
    shift now follows the model's scale. Exact similarity law: scaling every stiffness
    (E, G and the bearings) by s scales every natural frequency at rest by sqrt(s);
    tolerance 1e-8 is the eigen-solver accuracy."""
    steel = STEEL
    soft = rs.Material(name="soft", E=1.0, G_s=steel.G_s / steel.E, rho=steel.rho)
    ref = rs.modal(_two_disk(steel, 1e6), 0.0, 8, sparse=sparse)
    got = rs.modal(_two_disk(soft, 1e6 / steel.E), 0.0, 8, sparse=sparse)
    np.testing.assert_allclose(got.wn, ref.wn * np.sqrt(1.0 / steel.E), rtol=1e-8)
    assert got.rigid_body_modes == ref.rigid_body_modes == 2
    assert abs(got.options["sigma"]) < 0.1 * got.wn[0]  # the shift follows the model scale


@pytest.mark.parametrize("verb", ["modal", "campbell", "critical_speeds"])
def test_sparse_flag_must_be_a_bool_or_none(verb):
    # "no" used to be read as true and chose ARPACK
    calls = {"modal": lambda: rs.modal(small_rotor(), 0.0, 2, sparse="no"),
             "campbell": lambda: rs.campbell(small_rotor(), [0.0], 2, sparse="no"),
             "critical_speeds": lambda: critical_speeds(small_rotor(), 1, 2, sparse="no")}
    with pytest.raises(ModelError, match=f"{verb}: sparse must be None, True or False"):
        calls[verb]()


def test_pure_tilt_modes_get_their_whirl_from_the_tilt_orbits():
    """A rigid disk on one node (no beam): translation and tilt decouple exactly, so the
    conical modes have no translation at all. Their whirl comes from the tilt orbits, and
    must match the closed form: the forward tilt mode stiffens with speed,
    ``lam^2 Id - lam W Ip - kr = 0`` (Friswell et al. 2010, section 3.5), the backward one
    softens."""
    Id, Ip, kr, k, m, speed = 0.9, 0.5, 2e5, 4e6, 30.0, 600.0
    rotor = rs.Rotor([], [rs.DiskElement(n=0, m=m, Id=Id, Ip=Ip)],
                     [rs.BearingElement(n=0, kxx=k, krr=kr, kzz=1e10)],
                     lines=[ShaftLine("rotor", [])])
    modes = rs.modal(rotor, speed, num_modes=4)
    tilt = np.flatnonzero(np.abs(modes.wd - np.sqrt(k / m)) > 1.0)
    assert tilt.size == 2
    forward = (Ip * speed + np.sqrt((Ip * speed) ** 2 + 4 * Id * kr)) / (2 * Id)
    backward = (-Ip * speed + np.sqrt((Ip * speed) ** 2 + 4 * Id * kr)) / (2 * Id)
    whirl = np.asarray(modes.whirl)
    got = dict(zip(whirl[tilt], modes.wd[tilt], strict=True))
    assert set(got) == {"forward", "backward"}
    # a 12-DOF dense problem: eigenvalues to ~1e-13 relative
    np.testing.assert_allclose([got["forward"], got["backward"]], [forward, backward],
                               rtol=1e-9)
    # normalised by the largest entry (a tilt), not by a translation at rounding level
    np.testing.assert_allclose(np.abs(modes.mode_shapes[:, tilt]).max(axis=0), 1.0,
                               rtol=1e-12)
