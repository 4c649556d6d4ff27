"""VTK export: meshio reads back the shaft line with the expected point, cell and field data."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import meshio
import numpy as np
import pytest

from rotorsim.analyses.linear.campbell import campbell
from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.analyses.linear.frequency_response import frequency_response, unbalance_response
from rotorsim.analyses.linear.modal import modal
from rotorsim.analyses.statics.static import static
from rotorsim.elements.disk import DiskElement, PointMass
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.io.hdf5 import load, save
from rotorsim.io.vtk import export_vtk
from rotorsim.model.material import steel
from rotorsim.model.rotor import Rotor
from rotorsim.results.orbits import ellipse

N_EL = 5
OD = np.array([0.04, 0.05, 0.06, 0.05, 0.04])  # stepped shaft [m]


@pytest.fixture(scope="module")
def rotor() -> Rotor:
    """A stepped shaft whose left bearing sits in a housing (node 6) on a pedestal."""
    shaft = [ShaftElement(L=0.2, idl=0.0, odl=d, material=steel) for d in OD]
    disks = [DiskElement.from_geometry(2, steel, width=0.05, i_d=0.05, o_d=0.25)]
    bearings = [BearingElement(n=0, kxx=2e6, kzz=1e6, cxx=200.0, n_link=N_EL + 1),
                BearingElement(n=N_EL + 1, kxx=5e7, kzz=5e7, cxx=500.0),
                BearingElement(n=N_EL, kxx=2e6, kyy=1e6, cxx=200.0)]
    return Rotor(shaft, disks, bearings, [PointMass(n=N_EL + 1, m=8.0)], tag="vtk_test")


def _node_vectors(values: np.ndarray) -> np.ndarray:
    """(ndof, ...) on all DOFs -> (n_nodes, 6, ...)."""
    return values.reshape(-1, 6, *values.shape[1:])


def _pvd_files(pvd: Path) -> list[tuple[str, Path]]:
    root = ET.parse(pvd).getroot()
    assert root.get("type") == "Collection"
    return [(d.get("timestep"), pvd.parent / d.get("file"))
            for d in root.iter("DataSet")]


def _check_line(mesh: meshio.Mesh, rotor: Rotor) -> None:
    np.testing.assert_array_equal(mesh.points[:, 2], rotor.nodes_pos)
    np.testing.assert_array_equal(mesh.points[:, :2], 0.0)
    assert mesh.points[N_EL + 1, 2] == mesh.points[0, 2]  # housing at its shaft node
    blocks = {c.type: c.data for c in mesh.cells}
    np.testing.assert_array_equal(blocks["line"], np.column_stack([np.arange(N_EL),
                                                                   np.arange(1, N_EL + 1)]))
    np.testing.assert_array_equal(blocks["vertex"], [[N_EL + 1]])


def test_modal_time_series(rotor, tmp_path):
    m = modal(rotor, speed=200.0, num_modes=5)
    files = export_vtk(m, tmp_path / "modes.pvd", rotor=rotor)
    steps = _pvd_files(files[0])
    assert [s for s, _ in steps] == ["0", "1", "2", "3", "4"]
    assert [p for _, p in steps] == files[1:] and all(p.is_file() for p in files)
    shapes = _node_vectors(m.mode_shapes)
    for k, (_, path) in enumerate(steps):
        mesh = meshio.read(path)
        _check_line(mesh, rotor)
        pd = mesh.point_data
        assert pd["displacement"].shape == (rotor.n_nodes, 3)
        np.testing.assert_array_equal(pd["displacement"], shapes[:, :3, k].real)
        np.testing.assert_array_equal(pd["displacement_imag"], shapes[:, :3, k].imag)
        np.testing.assert_array_equal(pd["displacement_amplitude"], np.abs(shapes[:, :3, k]))
        np.testing.assert_array_equal(pd["rotation"], shapes[:, 3:, k].real)
        np.testing.assert_array_equal(pd["rotation_imag"], shapes[:, 3:, k].imag)
        np.testing.assert_array_equal(pd["orbit_major"], m.orbit(k, slice(None)).major)
        np.testing.assert_array_equal(pd["node"], np.arange(rotor.n_nodes))
        for key in ("wn", "wd", "log_dec"):
            np.testing.assert_array_equal(mesh.field_data[key], [getattr(m, key)[k]])
        np.testing.assert_array_equal(mesh.field_data["speed"], [200.0])


def test_radius_is_the_larger_neighbouring_outer_radius(rotor, tmp_path):
    m = modal(rotor, speed=0.0, num_modes=2)
    mesh = meshio.read(export_vtk(m, tmp_path / "m.vtu", rotor=rotor)[0])
    # nodes 0..5 of a stepped shaft 40/50/60/50/40 mm; the housing node has no shaft
    np.testing.assert_array_equal(mesh.point_data["radius"],
                                  [0.02, 0.025, 0.03, 0.03, 0.025, 0.02, 0.0])


def test_modal_single_file_has_one_field_per_mode(rotor, tmp_path):
    m = modal(rotor, speed=0.0, num_modes=3)
    files = export_vtk(m, tmp_path / "modes.vtu")  # shaft nodes from result.summary
    assert files == [tmp_path / "modes.vtu"]
    mesh = meshio.read(files[0])
    _check_line(mesh, rotor)
    shapes = _node_vectors(m.mode_shapes)
    for k in range(3):
        np.testing.assert_array_equal(mesh.point_data[f"mode_{k}"], shapes[:, :3, k].real)
        np.testing.assert_array_equal(mesh.point_data[f"mode_{k}_imag"], shapes[:, :3, k].imag)
        np.testing.assert_array_equal(mesh.point_data[f"mode_{k}_rotation"],
                                      shapes[:, 3:, k].real)
        np.testing.assert_array_equal(mesh.field_data[f"mode_{k}_wn"], [m.wn[k]])
    assert "radius" not in mesh.point_data and "mode_3" not in mesh.point_data


def test_frequency_response_one_step_per_frequency(rotor, tmp_path):
    speeds = np.linspace(50.0, 500.0, 4)
    u = unbalance_response(rotor, speeds, unbalance=[(2, 1e-4, 0.3)])
    files = export_vtk(u, tmp_path / "unbalance.pvd", rotor=rotor)
    steps = _pvd_files(files[0])
    assert len(steps) == speeds.size
    resp = _node_vectors(u.response[:, :, 0].T)  # (n_nodes, 6, F)
    for k, (_, path) in enumerate(steps):
        mesh = meshio.read(path)
        pd = mesh.point_data
        np.testing.assert_array_equal(pd["displacement"], resp[:, :3, k].real)
        np.testing.assert_array_equal(pd["displacement_imag"], resp[:, :3, k].imag)
        np.testing.assert_array_equal(pd["displacement_amplitude"], np.abs(resp[:, :3, k]))
        major = ellipse(resp[:, 0, k], resp[:, 1, k]).major
        np.testing.assert_array_equal(pd["orbit_major"], major)
        np.testing.assert_array_equal(mesh.field_data["frequency"], [speeds[k]])
    # the disk orbit at the last speed is the response amplitude the result reports
    assert pd["orbit_major"][2] == pytest.approx(u.orbit(2).major[-1], rel=1e-15)


def test_receptance_input_column(rotor, tmp_path):
    f = frequency_response(rotor, [100.0, 300.0], inputs=[(2, "ux"), (3, "uy")], speed=100.0)
    mesh = meshio.read(export_vtk(f, tmp_path / "r.vtu", input=1)[0])
    np.testing.assert_array_equal(mesh.point_data["freq_1_imag"],
                                  _node_vectors(f.response[1, :, 1])[:, :3].imag)
    with pytest.raises(ModelError, match=r"input 2 outside 0\.\.1"):
        export_vtk(f, tmp_path / "r.vtu", input=2)


def test_static_displacement_and_section_forces(rotor, tmp_path):
    s = static(rotor, loads=[(3, "ux", 100.0)])
    (path,) = export_vtk(s, tmp_path / "static.vtu", rotor=rotor)
    mesh = meshio.read(path)
    _check_line(mesh, rotor)
    q = _node_vectors(s.displacement)
    np.testing.assert_array_equal(mesh.point_data["displacement"], q[:, :3])
    np.testing.assert_array_equal(mesh.point_data["rotation"], q[:, 3:])
    np.testing.assert_array_equal(mesh.point_data["load_force"],
                                  _node_vectors(s.load)[:, :3])
    line = next(i for i, c in enumerate(mesh.cells) if c.type == "line")
    vertex = 1 - line
    force = mesh.cell_data["section_force_start"]
    np.testing.assert_array_equal(force[line][:, :2], s.shear_force[:, 0, :])
    np.testing.assert_array_equal(force[line][:, 2], s.axial_force[:, 0])
    assert np.isnan(force[vertex]).all()
    moment = mesh.cell_data["section_moment_end"][line]
    np.testing.assert_array_equal(moment[:, :2], s.bending_moment[:, 1, :])
    np.testing.assert_array_equal(moment[:, 2], s.torque[:, 1])


def test_exact_critical_speeds_and_a_loaded_result(rotor, tmp_path):
    cs = critical_speeds(rotor, num_modes=2)
    files = export_vtk(cs, tmp_path / "cs.pvd", rotor=rotor)
    mesh = meshio.read(files[2])
    np.testing.assert_array_equal(mesh.field_data["critical_speed"], [cs.speed[1]])
    np.testing.assert_array_equal(mesh.point_data["displacement"],
                                  _node_vectors(cs.mode_shapes)[:, :3, 1].real)
    m = load(save(modal(rotor, num_modes=2), tmp_path / "m.h5"))
    assert len(export_vtk(m, tmp_path / "loaded.pvd")) == 3


BAD: dict[str, Any] = {
    "campbell": (lambda r: campbell(r, [0.0, 100.0], num_modes=2), "x.pvd", {},
                 "cannot export a CampbellResult"),
    "no shapes": (lambda r: campbell(r, np.linspace(0, 800, 9), num_modes=2).critical_speeds(),
                  "x.pvd", {}, "no mode shapes"),
    "no positions": (lambda r: critical_speeds(r, num_modes=1), "x.pvd", {},
                     "pass rotor="),
    "suffix": (lambda r: modal(r, num_modes=1), "x.vtk", {}, r"\.pvd or \.vtu"),
    "other rotor": (lambda r: modal(r, num_modes=1), "x.pvd",
                    {"rotor": Rotor([ShaftElement(L=0.1, idl=0.0, odl=0.02, material=steel)])},
                    "rotor has 2 nodes, the result 7"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_requests_raise_model_error(rotor, tmp_path, case):
    make, name, kwargs, message = BAD[case]
    with pytest.raises(ModelError, match=message):
        export_vtk(make(rotor), tmp_path / name, **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_missing_folders_are_created(rotor, tmp_path):
    target = tmp_path / "new" / "deeper" / "modes.pvd"
    files = export_vtk(modal(rotor, num_modes=2), target, rotor=rotor)
    assert files[0] == target and all(f.is_file() for f in files) and len(files) == 3
    with pytest.raises(ModelError, match="export_vtk"):  # a bad request creates nothing
        export_vtk(modal(rotor, num_modes=1), tmp_path / "other" / "x.vtk")
    assert not (tmp_path / "other").exists()
    (tmp_path / "blocker").write_text("a file where a folder is needed")
    with pytest.raises(ModelError, match="a file of that name is in the way"):
        export_vtk(modal(rotor, num_modes=1), tmp_path / "blocker" / "x.vtu", rotor=rotor)
