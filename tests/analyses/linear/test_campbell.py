"""Campbell diagram: mode tracking, reference frequencies, critical speeds from the grid."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
import rotorsim.analyses.linear.campbell as campbell_module
from rotorsim.analyses.linear.campbell import campbell
from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.analyses.linear.mode_shapes import circularize, clusters, mac, whirl_of
from rotorsim.errors import ConvergenceError, ModelError, Status

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
RPM = np.pi / 30.0


def friswell_591() -> rs.Rotor:
    """Friswell et al. (2010) example 5.9.1: two disks, isotropic undamped bearings."""
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=STEEL) for _ in range(6)]
    disks = [rs.DiskElement.from_geometry(2, STEEL, width=0.07, i_d=0.05, o_d=0.28),
             rs.DiskElement.from_geometry(4, STEEL, width=0.07, i_d=0.05, o_d=0.35)]
    bearings = [rs.BearingElement(n=0, kxx=1e6, kyy=1e6, cxx=0.0),
                rs.BearingElement(n=6, kxx=1e6, kyy=1e6, cxx=0.0)]
    return rs.Rotor(shaft, disks, bearings)


def crossing_rotor() -> rs.Rotor:
    """Short stiff shaft, central disk with Ip = 1.5 Id: the bounce (cylindrical) pair sits
    at 277 rad/s, the conical pair at 496 rad/s at rest, and the backward conical branch
    falls through both bounce branches as the speed rises."""
    shaft = [rs.ShaftElement(L=0.2, idl=0.0, odl=0.04, material=STEEL) for _ in range(2)]
    disk = rs.DiskElement(n=1, m=20.0, Id=0.25, Ip=0.375)
    return rs.Rotor(shaft, [disk], [rs.BearingElement(n=0, kxx=1e6),
                                    rs.BearingElement(n=2, kxx=1e6)])


def tilting_disk(Id: float, Ip: float, m: float = 20.0, k: float = 1e6,
                 kr: float = 3e4) -> rs.Rotor:
    """Rigid disk on a bearing node with lateral stiffness k and tilting stiffness kr.

    The only shaft element is nearly massless (rho = 1e-3 kg/m^3, 2e-8 kg), so the
    disk's equations are exactly those of a disk on springs (relative model error ~1e-9).
    """
    light = rs.Material(name="light", E=211e9, G_s=81.2e9, rho=1e-3)
    shaft = [rs.ShaftElement(L=0.01, idl=0.0, odl=0.05, material=light)]
    rotor = rs.Rotor(shaft, [rs.DiskElement(n=0, m=m, Id=Id, Ip=Ip)],
                     [rs.BearingElement(n=0, kxx=k, krr=kr)])
    return rotor.without_axial_torsion()


# ---------------------------------------------------------------- shape tools
def test_mac_of_forward_and_backward_circles() -> None:
    fwd, bwd, line = np.array([1.0, -1j]), np.array([1.0, 1j]), np.array([1.0, 0.0])
    m = mac(np.stack([fwd, bwd], 1), np.stack([fwd * 3j, bwd, line], 1))
    np.testing.assert_allclose(m, [[1.0, 0.0, 0.5], [0.0, 1.0, 0.5]], atol=1e-14)


def test_circularize_splits_plane_modes_into_circles() -> None:
    rng = np.random.default_rng(0)
    phi = rng.normal(size=3)
    x_plane = np.zeros((18, 1), complex)
    y_plane = np.zeros((18, 1), complex)
    x_plane[0::6, 0], y_plane[1::6, 0] = phi, phi
    mixed = np.hstack([x_plane + 0.3 * y_plane, y_plane - 0.2j * x_plane])
    out = circularize(mixed, clusters([100.0, 100.0 * (1 + 1e-9)]))
    whirl, ratio = whirl_of(out)
    assert whirl.tolist() == ["forward", "backward"]
    np.testing.assert_allclose(ratio, [1.0, -1.0], atol=1e-12)


# ---------------------------------------------------------------- tracking
def test_tracks_follow_modes_through_a_crossing() -> None:
    speeds = np.linspace(0.0, 1000.0, 201)
    c = campbell(crossing_rotor(), speeds, num_modes=4)
    assert np.all(c.status == Status.OK)
    bounce = c.wd[0, 0]
    # the pairs are degenerate at rest and leave along their forward/backward branches
    assert c.whirl[0].tolist() == c.whirl[1].tolist() == ["forward", "backward"] * 2
    for j in range(4):
        assert np.all(c.whirl[:, j] == c.whirl[0, j])  # a track keeps its whirl
        jumps = np.abs(np.diff(c.wd[:, j])) / c.wd[:-1, j]
        assert jumps.max() < 0.03  # 5 rad/s steps: slopes <= 1.1 give < 2 %
    # cylindrical mode: disk does not tilt, no gyroscopic moment -> flat branches
    np.testing.assert_allclose(c.wd[:, :2], bounce, rtol=1e-3)
    # conical mode: forward stiffens, backward softens, monotonically
    assert np.all(np.diff(c.wd[:, 2]) > 0) and np.all(np.diff(c.wd[:, 3]) < 0)
    # the backward conical track really crosses both bounce tracks
    assert c.wd[0, 3] > 1.5 * bounce and c.wd[-1, 3] < 0.7 * bounce
    assert np.nanmin(c.tracking_mac[1:]) > 0.99


def test_tracking_does_not_depend_on_starting_at_rest() -> None:
    speeds = np.linspace(0.0, 1000.0, 101)
    full = campbell(crossing_rotor(), speeds, num_modes=4)
    late = campbell(crossing_rotor(), speeds[10:], num_modes=4)
    # columns start in frequency order at the first speed: match them, then whole curves
    perm = np.argmin(np.abs(late.wd[0][:, None] - full.wd[10][None, :]), axis=1)
    assert sorted(perm.tolist()) == [0, 1, 2, 3]
    np.testing.assert_allclose(late.wd, full.wd[10:, perm], rtol=1e-10)
    assert np.all(late.whirl == full.whirl[10:, perm])


@pytest.mark.validation
def test_friswell_591_frequencies_at_4000_rpm() -> None:
    """Damped frequencies at 4000 rpm (ROSS 3.1 reference values for Friswell 5.9.1)."""
    reference = [(85.389, "backward"), (87.796, "forward"), (251.785, "backward"),
                 (294.713, "forward"), (600.179, "backward"), (827.075, "forward"),
                 (1038.996, "backward"), (1088.193, "forward")]
    c = campbell(friswell_591(), np.linspace(0.0, 4000.0 * RPM, 21), num_modes=10)
    lateral = np.flatnonzero(c.kind[-1] == "lateral")
    order = lateral[np.argsort(c.wd[-1, lateral])][:8]
    # the reference is printed to 3 decimals: half a unit (5e-4 rad/s) is its precision;
    # measured: up to 4.75e-4 (1038.99552 against 1038.996), 1e-9 relative eigen margin
    wd = c.wd[-1, order]
    np.testing.assert_allclose(wd, [r[0] for r in reference], rtol=1e-9, atol=5e-4)
    assert c.whirl[-1, order].tolist() == [r[1] for r in reference]
    # disk-dominated modes: gyroscopic stiffening of forward, softening of backward whirl
    for j in order:
        slope = np.diff(c.wd[:, j])
        assert np.all(slope > 0) if c.whirl[-1, j] == "forward" else np.all(slope < 0)
    assert c.stats["eigen_solves"] == 21


@pytest.mark.verification
def test_grid_critical_speeds_match_exact_ones() -> None:
    rotor = friswell_591()
    c = campbell(rotor, np.linspace(0.0, 1200.0, 121), num_modes=10)
    from_grid = c.critical_speeds(harmonic=1)
    exact = critical_speeds(rotor, harmonic=1, num_modes=12)
    exact = exact.subset(np.flatnonzero(exact.speed < 1200.0))
    assert len(from_grid) == len(exact) == 9
    # local cubic interpolation on the 10 rad/s grid, O(h^4): 1.7e-8 / 2.0e-9 / 2.1e-10 on
    # 40 / 20 / 10 rad/s grids (measured); 1e-8 also keeps the eigen-solver margin
    np.testing.assert_allclose(from_grid.speed, exact.speed, rtol=1e-8)
    assert from_grid.whirl.tolist() == exact.whirl.tolist()
    np.testing.assert_allclose(from_grid.frequency, from_grid.speed)
    forward = c.critical_speeds(harmonic=1, whirl="forward")
    assert set(forward.whirl) == {"forward"} and len(forward) == 4


def test_grid_critical_speeds_of_tilting_disk_are_the_classic_ones() -> None:
    """Disk on springs: forward tilting critical sqrt(kr/(Id-Ip)), backward sqrt(kr/(Id+Ip)),
    bounce sqrt(k/m) (forward and backward, gyroscopically unaffected)."""
    Id, Ip, m, k, kr = 0.3, 0.1, 20.0, 1e6, 3e4
    c = campbell(tilting_disk(Id, Ip, m, k, kr), np.linspace(0.0, 600.0, 121), num_modes=4)
    fwd = c.critical_speeds(1, whirl="forward").speed
    bwd = c.critical_speeds(1, whirl="backward").speed
    # local cubic interpolation on a 5 rad/s grid: error well below 1e-5 here
    np.testing.assert_allclose(fwd, [np.sqrt(k / m), np.sqrt(kr / (Id - Ip))], rtol=1e-5)
    np.testing.assert_allclose(bwd, [np.sqrt(k / m), np.sqrt(kr / (Id + Ip))], rtol=1e-5)


def test_no_forward_tilting_critical_when_ip_exceeds_id() -> None:
    c = campbell(tilting_disk(0.1, 0.3), np.linspace(0.0, 2000.0, 101), num_modes=4)
    fwd = c.critical_speeds(1, whirl="forward")
    np.testing.assert_allclose(fwd.speed, [np.sqrt(1e6 / 20.0)], rtol=1e-5)


# ---------------------------------------------------------------- failures and input
def test_record_failure_leaves_nan_and_status(monkeypatch: pytest.MonkeyPatch) -> None:
    real_modal = campbell_module.modal

    def flaky(system, speed, *args, **kwargs):
        if speed == 100.0:
            raise ConvergenceError("ARPACK did not converge", "quadratic_eigen")
        return real_modal(system, speed, *args, **kwargs)

    monkeypatch.setattr(campbell_module, "modal", flaky)
    speeds = [0.0, 50.0, 100.0, 150.0]
    c = campbell(crossing_rotor(), speeds, num_modes=4, on_failure="record")
    assert c.status.tolist() == [Status.OK, Status.OK, Status.NOT_CONVERGED, Status.OK]
    assert np.all(np.isnan(c.wd[2])) and np.all(c.whirl[2] == "")
    assert np.all(np.isfinite(c.wd[[0, 1, 3]]))
    # the track after the gap still follows its mode
    assert c.whirl[3].tolist() == c.whirl[1].tolist()
    with pytest.raises(ConvergenceError, match="speed 100"):
        campbell(crossing_rotor(), speeds, num_modes=4)


@pytest.mark.parametrize(
    ("speeds", "kwargs"),
    [([], {}), ([0.0, np.nan], {}), ([0.0, np.inf], {}), ([0.0, 10.0], {"num_modes": 0}),
     ([-10.0, 10.0], {}), ([10.0, 5.0], {}), ([0.0, 10.0], {"on_failure": "ignore"})],
)
def test_bad_input_raises_model_error(speeds, kwargs) -> None:
    with pytest.raises(ModelError):
        campbell(crossing_rotor(), speeds, **kwargs)


@pytest.mark.parametrize("harmonic", [0, -1, np.nan])
def test_bad_harmonic_raises_model_error(harmonic) -> None:
    c = campbell(crossing_rotor(), [0.0, 100.0], num_modes=2)
    with pytest.raises(ModelError):
        c.critical_speeds(harmonic)
    with pytest.raises(ModelError):
        c.critical_speeds(1, whirl="sideways")


def test_progress_bar_gives_same_result(capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("tqdm")
    speeds = [0.0, 100.0, 200.0]
    quiet = campbell(crossing_rotor(), speeds, num_modes=2)
    shown = campbell(crossing_rotor(), speeds, num_modes=2, progress=True)
    np.testing.assert_array_equal(quiet.wd, shown.wd)
    assert "campbell" in capsys.readouterr().err
