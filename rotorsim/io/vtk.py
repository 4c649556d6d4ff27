"""Export mode shapes, harmonic responses and static deflections to VTK for ParaView.

The shaft line is an unstructured grid written with meshio: one point per node at
``(0, 0, z)`` [m], ``line`` cells between consecutive shaft nodes and ``vertex`` cells for
off-shaft (housing) nodes, which sit at the ``z`` of their shaft node. Two outputs:

* ``*.pvd``: a ParaView collection with one VTU per mode or frequency
  (``<stem>_0000.vtu``, ``<stem>_0001.vtu``, ... beside it; time step = index). Every step
  carries the same array names, so the time slider walks through modes or frequencies.
* ``*.vtu``: one file; every mode/frequency ``k`` gets its own arrays, named with the
  prefix ``mode_<k>`` (modes, critical speeds) or ``freq_<k>`` (responses).

Point data of a step (3-vectors are x, y, z components):

=========================== ==================================================
``displacement``            real part of ``(ux, uy, uz)`` [m; modes normalised]
``displacement_imag``       imaginary part
``displacement_amplitude``  ``|ux|, |uy|, |uz|``
``rotation``, ``rotation_imag``  real/imaginary ``(rx, ry, rz)`` [rad]
``orbit_major``             major semi-axis of the lateral orbit [m]
``node``                    node number
``radius``                  outer shaft radius at the node [m] (with ``rotor=``)
=========================== ==================================================

A transient (:class:`~rotorsim.results.transient.TransientResult`) gives one step per kept
time sample (every ``every``-th), the ``*.pvd`` time step being the time [s]: point data
``displacement`` and ``rotation`` hold the kept DOFs and zero at DOFs that were not kept,
and ``kept`` (per node: 1 if any of its DOFs was kept) tells the two apart; field data hold
``time`` [s], ``speed`` [rad/s] and ``angle`` [rad].

In the single-file form ``displacement`` becomes ``mode_<k>``, ``displacement_imag``
``mode_<k>_imag`` and any other array ``X`` becomes ``mode_<k>_X``. A static result has
``displacement``, ``rotation``, ``load_force`` [N], ``load_moment`` [N m] and, when section
forces are known, cell data ``section_force_start``/``_end`` = ``(V_x, V_y, N)`` [N] and
``section_moment_start``/``_end`` = ``(M_x, M_y, M_z)`` [N m] at the element ends. Field data
hold the step's scalars (``wn``, ``wd``, ``log_dec``, ``frequency``, ``speed`` [rad/s]).

meshio is imported when a file is written, not with this module.
"""

from __future__ import annotations

import base64
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.io.output_folder import prepare_folder
from rotorsim.model.rotor import Rotor
from rotorsim.results.critical_speeds import CriticalSpeeds
from rotorsim.results.frequency_response import FrequencyResponseResult
from rotorsim.results.modal import ModalResult
from rotorsim.results.orbits import ellipse
from rotorsim.results.static import StaticResult
from rotorsim.results.transient import TransientResult

__all__ = ["export_vtk"]

FloatArray = NDArray[np.float64]
_WHERE = "export_vtk"


@dataclass(frozen=True)
class _Geometry:
    points: FloatArray  # (n_nodes, 3)
    cells: list[tuple[str, NDArray[np.int64]]]
    point_data: dict[str, NDArray[Any]]


@dataclass(frozen=True)
class _Step:
    point_data: dict[str, NDArray[Any]]
    field_data: dict[str, NDArray[Any]] = field(default_factory=dict)
    cell_data: dict[str, list[NDArray[Any]]] = field(default_factory=dict)


def export_vtk(
    result: ModalResult | CriticalSpeeds | FrequencyResponseResult | StaticResult |
    TransientResult,
    path: str | os.PathLike[str],
    *,
    rotor: Rotor | None = None,
    input: int = 0,
    every: int = 1,
) -> list[Path]:
    """Write the shaft line with mode shapes or deflections as VTK point data.

    Parameters
    ----------
    result : ModalResult, CriticalSpeeds, FrequencyResponseResult, StaticResult or
        TransientResult
        ``CriticalSpeeds`` needs mode shapes (exact analysis) and ``rotor``.
    path : path-like
        ``*.pvd`` for a time series (one VTU per mode/frequency/time sample), ``*.vtu`` for
        one file; missing folders are created.
    rotor : Rotor, optional
        The analysed model: adds the ``radius`` point data and supplies node positions
        and the number of shaft nodes (else taken from ``result.summary``).
    input : int
        Input column of a :class:`FrequencyResponseResult`.
    every : int
        Time-sample stride of a :class:`TransientResult` (one VTU per ``every`` samples,
        and one for the final sample).

    Returns
    -------
    list of Path
        The files written; for ``*.pvd`` the collection first.

    Examples
    --------
    >>> import tempfile
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    >>> rotor = rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=1e6),
    ...                              rs.BearingElement(n=4, kxx=1e6)])
    >>> modes = rs.modal(rotor, speed=0.0, num_modes=4)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     files = export_vtk(modes, Path(folder) / "modes.pvd", rotor=rotor)
    ...     names = [f.name for f in files]
    >>> names
    ['modes.pvd', 'modes_0000.vtu', 'modes_0001.vtu', 'modes_0002.vtu', 'modes_0003.vtu']
    """
    target = Path(path)
    suffix = target.suffix.lower()
    if suffix not in (".pvd", ".vtu"):
        raise ModelError(f"file must end in .pvd or .vtu, got {target.name!r}", _WHERE)
    geometry = _geometry(result, rotor)
    prepare_folder(target, _WHERE)
    times = None
    if isinstance(result, TransientResult):
        steps, prefix, times = _transient_steps(result, geometry, every)
    else:
        steps, prefix = _steps(result, input, geometry)
    if suffix == ".vtu":
        _write_vtu(target, geometry, _merge(steps, prefix))
        return [target]
    files = [target.with_name(f"{target.stem}_{k:04d}.vtu") for k in range(len(steps))]
    for file, step in zip(files, steps, strict=True):
        _write_vtu(file, geometry, step)
    _write_pvd(target, files, times)
    return [target, *files]


# ---------------------------------------------------------------------------- geometry
def _geometry(result: object, rotor: Rotor | None) -> _Geometry:
    if not isinstance(result, ModalResult | CriticalSpeeds | FrequencyResponseResult |
                      StaticResult | TransientResult):
        raise ModelError(
            f"cannot export a {type(result).__name__}; supported: ModalResult, CriticalSpeeds "
            "(with mode shapes), FrequencyResponseResult, StaticResult, TransientResult",
            _WHERE)
    dof_map = result.dof_map
    if dof_map is None:
        raise ModelError("the result has no mode shapes (use the exact critical_speeds)",
                         _WHERE)
    n_nodes = dof_map.n_nodes
    if rotor is not None and rotor.n_nodes != n_nodes:
        raise ModelError(f"rotor has {rotor.n_nodes} nodes, the result {n_nodes}", _WHERE)
    z = getattr(result, "nodes_pos", None)
    if z is None:
        if rotor is None:
            raise ModelError(f"{type(result).__name__} holds no node positions: pass rotor=",
                             _WHERE)
        z = rotor.nodes_pos
    n_shaft = _shaft_nodes(result, rotor, n_nodes)
    points = np.zeros((n_nodes, 3))
    points[:, 2] = z
    starts = _element_starts(dof_map.node_names, n_shaft)
    cells = [("line", np.column_stack([starts, starts + 1]))] if starts.size else []
    first_vertex = n_shaft if starts.size else 0  # a rigid rotor's node 0 is a vertex
    if n_nodes > first_vertex:
        cells.append(("vertex", np.arange(first_vertex, n_nodes, dtype=np.int64)[:, None]))
    data: dict[str, NDArray[Any]] = {"node": np.arange(n_nodes, dtype=np.int64)}
    if dof_map.node_names:  # a machine: the line of every node (-1 off the lines)
        names = [n.split(":")[0] if n else "" for n in dof_map.node_names]
        order = list(dict.fromkeys(n for n in names if n))
        data["line"] = np.array([order.index(n) if n else -1 for n in names], dtype=np.int64)
    if rotor is not None:
        data["radius"] = _outer_radius(rotor)
    return _Geometry(points, cells, data)


def _element_starts(node_names: tuple[str, ...], n_shaft: int) -> NDArray[np.int64]:
    """First node of every shaft element: consecutive nodes of one line (every consecutive
    pair on a one-line rotor; on a machine, pairs whose ``"LINE:local"`` names share the
    line)."""
    starts = np.arange(n_shaft - 1, dtype=np.int64)
    if not node_names:
        return starts
    line = [n.split(":")[0] for n in node_names]
    return np.array([i for i in starts if line[i] and line[i] == line[i + 1]],
                    dtype=np.int64)


def _shaft_nodes(result: Any, rotor: Rotor | None, n_nodes: int) -> int:
    if rotor is not None:
        return int(rotor.n_shaft_nodes)
    elements = result.summary.get("shaft_elements")
    if elements is None:
        raise ModelError("result.summary has no 'shaft_elements': pass rotor=", _WHERE)
    n_shaft = int(elements) + 1
    if not 1 <= n_shaft <= n_nodes:
        raise ModelError(f"{n_shaft} shaft nodes do not fit {n_nodes} nodes", _WHERE)
    return n_shaft


def _outer_radius(rotor: Rotor) -> FloatArray:
    """Largest outer radius of the shaft elements meeting at each node; 0 off the shaft."""
    radius = np.zeros(rotor.n_nodes)
    for el in rotor.shaft_elements:  # element n joins nodes n and n + 1 of its line
        n = int(el.nodes[0])
        radius[n] = max(radius[n], float(el.odl) / 2.0)
        radius[n + 1] = max(radius[n + 1], float(el.odr or el.odl) / 2.0)
    return radius


# ---------------------------------------------------------------------------- steps
def _steps(result: Any, input: int, geometry: _Geometry) -> tuple[list[_Step], str]:
    n_nodes = geometry.points.shape[0]
    if isinstance(result, StaticResult):
        return [_static_step(result, geometry)], ""
    if isinstance(result, FrequencyResponseResult):
        if not 0 <= input < result.n_inputs:
            raise ModelError(f"input {input} outside 0..{result.n_inputs - 1}", _WHERE)
        shapes = result.response[:, :, input].reshape(-1, n_nodes, 6)
        scalars = {"frequency": result.frequencies, "speed": result.speeds}
        return _harmonic_steps(shapes, scalars), "freq"
    if result.mode_shapes is None:
        raise ModelError("the result has no mode shapes (use the exact critical_speeds)",
                         _WHERE)
    shapes = np.moveaxis(result.mode_shapes.reshape(n_nodes, 6, -1), 2, 0)
    if isinstance(result, ModalResult):
        scalars = {"wn": result.wn, "wd": result.wd, "log_dec": result.log_dec,
                   "speed": np.full(result.num_modes, result.speed)}
    else:
        scalars = {"critical_speed": result.speed, "frequency": result.frequency}
    return _harmonic_steps(shapes, scalars), "mode"


def _harmonic_steps(shapes: NDArray[np.complex128], scalars: dict[str, FloatArray]
                    ) -> list[_Step]:
    """Steps from complex node vectors ``shapes`` (S, n_nodes, 6) and per-step scalars."""
    u, r = shapes[..., :3], shapes[..., 3:]
    major = ellipse(shapes[..., 0], shapes[..., 1]).major
    arrays = {"displacement": u.real, "displacement_imag": u.imag,
              "displacement_amplitude": np.abs(u), "rotation": r.real,
              "rotation_imag": r.imag, "orbit_major": major}
    return [_Step({k: np.ascontiguousarray(v[s]) for k, v in arrays.items()},
                  {k: np.atleast_1d(np.float64(v[s])) for k, v in scalars.items()})
            for s in range(shapes.shape[0])]


def _transient_steps(result: TransientResult, geometry: _Geometry, every: int
                     ) -> tuple[list[_Step], str, FloatArray]:
    """One step per ``every``-th sample and the last one: kept DOFs in place, zeros
    elsewhere."""
    if not (isinstance(every, int) and every >= 1):
        raise ModelError(f"every must be a positive int, got {every!r}", _WHERE)
    n_nodes = geometry.points.shape[0]
    rows = np.arange(0, result.t.size, every)
    if rows[-1] != result.t.size - 1:  # the final sample always: the series ends at t_end
        rows = np.append(rows, result.t.size - 1)
    full = np.zeros((rows.size, 6 * n_nodes))
    full[:, result.dofs] = result.q[rows]
    nodes = full.reshape(rows.size, n_nodes, 6)
    kept = np.zeros(n_nodes, dtype=np.int64)
    kept[result.dofs // 6] = 1
    steps = [_Step({"displacement": np.ascontiguousarray(nodes[s, :, :3]),
                    "rotation": np.ascontiguousarray(nodes[s, :, 3:]), "kept": kept},
                   {"time": np.atleast_1d(result.t[r]), "speed": np.atleast_1d(result.speed[r]),
                    "angle": np.atleast_1d(result.angle[r])})
             for s, r in enumerate(rows)]
    return steps, "step", result.t[rows]


def _static_step(result: StaticResult, geometry: _Geometry) -> _Step:
    q = result.displacement.reshape(-1, 6)
    f = result.load.reshape(-1, 6)
    point = {"displacement": q[:, :3], "rotation": q[:, 3:], "load_force": f[:, :3],
             "load_moment": f[:, 3:]}
    shear, moment = result.shear_force, result.bending_moment
    axial, torque = result.axial_force, result.torque
    cell: dict[str, list[NDArray[Any]]] = {}
    lines = bool(geometry.cells) and geometry.cells[0][0] == "line"  # none: a rigid rotor
    if lines and shear is not None and moment is not None and axial is not None \
            and torque is not None:
        n_lines = geometry.cells[0][1].shape[0]
        if shear.shape[0] != n_lines:
            raise ModelError(f"{shear.shape[0]} section forces for {n_lines} shaft elements",
                             _WHERE)
        for end, label in ((0, "start"), (1, "end")):
            force = np.column_stack([shear[:, end, 0], shear[:, end, 1], axial[:, end]])
            mom = np.column_stack([moment[:, end, 0], moment[:, end, 1], torque[:, end]])
            cell[f"section_force_{label}"] = _per_block(force, geometry)
            cell[f"section_moment_{label}"] = _per_block(mom, geometry)
    return _Step(point, {"speed": np.atleast_1d(np.float64(result.speed))}, cell)


def _per_block(line_values: FloatArray, geometry: _Geometry) -> list[FloatArray]:
    """Cell data for every cell block: values on the lines, NaN on housing vertices."""
    blocks = [line_values]
    for _, cells in geometry.cells[1:]:
        blocks.append(np.full((cells.shape[0], line_values.shape[1]), np.nan))
    return blocks


def _merge(steps: list[_Step], prefix: str) -> _Step:
    """One step holding every step's arrays under ``<prefix>_<k>`` names."""
    if len(steps) == 1 and not prefix:
        return steps[0]
    point: dict[str, NDArray[Any]] = {}
    fields: dict[str, NDArray[Any]] = {}
    for k, step in enumerate(steps):
        name = f"{prefix}_{k}"
        for key, value in step.point_data.items():
            point[_renamed(key, name)] = value
        for key, value in step.field_data.items():
            fields[f"{name}_{key}"] = value
    return _Step(point, fields)


def _renamed(key: str, name: str) -> str:
    if key == "displacement":
        return name
    if key == "displacement_imag":
        return f"{name}_imag"
    return f"{name}_{key}"


# ---------------------------------------------------------------------------- writing
def _write_vtu(path: Path, geometry: _Geometry, step: _Step) -> None:
    import meshio

    mesh = meshio.Mesh(
        geometry.points, geometry.cells,
        point_data={**geometry.point_data, **step.point_data}, cell_data=step.cell_data,
    )
    meshio.write(path, mesh, file_format="vtu", binary=True, compression=None)
    if step.field_data:
        _add_field_data(path, step.field_data)


def _add_field_data(path: Path, field_data: dict[str, NDArray[Any]]) -> None:
    """Insert a ``FieldData`` block into a VTU written by meshio (whose VTU writer drops
    field data). Arrays are Float64 in VTK's uncompressed binary form: base64 of a UInt32
    byte count followed by the values, native byte order as declared in the file."""
    import xml.etree.ElementTree as ET  # slow to import: on first use

    tree = ET.parse(path)
    grid = tree.getroot().find("UnstructuredGrid")
    if grid is None:
        raise ModelError(f"{path.name}: no UnstructuredGrid written", _WHERE)
    block = ET.Element("FieldData")
    for name, values in field_data.items():
        data = np.ascontiguousarray(values, dtype=np.float64).ravel()
        array = ET.SubElement(block, "DataArray", type="Float64", Name=name,
                              NumberOfTuples=str(data.size), format="binary")
        raw = np.uint32(data.nbytes).tobytes() + data.tobytes()
        array.text = base64.b64encode(raw).decode()
    grid.insert(0, block)
    tree.write(path, encoding="utf-8", xml_declaration=True)


def _write_pvd(path: Path, files: list[Path], times: FloatArray | None = None) -> None:
    """Collection of ``files``; time step = index, or ``times`` [s] (exact repr)."""
    import xml.etree.ElementTree as ET  # slow to import: on first use

    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    collection = ET.SubElement(root, "Collection")
    for k, file in enumerate(files):
        step = str(k) if times is None else repr(float(times[k]))
        ET.SubElement(collection, "DataSet", timestep=step, group="", part="0",
                      file=file.name)
    ET.indent(root)
    ET.ElementTree(root).write(path, encoding="utf-8", xml_declaration=True)
