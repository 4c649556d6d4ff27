"""Build a :class:`~rotorsim.model.rotor.Rotor`, loads and analysis specs from validated
model-file tables.

This step resolves what the schema cannot check alone: material names, node numbers and
axial positions (``z`` must be a node position within
:data:`~rotorsim.io.model_nodes.Z_TOLERANCE`; :mod:`~rotorsim.io.model_nodes`), housing
nodes, bearing references. Errors name the key path of the culprit
(``disks[1].z: 0.512 m is not a node position; nearest nodes: 2 at 0.5 m, 3 at 0.75 m``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from rotorsim.analyses.statics.linearized_rotor import LinearizationPoint
from rotorsim.elements.disk import DiskElement, PointMass
from rotorsim.elements.foundation import Foundation, read_matrix
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.double_row import DoubleRowBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    StraightProfile,
)
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.io import analysis_spec as spec
from rotorsim.io.model_nodes import Nodes
from rotorsim.io.model_schema import BearingTable, CouplingTable, ModelTable, ShaftSegment
from rotorsim.io.rating_build import mounted_model
from rotorsim.io.rolling_schema import BallTable, ProfileTable, RollerTable, RollingTable
from rotorsim.model.damping import SystemDamping
from rotorsim.model.lines import ShaftLine
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor


def bare(err: ModelError) -> str:
    """Message of ``err`` without its ``where`` prefix."""
    text = str(err)
    prefix = f"{err.where}: " if err.where else ""
    return text[len(prefix):] if text.startswith(prefix) else text


def check_unique_tags(table: ModelTable, rolling: list[RollingTable]) -> None:
    """Refuse a tag used twice among the disks, the point masses, or the bearings and
    rolling bearings together (analyses select bearings by tag). Shaft segments may share
    a tag (a tapered part written element by element)."""
    groups: tuple[tuple[tuple[str, list[Any]], ...], ...] = (
        (("disks", table.disks),),
        (("point_masses", table.point_masses),),
        (("bearings", table.bearings), ("couplings", table.couplings),
         ("rolling_bearings", rolling)),
    )
    for group in groups:
        seen: dict[str, str] = {}
        for section, items in group:
            for i, item in enumerate(items):
                if not item.tag:
                    continue
                here = f"{section}[{i}]"
                if item.tag in seen:
                    raise ModelError(f"duplicate tag {item.tag!r} (also {seen[item.tag]}.tag);"
                                     " tags select elements, so each must be unique",
                                     f"{here}.tag")
                seen[item.tag] = here


def build_materials(table: ModelTable) -> dict[str, Material]:
    out: dict[str, Material] = {}
    for i, mat in enumerate(table.materials):
        if mat.name in out:
            raise ModelError(f"duplicate material '{mat.name}'", f"materials[{i}].name")
        try:
            out[mat.name] = Material(name=mat.name, E=mat.E, rho=mat.rho,
                                     G_s=np.nan if mat.G_s is None else mat.G_s,
                                     nu=np.nan if mat.nu is None else mat.nu)
        except ModelError as err:
            raise ModelError(bare(err), f"materials[{i}]") from None
    return out


def material(materials: dict[str, Material], name: str, where: str) -> Material:
    if name in materials:
        return materials[name]
    known = ", ".join(materials) if materials else "none; add [[materials]]"
    raise ModelError(f"unknown material '{name}' (defined: {known})", where)


def segment_elements(seg: ShaftSegment, mat: Material, where: str) -> list[ShaftElement]:
    """The equal-length elements of one shaft segment; diameters vary linearly along it."""
    n = seg.n_elements
    xi = np.linspace(0.0, 1.0, n + 1)
    idl, odl, idr, odr = seg.diameters

    def along(left: float, right: float) -> np.ndarray:
        d = left + (right - left) * xi
        d[0], d[-1] = left, right
        return d

    inner, outer = along(idl, idr), along(odl, odr)
    try:
        return [
            ShaftElement(L=seg.element_size, idl=float(inner[j]), odl=float(outer[j]),
                         idr=float(inner[j + 1]), odr=float(outer[j + 1]), material=mat,
                         shear_effects=seg.shear_effects, rotary_inertia=seg.rotary_inertia,
                         gyroscopic=seg.gyroscopic, axial_force=seg.axial_force,
                         shear_coefficient=seg.shear_coefficient, alpha=seg.alpha,
                         beta=seg.beta, tag=seg.tag)
            for j in range(n)
        ]
    except ModelError as err:
        raise ModelError(bare(err), where) from None


def build_shaft(table: ModelTable, materials: dict[str, Material]) -> list[ShaftElement]:
    return _segments(table.shaft, materials, "shaft")


def _segments(segments: list[ShaftSegment], materials: dict[str, Material], where: str
              ) -> list[ShaftElement]:
    shaft: list[ShaftElement] = []
    for i, seg in enumerate(segments):
        mat = material(materials, seg.material, f"{where}[{i}].material")
        shaft.extend(segment_elements(seg, mat, f"{where}[{i}]"))
    return shaft


def build_lines(table: ModelTable, materials: dict[str, Material]) -> list[ShaftLine]:
    """The shaft lines of the ``[lines.NAME]`` tables, in file order."""
    out = []
    for name, line in table.lines.items():
        elements = _segments(line.shaft, materials, f"lines.{name}.shaft")
        try:
            out.append(ShaftLine(name, elements, z0=line.z0, speed_ratio=line.speed_ratio))
        except ModelError as err:
            raise ModelError(bare(err), f"lines.{name}") from None
    return out


def node_layout(table: ModelTable, shaft: list[ShaftElement],
                lines: list[ShaftLine] | None = None) -> Nodes:
    """Line node positions (as :attr:`Rotor.nodes_pos`) and the housing nodes."""
    spans: tuple[tuple[str, int, int], ...] = ()
    if lines:
        z = np.concatenate([line.positions() for line in lines])
        counts = [line.n_nodes for line in lines]
        firsts = np.concatenate([[0], np.cumsum(counts)[:-1]])
        spans = tuple((line.name, int(f), int(c))
                      for line, f, c in zip(lines, firsts, counts, strict=True))
    else:
        z = np.concatenate([[0.0], np.cumsum([el.L for el in shaft])])
    housing = {pm.node for pm in table.point_masses if pm.node is not None
               and pm.node >= z.size} | {
        c.node for f in table.foundations for c in f.connections
        if c.node is not None and c.line is None and c.z is None and c.node >= z.size}
    expected = set(range(z.size, z.size + len(housing)))
    if housing != expected:
        bad = min(housing - expected)
        places = [f"point_masses[{j}].node" for j, pm in enumerate(table.point_masses)
                  if pm.node == bad] + [
            f"foundations[{j}].connections[{k}].node" for j, f in enumerate(table.foundations)
            for k, c in enumerate(f.connections) if c.node == bad]
        raise ModelError(f"housing node {bad}: nodes after the last shaft node "
                         f"({z.size - 1}) must be numbered {z.size}, {z.size + 1}, ... "
                         "without gaps", places[0])
    return Nodes(z=z, housings=frozenset(housing), lines=spans)


def build_elements(table: ModelTable, materials: dict[str, Material], nodes: Nodes
                   ) -> tuple[list[DiskElement], list[BearingElement], list[PointMass]]:
    disks = []
    for i, d in enumerate(table.disks):
        where = f"disks[{i}]"
        n = nodes.shaft_node(d, where)
        try:
            if d.m is not None:
                assert d.Id is not None and d.Ip is not None
                disks.append(DiskElement(n=n, m=d.m, Id=d.Id, Ip=d.Ip, tag=d.tag))
            else:
                assert d.material is not None and d.width is not None and d.o_d is not None
                mat = material(materials, d.material, f"{where}.material")
                disks.append(DiskElement.from_geometry(n, mat, d.width, d.i_d, d.o_d, d.tag))
        except ModelError as err:
            raise ModelError(bare(err), where) from None
    bearings = [_bearing(b, nodes, f"bearings[{i}]") for i, b in enumerate(table.bearings)]
    bearings += [_coupling(c, nodes, f"couplings[{i}]") for i, c in enumerate(table.couplings)]
    masses = []
    for i, pm in enumerate(table.point_masses):
        where = f"point_masses[{i}]"
        n = nodes.any_node(pm, where)
        try:
            masses.append(PointMass(n=n, m=pm.m, mx=pm.mx, my=pm.my, mz=pm.mz, tag=pm.tag))
        except ModelError as err:
            raise ModelError(bare(err), where) from None
    return disks, bearings, masses


def _bearing(b: BearingTable, nodes: Nodes, where: str) -> BearingElement:
    n = nodes.any_node(b, where)
    link = nodes.link(b, n, where)
    coefficients: dict[str, Any] = {}
    for key in BearingTable.coefficient_names():
        value = getattr(b, key)
        if value is not None:
            coefficients[key] = np.array(value) if isinstance(value, tuple) else value
    frequency = None if b.frequency is None else b.frequency.array()
    for key in ("stiffness_matrix", "damping_matrix"):  # full (5, 5) matrices, SI
        if getattr(b, key) is not None:
            coefficients[key] = np.array(getattr(b, key), dtype=float)
    try:
        return BearingElement(n=n, n_link=link, frequency=frequency, tag=b.tag, **coefficients)
    except ModelError as err:
        raise ModelError(bare(err), where) from None


def _coupling(c: CouplingTable, nodes: Nodes, where: str) -> BearingElement:
    n = nodes.any_node(c, where)
    link = nodes.link(c, n, where)
    assert link is not None  # the schema requires the second end
    values = {k: _scalar(getattr(c, k), f"{where}.{k}") for k in (
        "lateral", "angular", "torsional", "axial", "lateral_damping", "angular_damping",
        "torsional_damping", "axial_damping")}
    try:
        return BearingElement.coupling(n, link, tag=c.tag, **values)
    except ModelError as err:
        raise ModelError(bare(err), where) from None


def _scalar(value: Any, where: str) -> float:
    if isinstance(value, tuple):
        if len(value) != 1:
            raise ModelError("a coupling's coefficients are constant: give one value", where)
        value = value[0]
    return float(value)


def build_foundations(table: ModelTable, nodes: Nodes, base: Path) -> list[Foundation]:
    """The foundations of ``[[foundations]]``, files read relative to ``base``."""
    out = []
    for i, f in enumerate(table.foundations):
        where = f"foundations[{i}]"
        at = [nodes.any_node(c, f"{where}.connections[{k}]")
              for k, c in enumerate(f.connections)]
        dofs = [(n, d) for n in at for d in f.dofs]
        try:
            if f.shapes is not None:
                assert f.frequencies is not None and f.damping_ratios is not None
                shapes = read_matrix(base / f.shapes, f"{where}.shapes")
                out.append(Foundation.from_modal(dofs, f.frequencies, f.damping_ratios,
                                                 shapes, tag=f.tag))
            else:
                assert f.mass is not None and f.stiffness is not None
                out.append(Foundation.from_files(
                    dofs, base / f.mass, base / f.stiffness,
                    None if f.damping is None else base / f.damping, tag=f.tag))
        except ModelError as err:
            raise ModelError(bare(err), where) from None
    return out


def build_rotor(table: ModelTable, name: str, base: Path | None = None
                ) -> tuple[Rotor, Nodes]:
    """The rotor of a validated model file and its node layout."""
    materials = build_materials(table)
    shaft = build_shaft(table, materials)
    lines = build_lines(table, materials)
    nodes = node_layout(table, shaft, lines)
    disks, bearings, masses = build_elements(table, materials, nodes)
    fixed = [(nodes.any_node(f, f"fixed[{i}]"), dof)
             for i, f in enumerate(table.fixed) for dof in f.dofs]
    d = table.damping
    damping = None if d is None else SystemDamping(alpha=d.alpha, beta=d.beta,
                                                   modal_ratios=tuple(d.modal_ratios))
    foundations = build_foundations(table, nodes, Path.cwd() if base is None else base)
    rotor = Rotor(shaft, disks, bearings, masses, fixed=fixed, tag=name, lines=lines,
                  damping=damping, foundations=foundations)
    return rotor, nodes


def build_loads(table: ModelTable, nodes: Nodes) -> spec.Loads:
    loads = table.loads
    unbalance = unbalance_list(loads.unbalance, nodes, "loads.unbalance")
    point = tuple((nodes.any_node(p, f"loads.point_loads[{i}]"), str(p.dof), float(p.value))
                  for i, p in enumerate(loads.point_loads))
    gx, gy, gz = (float(v) for v in loads.gravity_direction)
    return spec.Loads(gravity=loads.gravity, gravity_direction=(gx, gy, gz),
                      unbalance=unbalance, point_loads=point)


def unbalance_list(items: list[Any], nodes: Nodes, where: str) -> spec.Unbalance:
    return tuple((nodes.shaft_node(u, f"{where}[{i}]"), float(u.magnitude), float(u.phase))
                 for i, u in enumerate(items))


def build_rolling(tables: list[RollingTable], nodes: Nodes
                  ) -> tuple[tuple[RollingBearing, ...], tuple[LinearizationPoint, ...]]:
    """The rolling-bearing elements of validated ``[[rolling_bearings]]`` tables and where
    each is linearised."""
    elements, points = [], []
    for i, t in enumerate(tables):
        where = f"rolling_bearings[{i}]"
        n = nodes.any_node(t, where)
        link = nodes.link(t, n, where)
        try:
            model: Any = mounted_model(_rolling_model(t), t.mounting)
            if t.rows == 2:
                assert t.row_spacing is not None
                model = DoubleRowBearing(model, t.row_spacing, t.arrangement,
                                         t.axial_interference, tag=t.tag)
            element = RollingBearing(
                ReversedBearing(model) if t.axial_direction == "-z" else model, n=n,
                n_link=link, tag=t.tag, contact_damping=t.contact_damping,
                damping_factor=t.damping_factor)
            points.append(LinearizationPoint(*t.linearize))
        except ModelError as err:
            raise ModelError(bare(err), where) from None
        elements.append(element)
    return tuple(elements), tuple(points)


_ROLLING_COMMON = ("pitch_diameter", "contact_angle", "radial_clearance", "diametral_clearance",
                   "exponent", "psi0", "cage")


def _rolling_model(t: RollingTable) -> BallBearing | RollerBearing:
    keys = {k: getattr(t, k) for k in _ROLLING_COMMON if getattr(t, k) is not None}
    if isinstance(t, BallTable):
        for k in ("n_balls", "ball_diameter", "f_i", "f_o", "A0", "groove_center_radius"):
            if getattr(t, k) is not None:
                keys[k] = getattr(t, k)
        if t.Kn is not None:
            return BallBearing(Kn=t.Kn, tag=t.tag, **keys)
        method = "iso16281" if t.spring_constant == "iso16281" else "exact"
        return BallBearing.from_geometry(tag=t.tag, method=method, **keys)  # f_i, f_o given
    assert isinstance(t, RollerTable)
    if t.influence_pressure is not None:   # the strip width of model = "influence"
        keys["influence_pressure"] = t.influence_pressure
    return RollerBearing(n_rollers=t.n_rollers, roller_diameter=t.roller_diameter,
                         effective_length=t.effective_length, Kn=t.Kn,
                         profile=_profile(t.profile), model=t.model, n_slices=t.n_slices,
                         slice_model=t.slice_model, tag=t.tag or "", **keys)


def _profile(p: ProfileTable | None) -> Any:
    if p is None or p.type == "straight":
        return StraightProfile()
    if p.type == "crowned":
        if p.crown_radius is not None:
            assert p.crown_length is not None
            return CircularCrown.from_radius(p.crown_radius, p.crown_length)
        assert p.crown_drop is not None
        return CircularCrown(crown_drop=p.crown_drop, crown_length=p.crown_length)
    assert p.scale is not None
    if p.end_drop is not None:
        return LogarithmicProfile.with_end_drop(p.scale, p.end_drop)
    return LogarithmicProfile(scale=p.scale, shape=1.0 if p.shape is None else p.shape)
