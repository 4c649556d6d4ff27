"""Machines of several lines in results files, VTK, the CLI and the periodic analysis
(issue 15)."""

from __future__ import annotations

from pathlib import Path

import h5py
import meshio
import numpy as np
import pytest

import rotorsim as rs
from rotorsim.cli.main import main
from rotorsim.errors import ModelError

MODELS = Path(__file__).resolve().parents[2] / "models"


@pytest.fixture(scope="module")
def machine() -> rs.Model:
    return rs.load_model(MODELS / "two_spool.toml")


def test_results_files_label_dofs_by_line_node_and_dof(machine, tmp_path: Path) -> None:
    rotor = machine.rotor
    result = rs.unbalance_response(rotor, [100.0, 900.0], machine.loads.unbalance)
    path = tmp_path / "unbalance.h5"
    rs.save(result, path)
    hp3 = rotor.node("HP", 3)
    with h5py.File(path) as f:
        labels = f["result/dof_map/dof_labels"].asstr()[()]
    assert labels[6 * hp3 + 1] == f"node {hp3} (HP:3) uy"
    assert labels[6 * (rotor.n_nodes - 1)] == f"node {rotor.n_nodes - 1} ux"  # a pedestal
    back = rs.load(path)
    assert back.dof_map.node_names == result.dof_map.node_names
    np.testing.assert_array_equal(back.input_ratios, [1.0, 1.45])
    np.testing.assert_array_equal(back.response, result.response)


def test_transient_results_label_their_kept_dofs_by_line(machine) -> None:
    rotor = machine.rotor
    hp3 = rotor.node("HP", 3)
    result = rs.transient(rotor, speed=300.0, t_end=2e-3, dt=1e-4,
                          unbalance=[(rotor.node("LP", 1), 1e-4, 0.0)], nodes=[hp3])
    assert f"node {hp3} (HP:3) uy" in result.dof_labels


def test_vtk_writes_every_line_as_its_own_polyline(machine, tmp_path: Path) -> None:
    rotor = machine.rotor
    modes = rs.modal(rotor, speed=500.0, num_modes=3)
    rs.export_vtk(modes, tmp_path / "modes.pvd", rotor=rotor)
    mesh = meshio.read(tmp_path / "modes_0000.vtu")
    lines = mesh.cells_dict["line"]
    assert len(lines) == len(rotor.shaft_elements)
    line_of = mesh.point_data["line"]
    assert np.all(line_of[lines[:, 0]] == line_of[lines[:, 1]])  # no cell joins two lines
    assert set(line_of.tolist()) == {-1, 0, 1, 2}


def test_info_lists_the_lines(capsys) -> None:
    assert main(["info", str(MODELS / "two_spool.toml")]) == 0
    out = capsys.readouterr().out
    assert "line HP" in out and "speed ratio 1.45" in out and "line casing" in out


def test_periodic_refuses_the_two_spool_unbalance_of_a_linear_machine(machine) -> None:
    """On a nonlinear machine it is a torus (tests/analyses/test_quasi_periodic_spools.py);
    on this linear one it is the sum of two unbalance responses."""
    rotor, loads = machine.rotor, machine.loads
    with pytest.raises(ModelError, match=r"quasi-periodic.*rs\.unbalance_response"):
        rs.periodic(rotor, start=200.0, stop=210.0, unbalance=list(loads.unbalance),
                    harmonics=1)


def test_sweeps_and_critical_speed_maps_run_on_a_machine(machine) -> None:
    from rotorsim.analyses.sweep.functions import min_log_dec, set_bearing_stiffness

    rotor = machine.rotor
    inter = [b.tag for b in rotor.bearing_elements].index("inter_shaft")
    result = rs.sweep(rotor, rs.Grid({"bearing_k": [5e6, 2e7, 8e7], "speed": [900.0]}),
                      set_bearing_stiffness(inter), min_log_dec(num_modes=6))
    assert np.all(np.isfinite(result.outputs["log_dec_min"]))
    # a stiffer inter-shaft bearing stiffens the coupled spools' modes
    assert np.all(np.diff(result.outputs["wd"][:, 1]) > 0)
    table = rs.critical_speed_map(rotor, (1e6, 1e9), num_points=6, num_modes=3,
                                  bearings=[inter])
    assert table.critical_speeds.shape == (6, 3)
    assert np.all(np.diff(table.critical_speeds[:, 0]) >= 0)  # stiffer: not lower


def test_a_saved_machine_reloads_to_the_same_matrices(machine, tmp_path: Path) -> None:
    path = rs.save_model(machine, tmp_path / "saved.toml")
    again = rs.load_model(path)
    assert [line.name for line in again.rotor.layout.lines] == ["LP", "HP", "casing"]
    before, after = (rs.assemble(m.rotor).matrices(500.0) for m in (machine, again))
    for key in "MCGK":  # the same elements: the same sums, entry by entry
        np.testing.assert_array_equal(getattr(after, key).toarray(),
                                      getattr(before, key).toarray())
    assert again.loads.unbalance == machine.loads.unbalance
    assert again.rotor.damping == machine.rotor.damping
