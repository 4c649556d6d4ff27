"""Transient results and their spectra: exact HDF5 round trip, units, and the VTK time
series of the kept nodes."""

from __future__ import annotations

import dataclasses
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import h5py
import meshio
import numpy as np
import pytest

from rotorsim.assembly.dof_map import DofMap
from rotorsim.errors import ModelError, Status
from rotorsim.io.hdf5 import load, save
from rotorsim.io.vtk import export_vtk
from rotorsim.results.order_tracking import order_track, waterfall
from rotorsim.results.spectra import amplitude_spectrum, harmonic_fit
from rotorsim.results.transient import TransientResult

N_NODES = 5  # shaft nodes 0..3 and a housing node 4


def _transient(*, bearings: int = 2, velocities: bool = True) -> TransientResult:
    t = np.arange(400) * 1e-3
    speed = 100.0 + 50.0 * t
    angle = 100.0 * t + 25.0 * t**2
    dofs = np.array([6, 7, 12, 13, 15, 24])  # 1:ux 1:uy 2:ux 2:uy 2:rx 4:ux
    q = 1e-5 * np.cos(angle[:, None] + np.arange(dofs.size))
    q[3, 2] = np.nan  # a diverged sample and a signed zero survive bitwise
    q[4, 0] = -0.0
    loads = np.zeros((t.size, bearings, 5))
    loads[:, :, 0] = np.cos(angle)[:, None] * np.arange(1, bearings + 1)
    loads[:, :, 1] = -300.0
    return TransientResult(
        t=t, q=q, v=-q * 3.0 if velocities else None, dofs=dofs, speed=speed, angle=angle,
        acceleration=np.full(t.size, 50.0), bearing_loads=loads,
        bearing_tags=tuple(f"B{i}" for i in range(bearings)),
        bearing_elements=np.array([9, 12][:bearings], dtype=np.int64),
        bearing_kappa=np.array([0.41, 0.38][:bearings]),
        reduced={"max_abs_q": np.abs(q).max(axis=0), "max_v": np.array([1.0, np.inf])}
        if bearings else {},
        dof_map=DofMap(N_NODES, fixed=[2, 5]), nodes_pos=np.array([0.0, 0.2, 0.4, 0.6, 0.0]),
        method="newmark", options={"dt": 1e-3, "tol": np.float64(1e-8), "nodes": (1, 2)},
        stats={"steps": 400, "factorizations": 3, "wall_time": 0.25},
        status=Status.NOT_CONVERGED if bearings else Status.OK,
        summary={"tag": "io_transient", "shaft_elements": 3, "nodes": N_NODES})


def assert_exactly_equal(a: Any, b: Any, path: str = "result") -> None:
    """Same types, dtypes, shapes and bytes (NaN and -0.0 included), dict keys in order."""
    assert type(a) is type(b), f"{path}: {type(a).__name__} != {type(b).__name__}"
    if isinstance(a, DofMap):
        assert a.n_nodes == b.n_nodes, path
        assert_exactly_equal(a.fixed, b.fixed, f"{path}.fixed")
    elif dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            assert_exactly_equal(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}")
    elif isinstance(a, np.ndarray):
        assert (a.dtype, a.shape) == (b.dtype, b.shape), f"{path}: {a.dtype}{a.shape}"
        assert a.tobytes() == b.tobytes(), f"{path}: values differ"
    elif isinstance(a, list | tuple):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            assert_exactly_equal(x, y, f"{path}[{i}]")
    elif isinstance(a, dict):
        assert list(a) == list(b), f"{path}: keys {list(a)} != {list(b)}"
        for key in a:
            assert_exactly_equal(a[key], b[key], f"{path}[{key!r}]")
    elif isinstance(a, float | np.floating):
        assert np.asarray(a).tobytes() == np.asarray(b).tobytes(), f"{path}: {a!r} != {b!r}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


def test_helper_sees_a_changed_sample():
    r = _transient()
    q = r.q.copy()
    q[10, 1] = np.nextafter(q[10, 1], 1.0)
    with pytest.raises(AssertionError, match=r"\.q: values differ"):
        assert_exactly_equal(r, dataclasses.replace(r, q=q))


@pytest.mark.parametrize("kind", ["full", "no_bearings_no_velocities"])
def test_transient_round_trips_exactly(kind, tmp_path):
    r = _transient() if kind == "full" else _transient(bearings=0, velocities=False)
    back = load(save(r, tmp_path / "transient.h5"))
    assert_exactly_equal(r, back)
    assert back.column(2, "uy") == 3 and back.bearing_tags == r.bearing_tags


def test_units_are_written(tmp_path):
    path = save(_transient(), tmp_path / "transient.h5")
    with h5py.File(path, "r") as f:
        g = f["result"]
        assert g.attrs["type"] == "TransientResult"
        units = {k: g[k].attrs.get("units") for k in ("t", "q", "speed", "angle",
                                                       "bearing_loads", "nodes_pos")}
    assert units == {"t": "s", "q": "m, rad", "speed": "rad/s", "angle": "rad",
                     "bearing_loads": "N, N m", "nodes_pos": "m"}


def test_spectral_results_round_trip_exactly(tmp_path):
    r = _transient()
    x = np.nan_to_num(r.q[:, :2])
    results = {
        "spectrum": amplitude_spectrum(r.t, x, t_min=0.1),
        "harmonic": harmonic_fit(r.t, x[:, 0], 100.0),
        "harmonic_columns": harmonic_fit(r.t, x, 100.0),
        "waterfall": waterfall(r.t, x[:, 0], r.speed, segment=0.05),
        "order_track": order_track(r.t, x[:, 0], r.angle, [1.0, 3.69],
                                   revolutions_per_block=2),
        "transient": r,
    }
    back = load(save(results, tmp_path / "all.h5"))
    assert list(back) == list(results)
    for name, value in results.items():
        assert_exactly_equal(value, back[name], name)
    assert isinstance(back["harmonic"].amplitude, np.ndarray)
    assert back["harmonic"].amplitude.shape == ()


# ---------------------------------------------------------------------------- VTK
def _steps(pvd: Path) -> list[tuple[str, Path]]:
    root = ET.parse(pvd).getroot()
    return [(d.get("timestep"), pvd.parent / d.get("file")) for d in root.iter("DataSet")]


def test_vtk_time_series_of_kept_nodes(tmp_path):
    r = _transient()
    files = export_vtk(r, tmp_path / "run.pvd", every=50)
    steps = _steps(files[0])
    rows = np.append(np.arange(0, r.t.size, 50), r.t.size - 1)  # and the final sample
    assert [float(s) for s, _ in steps] == r.t[rows].tolist()  # time steps are times [s]
    assert float(steps[-1][0]) == r.t[-1]
    assert [p for _, p in steps] == files[1:]
    expected_kept = [0, 1, 1, 0, 1]
    for row, (_, path) in zip(rows, steps, strict=True):
        mesh = meshio.read(path)
        np.testing.assert_array_equal(mesh.points[:, 2], r.nodes_pos)
        pd = mesh.point_data
        assert pd["kept"].tolist() == expected_kept
        disp, rot = pd["displacement"], pd["rotation"]
        assert disp.shape == rot.shape == (N_NODES, 3)
        np.testing.assert_array_equal(disp[1, :2], r.q[row, :2])
        np.testing.assert_array_equal(disp[2, :2], r.q[row, 2:4])
        np.testing.assert_array_equal(rot[2], [r.q[row, 4], 0.0, 0.0])
        np.testing.assert_array_equal(disp[4], [r.q[row, 5], 0.0, 0.0])
        np.testing.assert_array_equal(disp[[0, 3]], 0.0)  # not kept: zero, flagged kept=0
        text = path.read_text()
        assert 'Name="time"' in text and 'Name="speed"' in text and 'Name="angle"' in text
    blocks = {c.type: c.data for c in meshio.read(steps[0][1]).cells}
    np.testing.assert_array_equal(blocks["line"], [[0, 1], [1, 2], [2, 3]])
    np.testing.assert_array_equal(blocks["vertex"], [[4]])


def test_vtk_single_file_and_bad_stride(tmp_path):
    r = _transient(bearings=0)
    (path,) = export_vtk(r, tmp_path / "run.vtu", every=200)
    pd = meshio.read(path).point_data
    assert {"step_0", "step_1", "step_0_rotation", "step_1_kept"} <= set(pd)
    np.testing.assert_array_equal(pd["step_1"][1, :2], r.q[200, :2])
    np.testing.assert_array_equal(pd["step_2"][1, :2], r.q[399, :2])  # the final sample
    assert "step_3" not in pd
    with pytest.raises(ModelError, match="every must be a positive int"):
        export_vtk(r, tmp_path / "bad.pvd", every=0)
