"""Foundations as superelements on connection DOFs (issue 15): matrices from files, modal
data, the rigid limit, and the named errors of bad matrices."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

import rotorsim as rs
from rotorsim.elements.foundation import Foundation
from rotorsim.errors import ModelError
from rotorsim.io.model_file import model_from_dict

MODELS = Path(__file__).resolve().parents[2] / "models"
STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
SHAFT = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.04, material=STEEL) for _ in range(8)]
DISK = [rs.DiskElement(n=4, m=12.0, Id=0.06, Ip=0.11, tag="disk")]


def _on_pedestals(pedestal: list) -> rs.Rotor:
    """The rotor on bearings to housing nodes 9 and 10, given as point masses on springs
    (``pedestal`` empty) or by foundations."""
    bearings = [rs.BearingElement(n=0, n_link=9, kxx=2e7, kzz=1e8, tag="left"),
                rs.BearingElement(n=8, n_link=10, kxx=2e7, tag="right")]
    if pedestal:
        return rs.Rotor(SHAFT, DISK, bearings, foundations=pedestal)
    springs = [rs.BearingElement(n=n, kxx=5e7, kyy=8e7, cxx=2e3, cyy=2e3, kzz=1e9,
                                 tag=f"ground{n}") for n in (9, 10)]
    masses = [rs.PointMass(n=n, m=30.0, tag=f"pedestal{n}") for n in (9, 10)]
    return rs.Rotor(SHAFT, DISK, [*bearings, *springs], masses)


def _pedestal_matrices() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """M, C, K of the two pedestals on (9 ux, 9 uy, 9 uz, 10 ux, 10 uy, 10 uz)."""
    m = np.eye(6) * 30.0
    k = np.diag([5e7, 8e7, 1e9] * 2)
    c = np.diag([2e3, 2e3, 0.0] * 2)
    return m, c, k


DOFS = [(n, d) for n in (9, 10) for d in ("ux", "uy", "uz")]


@pytest.mark.verification
def test_a_foundation_of_pedestal_matrices_equals_point_masses_on_springs() -> None:
    m, c, k = _pedestal_matrices()
    expected = rs.modal(_on_pedestals([]), speed=1200.0, num_modes=10)
    got = rs.modal(_on_pedestals([Foundation(DOFS, M=m, C=c, K=k, tag="frame")]),
                   speed=1200.0, num_modes=10)
    # the same global matrices, so the eigenvalues agree to solver accuracy
    np.testing.assert_allclose(got.eigenvalues, expected.eigenvalues, rtol=1e-9)


@pytest.mark.validation
def test_modal_data_with_as_many_modes_as_dofs_rebuild_the_matrices(tmp_path) -> None:
    """``Phi^T M Phi = I``, ``Phi^T K Phi = diag(w^2)``, ``Phi^T C Phi = diag(2 zeta w)``:
    the modes of the pedestal matrices give back the same foundation."""
    import scipy.linalg as sl

    m, c, k = _pedestal_matrices()
    w2, phi = sl.eigh(k, m)
    w = np.sqrt(w2)
    zeta = np.diag(phi.T @ c @ phi) / (2 * w)  # c is diagonal in these modes here
    modal = Foundation.from_modal(DOFS, w, zeta, phi, tag="frame")
    np.testing.assert_allclose(modal.M, m, rtol=1e-12, atol=1e-12 * 30)
    np.testing.assert_allclose(modal.K, k, rtol=1e-12, atol=1e-12 * 1e9)
    np.testing.assert_allclose(modal.C, c, rtol=1e-12, atol=1e-9 * 2e3)


@pytest.mark.verification
def test_a_stiff_foundation_equals_ground() -> None:
    """Pedestals of stiffness 1e14 N/m (and small mass) leave the rotor on its bearings to
    ground: the frequencies agree to ``k_bearing / k_foundation`` ~ 1e-7."""
    dofs = [(n, d) for n in (9, 10) for d in ("ux", "uy", "uz", "rx", "ry", "rz")]
    stiff = Foundation(dofs, M=np.eye(12) * 1e-3, K=np.eye(12) * 1e14)
    bearings = [rs.BearingElement(n=0, kxx=2e7, kzz=1e8, tag="left"),
                rs.BearingElement(n=8, kxx=2e7, tag="right")]
    grounded = rs.modal(rs.Rotor(SHAFT, DISK, bearings), speed=800.0, num_modes=6).wd
    got = rs.modal(_on_pedestals([stiff]), speed=800.0, num_modes=6).wd
    np.testing.assert_allclose(got, grounded, rtol=1e-6)


def test_foundation_model_files_read_npy_and_matrix_market(tmp_path) -> None:
    m, c, k = _pedestal_matrices()
    np.save(tmp_path / "M.npy", m)
    scipy.io.mmwrite(str(tmp_path / "K.mtx"), sp.coo_matrix(k))
    np.save(tmp_path / "C.npy", c)
    with open(MODELS / "default.toml", "rb") as stream:
        data = tomllib.load(stream)
    data.pop("rolling_bearings")
    data["analyses"] = []
    n = 25  # housing nodes after the 25 shaft nodes of the default model
    data["bearings"] = [{"tag": "DE", "z": "0 mm", "n_link": n, "kxx": 2e7, "kzz": 1e8},
                        {"tag": "NDE", "z": "1500 mm", "n_link": n + 1, "kxx": 2e7}]
    data["foundations"] = [{"tag": "frame", "connections": [{"node": n}, {"node": n + 1}],
                            "dofs": ["ux", "uy", "uz"], "mass": "M.npy",
                            "stiffness": "K.mtx", "damping": "C.npy"}]
    path = tmp_path / "framed.toml"
    model = model_from_dict(data, source=path)
    (foundation,) = model.rotor.foundations
    np.testing.assert_array_equal(foundation.K, k)
    assert foundation.dofs[3] == (n + 1, "ux")
    modes = rs.modal(model.rotor, speed=0.0, num_modes=4)
    assert np.all(modes.wn > 0)


@pytest.mark.parametrize(("matrix", "message"), [
    (np.array([[1.0, 2.0], [0.0, 1.0]]), "K is not symmetric: entry"),
    (np.array([[1.0, 0.0], [0.0, -1.0]]), "K is not positive semi-definite"),
    (np.eye(3), r"K must be \(2, 2\)"),
    (np.array([[1.0, np.nan], [np.nan, 1.0]]), "non-finite"),
])
def test_bad_foundation_matrices_are_named(matrix, message) -> None:
    with pytest.raises(ModelError, match=message):
        Foundation([(0, "ux"), (0, "uy")], M=np.eye(2), K=matrix, tag="frame")


def test_bad_foundation_inputs_are_named(tmp_path) -> None:
    with pytest.raises(ModelError, match="connection DOF is listed twice"):
        Foundation([(0, "ux"), (0, "ux")], M=np.eye(2), K=np.eye(2))
    with pytest.raises(ModelError, match="3 modes for 2 connection DOFs"):
        Foundation.from_modal([(0, "ux"), (0, "uy")], [1.0, 2.0, 3.0], [0.0] * 3,
                              np.ones((2, 3)))
    with pytest.raises(ModelError, match="no file"):
        Foundation.from_files([(0, "ux")], tmp_path / "missing.npy", tmp_path / "K.npy")
    with pytest.raises(ModelError, match="linearly dependent"):
        Foundation.from_modal([(0, "ux"), (0, "uy")], [1.0, 2.0], [0.0, 0.0],
                              np.ones((2, 2)))
    assert math.isfinite(Foundation([(0, "ux")], M=[[1.0]], K=[[1.0]]).matrices().M.sum())
