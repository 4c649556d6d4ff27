"""Shared contract of every linear element: symmetric M and K, skew G, mass, rigid-body modes."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.model.material import steel

SHAFTS = {
    "solid": rs.ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel, n=0),
    "hollow": rs.ShaftElement(L=0.3, idl=0.03, odl=0.08, material=steel, n=0),
    "tapered": rs.ShaftElement(L=0.25, idl=0.01, odl=0.06, idr=0.02, odr=0.04,
                               material=steel, n=0),
    "euler_bernoulli": rs.ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel, n=0,
                                       shear_effects=False, rotary_inertia=False),
    "axial_load": rs.ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel, n=0,
                                  axial_force=1e4),
    "rayleigh": rs.ShaftElement(L=0.2, idl=0.0, odl=0.05, material=steel, n=0,
                                alpha=2.0, beta=1e-5),
}
OTHERS = {
    "disk": rs.DiskElement(n=0, m=10.0, Id=0.1, Ip=0.18),
    "point_mass": rs.PointMass(n=0, m=3.0),
    "bearing_ground": rs.BearingElement(n=0, kxx=1e7, kyy=2e7, kxy=1e5, kyx=1e5, kzz=1e6,
                                        cxx=100.0, krr=1e4),
    "bearing_link": rs.BearingElement(n=0, n_link=1, kxx=1e7, kyy=2e7, cxx=50.0, kzz=3e6),
}
ALL = {**SHAFTS, **OTHERS}


def _rigid_motions(z: np.ndarray) -> np.ndarray:
    """The 6 rigid motions (columns) of nodes at axial positions ``z``."""
    n = z.size
    r = np.zeros((6 * n, 6))
    for i, zi in enumerate(z):
        b = 6 * i
        r[b + 0, 0] = r[b + 1, 1] = r[b + 2, 2] = 1.0  # translations
        r[b + 3, 3], r[b + 1, 3] = 1.0, -zi  # rotation about x: uy = -z theta
        r[b + 4, 4], r[b + 0, 4] = 1.0, zi  # rotation about y: ux = z theta
        r[b + 5, 5] = 1.0  # torsion
    return r


@pytest.mark.parametrize("name", ALL)
def test_symmetry_and_skew(name):
    mats = ALL[name].matrices(0.0)
    scale = max(np.abs(mats.K).max(), 1.0)
    assert np.allclose(mats.M, mats.M.T, atol=1e-12 * np.abs(mats.M).max())
    assert np.allclose(mats.G, -mats.G.T, atol=1e-12 * max(np.abs(mats.G).max(), 1e-30))
    assert np.allclose(mats.C, mats.C.T, atol=1e-12 * max(np.abs(mats.C).max(), 1e-30))
    # cross-coupled bearings are the one non-symmetric K: asserted both ways, so that a
    # case named wrongly cannot drop the check
    symmetric = np.allclose(mats.K, mats.K.T, atol=1e-12 * scale)
    assert symmetric == ("kxy" not in name), name
    assert np.linalg.eigvalsh(mats.M).min() >= -1e-12 * np.abs(mats.M).max()


@pytest.mark.parametrize("name", SHAFTS)
def test_shaft_mass_equals_rho_volume(name):
    el = SHAFTS[name]
    mats = el.matrices()
    assert el.idr is not None and el.odr is not None
    # frustum volume of the outer cone minus the inner cone (exact, independent formula)
    def frustum(d1, d2):
        return math.pi * el.L / 12.0 * (d1**2 + d1 * d2 + d2**2)

    volume = frustum(el.odl, el.odr) - frustum(el.idl, el.idr)
    r = _rigid_motions(np.array([0.0, el.L]))
    for direction in range(3):
        e = r[:, direction]
        assert e @ mats.M @ e == pytest.approx(steel.rho * volume, rel=1e-12)


@pytest.mark.parametrize("name", SHAFTS)
def test_shaft_has_exactly_six_rigid_body_modes(name):
    el = SHAFTS[name]
    K = el.matrices().K
    r = _rigid_motions(np.array([0.0, el.L]))
    if el.axial_force == 0.0:
        assert np.abs(K @ r).max() <= 1e-9 * np.abs(K).max()
        eig = np.linalg.eigvalsh(K)
        assert np.sum(np.abs(eig) < 1e-9 * eig.max()) == 6
    else:  # a tensioned string resists rigid rotation: only 4 zero modes (x, y, z, torsion)
        assert np.abs(K @ r[:, [0, 1, 2, 5]]).max() <= 1e-9 * np.abs(K).max()


def test_disk_mass_inertia_and_gyroscopic():
    d = OTHERS["disk"]
    mats = d.matrices()
    assert np.diag(mats.M).tolist() == [10.0, 10.0, 10.0, 0.1, 0.1, 0.18]
    assert mats.G[3, 4] == pytest.approx(0.18) and mats.G[4, 3] == pytest.approx(-0.18)


def test_shaft_gyroscopic_equals_polar_inertia_under_uniform_tilt():
    """A uniform tilt rate of the whole element carries the polar moment rho*J*L."""
    el = SHAFTS["solid"]
    G = el.matrices().G
    r = _rigid_motions(np.array([0.0, el.L]))
    rot_x, rot_y = r[:, 3], r[:, 4]
    polar = steel.rho * math.pi * el.odl**4 / 32.0 * el.L
    assert rot_x @ G @ rot_y == pytest.approx(polar, rel=1e-12)


def test_node_to_node_bearing_moves_with_rigid_translation():
    mats = OTHERS["bearing_link"].matrices()
    r = _rigid_motions(np.array([0.0, 0.0]))[:, :3]
    # zero up to the round-off of the product: n eps |K| |r| (exact in practice, but the
    # summation order of a matrix product is the BLAS kernel's choice)
    for matrix in (mats.K, mats.C):
        scale = matrix.shape[0] * np.finfo(float).eps * np.abs(matrix).max() * np.abs(r).max()
        assert np.abs(matrix).max() > 0.0
        assert np.abs(matrix @ r).max() <= scale


def test_cantilever_tip_deflection_is_exact_with_one_element():
    """Timoshenko cantilever: delta = P L^3 / (3 E I) + P L / (kappa G A) (exact)."""
    el = SHAFTS["hollow"]
    K = el.matrices().K[6:, 6:]
    P = 1e3
    A = math.pi / 4 * (el.odl**2 - el.idl**2)
    Imom = math.pi / 64 * (el.odl**4 - el.idl**4)
    kappa = float(rs.cowper_shear_coefficient(steel.nu, el.idl / el.odl))
    exact = P * el.L**3 / (3 * steel.E * Imom) + P * el.L / (kappa * steel.G_s * A)
    for dof in (0, 1):
        f = np.zeros(6)
        f[dof] = P
        assert np.linalg.solve(K, f)[dof] == pytest.approx(exact, rel=1e-12)


def test_cowper_coefficient_solid_value():
    """Cowper (1966): 6 (1 + nu) / (7 + 6 nu) = 0.8863 for G = 81.2 GPa, E = 211 GPa."""
    assert float(rs.cowper_shear_coefficient(steel.nu, 0.0)) == pytest.approx(0.8863, abs=1e-4)


def test_speed_dependent_bearing_interpolates_and_clamps():
    b = rs.BearingElement(n=0, kxx=[1e6, 3e6], cxx=[10.0, 30.0], frequency=[0.0, 100.0])
    assert b.matrices(50.0).K[0, 0] == pytest.approx(2e6)
    assert b.matrices(500.0).K[0, 0] == pytest.approx(3e6)
    assert b.matrices(50.0).C[1, 1] == pytest.approx(20.0)


def test_full_stiffness_matrix_adds_to_the_coefficients():
    K5 = np.arange(25, dtype=float).reshape(5, 5)
    K5 = K5 + K5.T
    b = rs.BearingElement(n=0, kxx=1e6, stiffness_matrix=K5, damping_matrix=2 * K5)
    mats = b.matrices()
    expected = K5.copy()
    expected[0, 0] += 1e6
    expected[1, 1] += 1e6
    assert np.array_equal(mats.K[:5, :5], expected)
    assert np.array_equal(mats.C[:5, :5], 2 * K5)
    linked = rs.BearingElement(n=0, n_link=1, stiffness_matrix=K5).matrices()
    assert np.array_equal(linked.K[6:11, :5], -K5)
    with pytest.raises(rs.ModelError, match=r"stiffness_matrix must be a finite \(5, 5\)"):
        rs.BearingElement(n=0, stiffness_matrix=np.ones((3, 3)))
