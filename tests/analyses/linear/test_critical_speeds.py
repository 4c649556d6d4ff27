"""Exact undamped critical speeds and the critical-speed map."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.linear.critical_speed_map import critical_speed_map
from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.errors import ModelError

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def tilting_disk(Id: float, Ip: float, m: float = 20.0, k: float = 1e6,
                 kr: float = 3e4) -> rs.Rotor:
    """Rigid disk on a bearing node with lateral stiffness k and tilting stiffness kr.

    The only shaft element is nearly massless (rho = 1e-3 kg/m^3, 2e-8 kg): the low modes
    are those of the disk on springs to a relative error ~1e-9.
    """
    light = rs.Material(name="light", E=211e9, G_s=81.2e9, rho=1e-3)
    shaft = [rs.ShaftElement(L=0.01, idl=0.0, odl=0.05, material=light)]
    rotor = rs.Rotor(shaft, [rs.DiskElement(n=0, m=m, Id=Id, Ip=Ip)],
                     [rs.BearingElement(n=0, kxx=k, krr=kr)])
    return rotor.without_axial_torsion()


def two_disk_rotor(n_elements: int, bearings=None) -> rs.Rotor:
    """Friswell 5.9.1 geometry (1.5 m, disks at 0.5 m and 1 m) on ``n_elements`` elements."""
    shaft = [rs.ShaftElement(L=1.5 / n_elements, idl=0.0, odl=0.05, material=STEEL)
             for _ in range(n_elements)]
    disks = [rs.DiskElement.from_geometry(n_elements // 3, STEEL, 0.07, 0.05, 0.28),
             rs.DiskElement.from_geometry(2 * n_elements // 3, STEEL, 0.07, 0.05, 0.35)]
    if bearings is None:
        bearings = [rs.BearingElement(n=0, kxx=1e6), rs.BearingElement(n=n_elements, kxx=1e6)]
    return rs.Rotor(shaft, disks, bearings)


def euler_shaft(n_elements: int = 10, length: float = 1.0, d: float = 0.05) -> rs.Rotor:
    """Uniform Euler-Bernoulli shaft (no shear, rotary inertia or gyroscopics), end bearings."""
    shaft = [rs.ShaftElement(L=length / n_elements, idl=0.0, odl=d, material=STEEL,
                             shear_effects=False, rotary_inertia=False, gyroscopic=False)
             for _ in range(n_elements)]
    return rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=1e6),
                                rs.BearingElement(n=n_elements, kxx=1e6)])


# ---------------------------------------------------------------- exact critical speeds
@pytest.mark.validation
@pytest.mark.parametrize("harmonic", [1.0, 2.0])
def test_tilting_disk_classic_critical_speeds(harmonic: float) -> None:
    """Disk on springs, whirl w = k W: tilting ``Id w^2 -+ Ip W w = kr`` gives
    ``W = sqrt(kr / (k^2 Id -+ k Ip))`` forward/backward; bounce ``W = sqrt(k_lat/m) / k``."""
    Id, Ip, m, k_lat, kr = 0.3, 0.1, 20.0, 1e6, 3e4
    cs = critical_speeds(tilting_disk(Id, Ip, m, k_lat, kr), harmonic, num_modes=4)
    bounce = np.sqrt(k_lat / m) / harmonic
    fwd = np.sqrt(kr / (harmonic**2 * Id - harmonic * Ip))
    bwd = np.sqrt(kr / (harmonic**2 * Id + harmonic * Ip))
    expected = sorted([(bounce, "forward"), (bounce, "backward"), (fwd, "forward"),
                       (bwd, "backward")])
    # model error: the 2e-8 kg shaft element on the 20 kg disk lowers the speeds by 5e-10
    # (measured); 1e-8 keeps the eigen-solver margin (BLAS kernels differ by CPU)
    np.testing.assert_allclose(cs.speed, [e[0] for e in expected], rtol=1e-8)
    np.testing.assert_allclose(cs.frequency, harmonic * cs.speed)
    tilting = ~np.isclose(cs.speed, bounce, rtol=1e-6)
    assert cs.whirl[tilting].tolist() == [w for s, w in expected if abs(s - bounce) > 1e-3]
    assert np.all(cs.kind == "lateral") and np.all(np.isnan(cs.log_dec))


def test_no_forward_tilting_critical_speed_when_ip_exceeds_id() -> None:
    Id, Ip, m, k_lat, kr = 0.1, 0.3, 20.0, 1e6, 3e4
    fwd = critical_speeds(tilting_disk(Id, Ip, m, k_lat, kr), 1, num_modes=2, whirl="forward")
    # only the bounce mode: sqrt(kr/(Id - Ip)) is imaginary, the next mode is the shaft's own
    np.testing.assert_allclose(fwd.speed[0], np.sqrt(k_lat / m), rtol=1e-7)
    assert fwd.speed[1] > 1e6
    bwd = critical_speeds(tilting_disk(Id, Ip, m, k_lat, kr), 1, num_modes=2, whirl="backward")
    np.testing.assert_allclose(bwd.speed, sorted([np.sqrt(k_lat / m), np.sqrt(kr / (Id + Ip))]),
                               rtol=1e-7)


def test_sparse_and_dense_solvers_agree() -> None:
    rotor = two_disk_rotor(24)  # 150 DOFs
    dense = critical_speeds(rotor, 1, num_modes=8, sparse=False)
    sparse = critical_speeds(rotor, 1, num_modes=8, sparse=True)
    np.testing.assert_allclose(sparse.speed, dense.speed, rtol=1e-9)
    assert sparse.whirl.tolist() == dense.whirl.tolist()
    assert sparse.stats["factorizations"] == 1 and sparse.stats["eigen_solves"] == 1
    assert dense.stats["factorizations"] == 1  # the dense path also shift-inverts (issue 12)


def test_large_model_is_the_limit_of_mesh_refinement() -> None:
    fine = critical_speeds(two_disk_rotor(120), 1, num_modes=3, whirl="forward")  # 726 DOFs
    assert fine.stats["factorizations"] == 1 and fine.stats["eigen_solves"] == 1
    assert fine.mode_shapes.shape == (726, 3) and set(fine.whirl) == {"forward"}
    # dense solutions on 6, 12, 24 elements converge to the sparse 120-element one
    errors = np.array([
        np.abs(critical_speeds(two_disk_rotor(n), 1, 3, whirl="forward").speed - fine.speed)
        / fine.speed for n in (6, 12, 24)
    ])
    assert np.all(errors[1:] < errors[:-1] / 4)  # at least second order in h
    assert errors[-1].max() < 1e-4


def test_accepts_an_assembled_system() -> None:
    rotor = two_disk_rotor(6)
    a = critical_speeds(rotor, 1, num_modes=4)
    b = critical_speeds(rs.assemble(rotor), 1, num_modes=4)
    # the same model assembled twice: equal up to LAPACK round-off
    np.testing.assert_allclose(a.speed, b.speed, rtol=1e-10)


@pytest.mark.parametrize(
    "kwargs", [{"harmonic": 0}, {"harmonic": -1.0}, {"harmonic": np.nan}, {"num_modes": 0},
               {"whirl": "both"}],
)
def test_bad_input_raises_model_error(kwargs) -> None:
    with pytest.raises(ModelError):
        critical_speeds(two_disk_rotor(6), **kwargs)


# ---------------------------------------------------------------- critical-speed map
@pytest.mark.validation
def test_map_limits_match_beam_and_rigid_body_formulas() -> None:
    L, d = 1.0, 0.05
    rotor = euler_shaft(10, L, d)
    area, inertia = np.pi * d**2 / 4, np.pi * d**4 / 64
    mass = STEEL.rho * area * L
    res = critical_speed_map(rotor, stiffness_range=(1e2, 1e12), num_points=11, num_modes=2,
                             gyroscopic=False)
    soft, rigid = res.critical_speeds[0], res.critical_speeds[-1]
    # soft supports (k = 100 N/m): rigid-body bounce and rock. The formulas take the shaft
    # as rigid; its compliance in series with the supports lowers the speeds by a fraction
    # of k / k_shaft (k_shaft = 48 EI / L^3 = 3.1e6 N/m: 3.2e-5). Measured -1.3e-5, -1.8e-6.
    flexibility = 1e2 / (48 * STEEL.E * inertia / L**3)
    np.testing.assert_allclose(soft[0], np.sqrt(2 * 1e2 / mass), rtol=flexibility)
    np.testing.assert_allclose(soft[1], np.sqrt(6 * 1e2 / mass),  # k L^2/2 / (m L^2/12)
                               rtol=flexibility)
    # stiff supports: pinned-pinned Euler beam (pi/L)^2 sqrt(EI/(rho A)). Error +5.5e-6:
    # the 10-element cubic-Hermite discretisation, O(h^4) (+6.7e-6; 20 and 40 elements give
    # -8.6e-7 and -1.3e-6, the compliance of the 1e12 N/m supports): 2e-5 bounds both
    pinned = (np.pi / L) ** 2 * np.sqrt(STEEL.E * inertia / (STEEL.rho * area))
    np.testing.assert_allclose(rigid[0], pinned, rtol=2e-5)
    assert np.all(np.diff(res.critical_speeds[:, 0]) > 0)
    assert res.speeds.size == 0 and len(res.intersections) == 0
    # the elements have no gyroscopic matrix: the forward synchronous critical speed is the
    # same (measured: equal; 1e-8 is the eigen-solver margin)
    gyro = critical_speed_map(rotor, stiffness=[1e2], num_modes=1)
    np.testing.assert_allclose(gyro.critical_speeds[0, 0], soft[0], rtol=1e-8)


def test_map_of_one_bearing_leaves_the_other() -> None:
    rotor = euler_shaft(6)
    res = critical_speed_map(rotor, stiffness=[1e6], num_modes=2, bearings=[1])
    direct = critical_speeds(rotor, 1, num_modes=2, whirl="forward")  # both at 1e6 already
    np.testing.assert_allclose(res.critical_speeds[0], direct.speed, rtol=1e-9)
    assert res.bearings.tolist() == [1]


@pytest.mark.verification
def test_speed_dependent_bearing_intersections() -> None:
    freq = np.array([0.0, 200.0, 400.0, 800.0])
    k = np.array([2e5, 1e6, 4e6, 1e7])
    bearings = [rs.BearingElement(n=0, kxx=k, kyy=k, frequency=freq),
                rs.BearingElement(n=6, kxx=k, kyy=k, frequency=freq)]
    rotor = two_disk_rotor(6, bearings)
    res = critical_speed_map(rotor, stiffness_range=(1e5, 1e8), num_points=30, num_modes=3)
    assert res.curve_bearings.tolist() == [0, 1]
    assert res.bearing_kxx.shape == (2, res.speeds.size) == res.bearing_kyy.shape
    hits = res.intersections
    assert len(hits) == 12  # 2 bearings x (kxx, kyy) x 3 modes
    assert sorted(set(hits.mode.tolist())) == [0, 1, 2]
    for b, name, w, k_s in zip(hits.bearing, hits.coefficient, hits.speed, hits.stiffness,
                               strict=True):
        # on the bearing curve
        np.testing.assert_allclose(k_s, rotor.bearing_elements[b].coefficient(name, w),
                                   rtol=1e-12)
    # on the critical-speed curve: the rotor on constant supports of that stiffness has a
    # forward critical speed there. Tolerance: the spline interpolation error of the map,
    # O(h^4): 7.4e-6 / 4.3e-7 / 3.2e-8 with 15 / 30 / 60 points (measured); 4e-6 is below
    # the error of a map with half the points
    for j in range(3):
        first = np.flatnonzero(hits.mode == j)[0]
        const = [rs.BearingElement(n=n, kxx=hits.stiffness[first]) for n in (0, 6)]
        exact = critical_speeds(two_disk_rotor(6, const), 1, 3, whirl="forward")
        np.testing.assert_allclose(hits.speed[first], exact.speed[j], rtol=4e-6)
    # and they are the rotor's own critical speeds on its speed-dependent bearings
    fixed_point = critical_speeds(rotor, 1, num_modes=3, whirl="forward")
    assert "fixed point" in fixed_point.options["bearings"]
    for j in range(3):
        np.testing.assert_allclose(hits.speed[hits.mode == j], fixed_point.speed[j],
                                   rtol=4e-6)


@pytest.mark.parametrize(
    ("args", "kwargs"),
    [((), {"stiffness_range": (1e6, 1e5)}), ((), {"num_points": 1}),
     ((), {"bearings": [5]}), ((), {"stiffness": [1e6, -1.0]}),
     ((), {"stiffness": [2e6, 1e6]}),
     ((), {"harmonic": 0}), ((), {"num_modes": 0})],
)
def test_map_bad_input_raises_model_error(args, kwargs) -> None:
    with pytest.raises(ModelError):
        critical_speed_map(euler_shaft(4), *args, **kwargs)


def test_map_needs_a_rotor() -> None:
    with pytest.raises(ModelError):
        critical_speed_map(rs.assemble(euler_shaft(4)))  # type: ignore[arg-type]


def test_cross_coupled_bearings_are_dropped_for_a_rotor_and_refused_for_a_system() -> None:
    """Classical undamped critical speeds use the direct bearing stiffness only."""
    base = two_disk_rotor(6)
    coupled = base.with_bearings([dataclasses.replace(b, kxy=3e5, kyx=-3e5)
                                  for b in base.bearing_elements])
    direct = critical_speeds(base, 1, num_modes=4)
    result = critical_speeds(coupled, 1, num_modes=4)
    assert result.options["cross_coupling"] == "dropped"
    assert direct.options["cross_coupling"] == "none"
    np.testing.assert_allclose(result.speed, direct.speed, rtol=1e-10)
    with pytest.raises(ModelError, match="not symmetric"):
        critical_speeds(rs.assemble(coupled), 1, num_modes=4)


def test_forward_filter_keeps_predominantly_forward_elliptical_modes() -> None:
    """Strongly anisotropic supports make elliptical orbits; the forward critical speeds
    must still be found (classic: each mode pair splits into two crossings)."""
    base = two_disk_rotor(6)
    aniso = base.with_bearings([dataclasses.replace(b, kxx=1e6, kyy=4e6)
                                for b in base.bearing_elements])
    every = critical_speeds(aniso, 1, num_modes=8)
    forward = critical_speeds(aniso, 1, num_modes=3, whirl="forward")
    assert forward.speed.size == 3
    np.testing.assert_allclose(forward.speed, every.speed[[1, 3, 7]], rtol=1e-10)
    assert forward.whirl.tolist() == ["forward", "forward", "mixed"]  # the third elliptical


def test_map_keeps_axial_and_tilt_part_of_a_full_bearing_matrix() -> None:
    import rotorsim.analyses.linear.critical_speed_map as csm

    K5 = np.diag([5e7, 6e7, 2e7, 3e4, 4e4])
    K5[2, 3] = K5[3, 2] = 1e5
    support = csm._support(rs.BearingElement(n=0, stiffness_matrix=K5), 1e6)
    assert support.stiffness_matrix is not None
    np.testing.assert_array_equal(support.stiffness_matrix[2:, 2:], K5[2:, 2:])
    assert not support.stiffness_matrix[:2].any() and not support.stiffness_matrix[:, :2].any()
    assert support.matrices().K[0, 0] == 1e6 and support.matrices().K[1, 1] == 1e6


@pytest.mark.validation
@pytest.mark.parametrize("sparse", [False, True])
@pytest.mark.parametrize("k_support", [1e20, 1e30])
def test_stiff_supports_give_pinned_beam_critical_speeds(k_support: float, sparse: bool) -> None:
    """Pinned supports as 1e20 or 1e30 N/m springs (issue 12: the rigid-body threshold scaled
    with the stiffest spring, so bending modes were dropped and penalty modes reported).
    Reference: pinned-pinned Euler-Bernoulli beam ``(j pi / L)^2 sqrt(E I / (rho A))``; the
    non-gyroscopic EB shaft has no speed dependence. Tolerances 1e-6 and 2e-5: the error of
    cubic Hermite elements falls as h^4 (measured 6.7e-6, 4.2e-7, 2.6e-8 for mode 1 with 10,
    20, 40 elements; 1.1e-4, 6.7e-6, 4.2e-7 for mode 2)."""
    L, d, n = 1.0, 0.05, 20
    shaft = euler_shaft(n, L, d)
    rotor = shaft.with_bearings([rs.BearingElement(n=0, kxx=k_support),
                                 rs.BearingElement(n=n, kxx=k_support)])
    cs = critical_speeds(rotor, 1, num_modes=2, whirl="forward", sparse=sparse)
    area, inertia = np.pi * d**2 / 4, np.pi * d**4 / 64
    pinned = (np.arange(1, 3) * np.pi / L) ** 2 * np.sqrt(STEEL.E * inertia / (STEEL.rho * area))
    assert np.all(np.abs(cs.speed / pinned - 1.0) < [1e-6, 2e-5])
    assert np.all(cs.kind == "lateral")


def test_map_reaches_the_pinned_limit_with_penalty_stiffness() -> None:
    """A map up to 1e20 N/m ends on the pinned-pinned beam instead of failing or dropping
    the bending mode (issue 12); tolerance as in the test above."""
    L, d = 1.0, 0.05
    res = critical_speed_map(euler_shaft(20, L, d), stiffness=[1e6, 1e12, 1e20], num_modes=1,
                             gyroscopic=False)
    area, inertia = np.pi * d**2 / 4, np.pi * d**4 / 64
    pinned = (np.pi / L) ** 2 * np.sqrt(STEEL.E * inertia / (STEEL.rho * area))
    assert res.critical_speeds[-1, 0] == pytest.approx(pinned, rel=1e-6)
    assert np.all(np.diff(res.critical_speeds[:, 0]) > 0)
