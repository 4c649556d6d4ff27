"""HDF5 results label their DOFs ("node 8 uy"), so readers without rotorsim find a DOF
without computing ``6 * node + k`` (issue 12)."""

from __future__ import annotations

import h5py
import numpy as np
import pytest

import rotorsim as rs

steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


@pytest.fixture(scope="module")
def rotor() -> rs.Rotor:
    shaft = [rs.ShaftElement(L=0.1, idl=0.0, odl=0.05, material=steel) for _ in range(10)]
    return rs.Rotor(shaft, [rs.DiskElement(n=8, m=5.0, Id=0.02, Ip=0.04)],
                    [rs.BearingElement(n=0, kxx=1e7, cxx=1e3),
                     rs.BearingElement(n=10, kxx=1e7, cxx=1e3)])


def labels(ds: h5py.Dataset) -> list[str]:
    return list(ds.asstr()[()])


def test_transient_columns_are_labelled(rotor, tmp_path):
    result = rs.transient(rotor, 0.01, 1e-4, speed=300.0, unbalance=[(8, 1e-4, 0.0)],
                          excitation=rs.Excitation(gravity=None), initial="zero", nodes=[8, 3])
    path = rs.save(result, tmp_path / "run.h5")
    with h5py.File(path) as f:
        g = f["result"]
        names = labels(g["dof_labels"])
        assert len(names) == g["q"].shape[1] == g["dofs"].shape[0]
        col = names.index("node 8 uy")
        assert g["dofs"][col] == 6 * 8 + 1
        np.testing.assert_array_equal(g["q"][:, col], result.node_displacement(8)[:, 1])
        assert np.any(g["q"][:, col] != 0.0)
        assert names == result.dof_labels  # the same labels in memory and in the file
        everything = labels(g["dof_map"]["dof_labels"])
        assert len(everything) == 6 * rotor.n_nodes and everything[49] == "node 8 uy"
    assert rs.load(path).dof_labels == result.dof_labels  # loading ignores the labels


def test_modal_rows_are_labelled(rotor, tmp_path):
    modes = rs.modal(rotor, num_modes=4)
    path = rs.save({"modes": modes}, tmp_path / "modes.h5")
    with h5py.File(path) as f:
        g = f["results/modes"]
        row = labels(g["dof_map"]["dof_labels"]).index("node 3 rx")
        assert row == 6 * 3 + 3
        np.testing.assert_array_equal(g["mode_shapes"][row], modes.mode_shapes[row])
    back = rs.load(path)["modes"]
    np.testing.assert_array_equal(back.mode_shapes, modes.mode_shapes)


def test_one_function_spells_both_label_forms():
    from rotorsim.assembly.dof_map import dof_label
    from rotorsim.results.dof_access import KeptDofs

    assert rs.DofMap(9).names()[49] == dof_label(49, short=True) == "8:uy"
    assert dof_label(np.int64(49)) == "node 8 uy"
    assert issubclass(rs.TransientResult, KeptDofs) and issubclass(rs.PeriodicResult, KeptDofs)
