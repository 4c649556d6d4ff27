"""The immutable rotor model: nodes along the shaft line plus element objects."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.base import DOF_NAMES, FloatArray, NonlinearElement
from rotorsim.elements.disk import DiskElement, PointMass
from rotorsim.elements.foundation import Foundation
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.model.damping import SystemDamping
from rotorsim.model.lines import LineLayout, ShaftLine, check_overlaps, check_rotating_parts


@dataclass(frozen=True, eq=False)
class Rotor:
    """A rotor or machine: shaft lines, disks, bearings and point masses.

    One shaft line: shaft element ``i`` joins nodes ``i`` and ``i + 1``. A machine of
    several lines (spools, a casing; DESIGN section 12) gives ``lines`` instead: the nodes
    of each line follow those of the lines before it (:meth:`node` maps ``(line, local
    node)`` to the global number), and each line turns at its own ``speed_ratio`` times the
    reference speed. Nodes after the last line node (housings, pedestals) are created by the
    bearings and point masses that name them; they must be numbered consecutively and each
    needs mass (a :class:`PointMass`). They do not rotate.

    Parameters
    ----------
    shaft_elements : sequence of ShaftElement
        May be empty: the rotor is then rigid, a disk or point mass at node 0 (``z = 0``)
        on its bearings, the classic model of the bearing literature.
    disk_elements : sequence of DiskElement, optional
    bearing_elements : sequence of BearingElement, optional
    point_mass_elements : sequence of PointMass, optional
    fixed : iterable of (node, dof), optional
        DOFs held at zero, ``dof`` one of ``ux, uy, uz, rx, ry, rz``.
    tag : str, optional
        Model name.
    foundations : sequence of Foundation, optional
        Support structures as superelements on connection DOFs (their nodes need no point
        mass; :mod:`rotorsim.elements.foundation`).
    damping : SystemDamping, optional
        Rayleigh and modal damping of the assembled system, beside the elements' own
        (:mod:`rotorsim.model.damping`).
    lines : sequence of ShaftLine, optional
        The shaft lines of a machine of several shafts (then ``shaft_elements`` must be
        empty). Lines whose axial extents overlap must be joined by connections, and a
        line with a non-zero speed ratio needs rotating parts (:mod:`rotorsim.model.lines`).

    Disks, point masses and bearings (linear and nonlinear together) must have unique
    tags (``None`` is no tag); shaft elements may share one (a segment's elements).
    nonlinear_elements : sequence of NonlinearElement, optional
        Nonlinear elements such as :class:`~rotorsim.elements.rolling.element.RollingBearing`
        (a nonlinear element given among ``bearing_elements`` is moved here). Transient
        and static analyses use them; linear analyses need them linearised first
        (:func:`rotorsim.linearize_rolling_bearings`).

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> shaft = [ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    >>> rotor = Rotor(shaft, [DiskElement(n=2, m=10.0, Id=0.05, Ip=0.1)],
    ...               [BearingElement(n=0, kxx=1e6), BearingElement(n=4, kxx=1e6)])
    >>> rotor.n_nodes, rotor.ndof
    (5, 30)
    >>> rigid = Rotor([], [DiskElement(n=0, m=1.0, Id=1e-3, Ip=2e-3)],
    ...               [BearingElement(n=0, kxx=1e6)])
    >>> rigid.n_nodes, rigid.length
    (1, 0.0)

    Two coaxial spools joined by a bearing, the second turning 1.5 times as fast:

    >>> from rotorsim.model.lines import ShaftLine
    >>> lp = ShaftLine("LP", shaft)
    >>> hp = ShaftLine("HP", shaft[:2], z0=0.25, speed_ratio=1.5)
    >>> machine = Rotor([], lines=[lp, hp], bearing_elements=[
    ...     BearingElement(n=0, kxx=1e7), BearingElement(n=4, kxx=1e7),
    ...     BearingElement(n=1, n_link=5, kxx=1e7, tag="inter"),
    ...     BearingElement(n=7, kxx=1e7, tag="HP_rear")])
    >>> machine.n_nodes, machine.node("HP", 2), machine.node_speed_ratio.tolist()
    (8, 7, [1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 1.5, 1.5])
    """

    shaft_elements: Sequence[ShaftElement]
    disk_elements: Sequence[DiskElement] = ()
    bearing_elements: Sequence[BearingElement] = ()
    point_mass_elements: Sequence[PointMass] = ()
    fixed: Sequence[tuple[int, str]] = ()
    tag: str = "rotor"
    nonlinear_elements: Sequence[Any] = ()
    lines: Sequence[ShaftLine] = ()
    damping: SystemDamping | None = None
    foundations: Sequence[Foundation] = ()
    n_shaft_nodes: int = field(init=False)
    n_nodes: int = field(init=False)
    layout: LineLayout = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if isinstance(self.shaft_elements, str) or not isinstance(self.shaft_elements,
                                                                   Iterable):
            raise ModelError("give a sequence of ShaftElement (may be empty: a rigid rotor "
                             "or point mass at node 0)", f"Rotor '{self.tag}'")
        if self.damping is not None and not isinstance(self.damping, SystemDamping):
            raise ModelError(f"damping must be a SystemDamping, got {self.damping!r}",
                             f"Rotor '{self.tag}'")
        layout = self._line_layout()
        object.__setattr__(self, "layout", layout)
        object.__setattr__(self, "lines", tuple(self.lines))
        object.__setattr__(self, "shaft_elements", layout.numbered_elements())
        object.__setattr__(self, "n_shaft_nodes", layout.n_line_nodes)
        for name in ("disk_elements", "bearing_elements", "point_mass_elements",
                     "foundations"):
            object.__setattr__(self, name, tuple(getattr(self, name)))
            _check_kinds(name, getattr(self, name))
        moved = tuple(b for b in self.bearing_elements if _is_nonlinear(b))
        object.__setattr__(self, "bearing_elements",
                           tuple(b for b in self.bearing_elements if not _is_nonlinear(b)))
        nonlinear = (*tuple(self.nonlinear_elements), *moved)
        for i, el in enumerate(nonlinear):
            if not _is_nonlinear(el):
                raise ModelError(f"not a nonlinear element (needs nodes and force): {el!r}",
                                 f"nonlinear_elements[{i}]")
        object.__setattr__(self, "nonlinear_elements", nonlinear)
        _check_unique_tags(self)
        object.__setattr__(self, "n_nodes", self._count_nodes())
        fixed = _fixed_dofs(self.fixed)
        for node, dof in fixed:
            if dof not in DOF_NAMES:
                raise ModelError(f"unknown DOF '{dof}', use one of {DOF_NAMES}", "Rotor.fixed")
            if not 0 <= node < self.n_nodes:
                raise ModelError(f"node {node} outside 0..{self.n_nodes - 1}", "Rotor.fixed")
        object.__setattr__(self, "fixed", fixed)
        if self.multi_line:
            where = f"Rotor '{self.tag}'"
            links = [el.nodes for el in (*self.bearing_elements, *self.nonlinear_elements,
                                         *self.foundations) if len(el.nodes) > 1]
            check_overlaps(layout, links, self.n_nodes, where)
            check_rotating_parts(layout, [(d.n, d.Ip) for d in self.disk_elements], where)
            ratios = self.node_speed_ratio
            object.__setattr__(self, "nonlinear_elements", tuple(
                _with_ring_speeds(el, ratios, f"nonlinear_elements[{i}]")
                for i, el in enumerate(self.nonlinear_elements)))

    def _line_layout(self) -> LineLayout:
        """The lines given, or the one line of ``shaft_elements`` (numbered in order)."""
        if self.lines:
            layout = LineLayout.of(tuple(self.lines))
            given = tuple(self.shaft_elements)  # a copy (dataclasses.replace) passes them
            if given and given != layout.numbered_elements():
                raise ModelError("give either shaft_elements (one line) or lines, not both",
                                 f"Rotor '{self.tag}'")
            return layout
        shaft = tuple(self.shaft_elements)
        for i, el in enumerate(shaft):
            if not isinstance(el, ShaftElement):
                raise ModelError(f"not a ShaftElement: {el!r}", f"shaft_elements[{i}]")
            if el.n is not None and el.n != i:
                raise ModelError(f"element {i} must join nodes {i} and {i + 1}, has n={el.n}",
                                 el.label)
        return LineLayout.of((ShaftLine("shaft", shaft),))

    # ------------------------------------------------------------------ lines
    @property
    def multi_line(self) -> bool:
        """Whether the model has several lines or a line turning at a ratio other than 1."""
        return len(self.layout.lines) > 1 or self.layout.lines[0].speed_ratio != 1.0

    def node(self, line: str, local: int) -> int:
        """Global node number of local node ``local`` of the line called ``line``."""
        return self.layout.node(line, local)

    @cached_property
    def node_line(self) -> NDArray[np.int64]:
        """Line index of every node; ``-1`` for housing nodes."""
        return self.layout.line_of_node(self.n_nodes)

    @cached_property
    def node_speed_ratio(self) -> FloatArray:
        """Speed ratio of every node [-]: its line's, 0 for housing nodes."""
        ratios = np.array([line.speed_ratio for line in self.layout.lines] + [0.0])
        return ratios[self.node_line]

    def node_name(self, node: int) -> str:
        """``"LINE:local"`` for a line node of a machine, ``"node N"`` otherwise."""
        k = int(self.node_line[node])
        if k < 0 or not self.multi_line:
            return f"node {node}"
        return f"{self.layout.lines[k].name}:{node - int(self.layout.first_node[k])}"

    def lines_description(self) -> dict[str, str]:
        """``{"line NAME": "nodes a..b, z .. m, speed ratio r"}`` for every line."""
        out = {}
        for line, first in zip(self.layout.lines, self.layout.first_node, strict=True):
            z = line.positions()
            out[f"line {line.name}"] = (f"nodes {first}..{first + line.n_nodes - 1}, z "
                                        f"{z.min():.4g}..{z.max():.4g} m, speed ratio "
                                        f"{line.speed_ratio:g}")
        return out

    def _count_nodes(self) -> int:
        n_shaft = self.n_shaft_nodes
        last = n_shaft - 1
        massive = {pm.n for pm in self.point_mass_elements} | {
            n for f in self.foundations for n in f.nodes}
        extra: set[int] = set()
        for disk in self.disk_elements:
            if disk.n > last:
                raise ModelError(f"node {disk.n} is not on the shaft (nodes 0..{last})",
                                 disk.label)
        others: tuple[Any, ...] = (
            *self.bearing_elements, *self.point_mass_elements, *self.nonlinear_elements,
            *self.foundations)
        for el in others:
            for node in el.nodes:
                if node > last and node not in massive:
                    raise ModelError(
                        f"node {node} is not on the shaft (nodes 0..{last}); an off-shaft"
                        f" (housing) node needs a PointMass(n={node}, m=...)",
                        str(getattr(el, "label", el)),
                    )
                if node > last:
                    extra.add(node)
        expected = set(range(n_shaft, n_shaft + len(extra)))
        if extra != expected:
            raise ModelError(
                f"housing nodes must be numbered {n_shaft}, {n_shaft + 1}, ... without gaps;"
                f" got {sorted(extra)}",
                f"Rotor '{self.tag}'",
            )
        return n_shaft + len(extra)

    # ------------------------------------------------------------------ geometry
    @cached_property
    def nodes_pos(self) -> FloatArray:
        """Axial position z [m] of every node; housing nodes sit at their shaft node."""
        z = np.zeros(self.n_nodes)
        z[: self.n_shaft_nodes] = self.layout.positions()
        for b in (*self.bearing_elements, *self.nonlinear_elements):
            n, link = int(b.nodes[0]), (int(b.nodes[1]) if len(b.nodes) > 1 else None)
            if link is not None and link >= self.n_shaft_nodes and n < self.n_shaft_nodes:
                z[link] = z[n]
        return z

    @property
    def length(self) -> float:
        """Axial extent of the shaft lines [m] (the shaft length for one line)."""
        z = self.nodes_pos[: self.n_shaft_nodes]
        return float(z.max() - z.min())

    @property
    def ndof(self) -> int:
        return 6 * self.n_nodes

    @cached_property
    def m_shaft(self) -> float:
        return float(sum(el.mass for el in self.shaft_elements))

    @cached_property
    def m_disks(self) -> float:
        return float(sum(d.m for d in self.disk_elements))

    @property
    def m(self) -> float:
        """Mass of the rotating parts (shaft and disks) [kg]."""
        return self.m_shaft + self.m_disks

    @property
    def speed_dependent(self) -> bool:
        return any(b.speed_dependent for b in self.bearing_elements)

    # ------------------------------------------------------------------ copies
    def with_bearings(self, bearings: Sequence[BearingElement]) -> Rotor:
        """Copy with the bearing elements replaced."""
        return dataclasses.replace(self, bearing_elements=tuple(bearings))

    def with_nonlinear(self, elements: Sequence[Any]) -> Rotor:
        """Copy with the nonlinear elements replaced."""
        return dataclasses.replace(self, nonlinear_elements=tuple(elements))

    def linear_part(self) -> Rotor:
        """Copy without the nonlinear elements."""
        return self.with_nonlinear(())

    def with_fixed(self, fixed: Iterable[tuple[int, str]]) -> Rotor:
        """Copy with more DOFs held at zero."""
        return dataclasses.replace(self, fixed=(*self.fixed, *fixed))

    def without_axial_torsion(self) -> Rotor:
        """Copy with ``uz`` and ``rz`` fixed at every node: a purely lateral model."""
        extra = [(n, d) for n in range(self.n_nodes) for d in ("uz", "rz")]
        return self.with_fixed(extra)

    def summary(self) -> dict[str, object]:
        """Counts, length and masses, for tables and result metadata."""
        return {
            "tag": self.tag,
            "nodes": self.n_nodes,
            "dofs": self.ndof,
            "fixed_dofs": len(self.fixed),
            "shaft_elements": len(self.shaft_elements),
            "disks": len(self.disk_elements),
            "bearings": len(self.bearing_elements),
            "nonlinear_elements": len(self.nonlinear_elements),
            "point_masses": len(self.point_mass_elements),
            **({"foundations": len(self.foundations)} if self.foundations else {}),
            **(self.lines_description() if self.multi_line else {}),
            "length_m": self.length,
            "mass_shaft_kg": self.m_shaft,
            "mass_disks_kg": self.m_disks,
        }


def _check_unique_tags(rotor: Rotor) -> None:
    """Refuse two disks, two point masses or two bearings (linear and nonlinear together,
    since analyses such as critical-speed maps select bearings by tag) with the same tag.
    Shaft elements may share a tag: a segment's elements all carry it."""
    groups = (
        (("disk_elements", rotor.disk_elements),),
        (("point_mass_elements", rotor.point_mass_elements),),
        (("bearing_elements", rotor.bearing_elements),
         ("nonlinear_elements", rotor.nonlinear_elements)),
    )
    for group in groups:
        seen: dict[str, str] = {}
        for name, elements in group:
            for i, el in enumerate(elements):
                tag = getattr(el, "tag", None)
                if not tag:
                    continue
                here = f"{name}[{i}]"
                if tag in seen:
                    raise ModelError(f"duplicate tag {tag!r}: {seen[tag]} and {here} (tags "
                                     "select elements, so each must be unique)",
                                     f"Rotor '{rotor.tag}'")
                seen[tag] = here


_KINDS: dict[str, tuple[type, ...]] = {"disk_elements": (DiskElement,),
                                       "bearing_elements": (BearingElement,),
                                       "point_mass_elements": (PointMass,),
                                       "foundations": (Foundation,)}


def _check_kinds(name: str, elements: tuple[Any, ...]) -> None:
    """Refuse an element in the wrong list (a bearing among the disks would be assembled
    without its speed dependence); nonlinear elements may sit among the bearings."""
    kinds = _KINDS[name]
    for i, el in enumerate(elements):
        if not isinstance(el, kinds) and not (name == "bearing_elements" and _is_nonlinear(el)):
            raise ModelError(f"expected a {' or '.join(k.__name__ for k in kinds)}, got "
                             f"{type(el).__name__}", f"{name}[{i}]")


def _fixed_dofs(fixed: Iterable[Any]) -> tuple[tuple[int, str], ...]:
    """``fixed`` as ``((node, dof), ...)``, or a ModelError naming the malformed entry."""
    out = []
    for i, item in enumerate(fixed):
        try:
            node, dof = item
        except (TypeError, ValueError):
            node = dof = None
        if isinstance(node, bool) or not isinstance(node, int | np.integer) \
                or not isinstance(dof, str):
            raise ModelError(f"expected (node, dof) such as (0, 'uz'), got {item!r}",
                             f"Rotor.fixed[{i}]")
        out.append((int(node), dof))
    return tuple(out)


def _with_ring_speeds(element: Any, ratios: FloatArray, where: str) -> Any:
    """``element`` with its rings turning at the speed ratios of its two nodes' lines (the
    outer ring of a bearing to ground stands still)."""
    nodes = element.nodes
    inner = float(ratios[nodes[0]])
    outer = float(ratios[nodes[1]]) if len(nodes) > 1 else 0.0
    if (inner, outer) == (1.0, 0.0):
        return element
    if not hasattr(element, "inner_speed_ratio"):
        raise ModelError(f"{type(element).__name__} has a standing outer ring only; on "
                         f"these nodes its rings turn at {inner:g} and {outer:g} times the "
                         "reference speed (use a RollingBearing)", where)
    if (element.inner_speed_ratio, element.outer_speed_ratio) == (inner, outer):
        return element
    return dataclasses.replace(element, inner_speed_ratio=inner, outer_speed_ratio=outer)


def _is_nonlinear(element: Any) -> bool:
    """True for an element with a nonlinear ``force`` (DESIGN section 4)."""
    return isinstance(element, NonlinearElement) and not isinstance(element, BearingElement)
