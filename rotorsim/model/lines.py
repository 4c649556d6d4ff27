"""Shaft lines of a machine: beam lines with their own axial position and speed ratio.

A machine of several shafts (DESIGN section 12) is a set of lines. Each line is a chain of
shaft elements; its nodes are numbered consecutively after the nodes of the lines before
it. A line turns at ``speed_ratio`` times the reference speed ``W`` of the analyses: ``1``
for the reference spool, another positive value for a co-rotating spool, a negative value
for a counter-rotating one and ``0`` for a casing or frame modelled with the same beams.
The gyroscopic matrix of the machine is ``G(W) = W sum_k r_k G_k`` (DESIGN section 12).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class ShaftLine:
    """One beam line of a machine.

    Parameters
    ----------
    name : str
        Name of the line (``"LP"``, ``"HP"``, ``"casing"``); connections and results name
        nodes as ``(line, local node)``.
    elements : sequence of ShaftElement
        Elements in order along z; element ``j`` joins the line's local nodes ``j`` and
        ``j + 1``. Empty: a single node (a rigid body carried by its disks).
    z0 : float
        Axial position of the line's first node [m], in the machine's frame.
    speed_ratio : float
        Signed speed of the line per unit reference speed [-]: ``1`` the reference spool,
        ``< 0`` counter-rotating, ``0`` not rotating (casing, frame).

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> hp = ShaftLine("HP", [ShaftElement(L=0.2, idl=0.06, odl=0.08, material=steel)] * 3,
    ...                z0=0.3, speed_ratio=1.45)
    >>> hp.n_nodes, hp.positions().round(2).tolist()
    (4, [0.3, 0.5, 0.7, 0.9])
    """

    name: str
    elements: Sequence[ShaftElement] = ()
    z0: float = 0.0
    speed_ratio: float = 1.0

    def __post_init__(self) -> None:
        where = f"ShaftLine {self.name!r}"
        if not isinstance(self.name, str) or not self.name.strip() or ":" in self.name:
            raise ModelError(f"name must be a non-empty string without ':', got {self.name!r}",
                             "ShaftLine")
        if isinstance(self.elements, str) or not isinstance(self.elements, Iterable):
            raise ModelError("elements must be a sequence of ShaftElement", where)
        elements = tuple(self.elements)
        for j, el in enumerate(elements):
            if not isinstance(el, ShaftElement):
                raise ModelError(f"not a ShaftElement: {el!r}", f"{where}.elements[{j}]")
        object.__setattr__(self, "elements", elements)
        for key in ("z0", "speed_ratio"):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, int | float | np.floating) \
                    or not math.isfinite(value):
                raise ModelError(f"{key} must be a finite number, got {value!r}", where)
            object.__setattr__(self, key, float(value))

    @property
    def n_nodes(self) -> int:
        return len(self.elements) + 1

    def positions(self) -> FloatArray:
        """Axial position of every node of the line [m]."""
        return self.z0 + np.concatenate([[0.0], np.cumsum([el.L for el in self.elements])])

    @property
    def has_polar_inertia(self) -> bool:
        """Whether any element of the line carries a gyroscopic (polar) inertia."""
        return any(el.gyroscopic for el in self.elements)


@dataclass(frozen=True, eq=False)
class LineLayout:
    """Global node numbering of a set of lines.

    Attributes
    ----------
    lines : tuple of ShaftLine
    first_node : int array (n_lines,)
        Global number of each line's local node 0.
    n_line_nodes : int
        Number of nodes on all lines (housing nodes follow them).
    """

    lines: tuple[ShaftLine, ...]
    first_node: IntArray
    n_line_nodes: int

    @classmethod
    def of(cls, lines: Sequence[ShaftLine]) -> LineLayout:
        """Number the nodes of ``lines`` in order; refuse duplicate names."""
        lines = tuple(lines)
        if not lines:
            raise ModelError("give at least one ShaftLine", "Rotor.lines")
        seen: set[str] = set()
        for i, line in enumerate(lines):
            if not isinstance(line, ShaftLine):
                raise ModelError(f"not a ShaftLine: {line!r}", f"Rotor.lines[{i}]")
            if line.name in seen:
                raise ModelError(f"duplicate line name {line.name!r}", f"Rotor.lines[{i}]")
            seen.add(line.name)
        counts = np.array([line.n_nodes for line in lines], dtype=np.int64)
        first = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
        return cls(lines, first, int(counts.sum()))

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(line.name for line in self.lines)

    def index(self, name: str) -> int:
        """Position of the line called ``name``; a ModelError listing the lines if none."""
        try:
            return self.names.index(name)
        except ValueError:
            raise ModelError(f"no line named {name!r} (lines: {', '.join(self.names)})",
                             "lines") from None

    def node(self, name: str, local: int) -> int:
        """Global node number of local node ``local`` of line ``name``."""
        k = self.index(name)
        n = self.lines[k].n_nodes
        if isinstance(local, bool) or not isinstance(local, int | np.integer) \
                or not 0 <= local < n:
            raise ModelError(f"line {name!r} has nodes 0..{n - 1}, got {local!r}",
                             f"line {name!r}")
        return int(self.first_node[k] + local)

    def numbered_elements(self) -> tuple[ShaftElement, ...]:
        """All shaft elements with their global first node set."""
        out = []
        for line, first in zip(self.lines, self.first_node, strict=True):
            for j, el in enumerate(line.elements):
                if el.n is not None and el.n != j:
                    raise ModelError(f"element {j} of a line joins its local nodes {j} and "
                                     f"{j + 1}, has n={el.n}",
                                     f"ShaftLine {line.name!r}.elements[{j}]")
                out.append(el.with_node(int(first) + j))
        return tuple(out)

    def line_of_node(self, n_nodes: int) -> IntArray:
        """Line index of every node; ``-1`` for nodes off the lines (housings)."""
        out = np.full(n_nodes, -1, dtype=np.int64)
        for k, (line, first) in enumerate(zip(self.lines, self.first_node, strict=True)):
            out[first:first + line.n_nodes] = k
        return out

    def positions(self) -> FloatArray:
        """Axial position of every line node [m]."""
        return np.concatenate([line.positions() for line in self.lines])

    def element_speed_ratios(self) -> FloatArray:
        """Speed ratio of every shaft element, in the order of :meth:`numbered_elements`."""
        return np.concatenate([np.full(len(line.elements), line.speed_ratio)
                               for line in self.lines])


def check_overlaps(layout: LineLayout, links: Iterable[tuple[int, ...]], n_nodes: int,
                   where: str) -> None:
    """Refuse two lines whose axial extents overlap but that no chain of connections joins.

    Connections to ground do not count: two coaxial spools that are each held by the
    ground only are two machines drawn on top of each other, almost always a missing
    inter-shaft bearing. ``links`` are the node tuples of the connecting elements
    (bearings, seals, rolling bearings, couplings); housing nodes join what they link.
    """
    parent = list(range(n_nodes))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for line, first in zip(layout.lines, layout.first_node, strict=True):
        for j in range(1, line.n_nodes):
            parent[root(int(first) + j)] = root(int(first))
    for nodes in links:
        for other in nodes[1:]:
            parent[root(int(other))] = root(int(nodes[0]))
    spans = [(line.positions().min(), line.positions().max()) for line in layout.lines]
    for a in range(len(layout.lines)):
        for b in range(a + 1, len(layout.lines)):
            (lo_a, hi_a), (lo_b, hi_b) = spans[a], spans[b]
            overlap = min(hi_a, hi_b) - max(lo_a, lo_b)
            joined = root(int(layout.first_node[a])) == root(int(layout.first_node[b]))
            if overlap > 0 and not joined:
                raise ModelError(
                    f"lines {layout.lines[a].name!r} and {layout.lines[b].name!r} overlap "
                    f"along z ({max(lo_a, lo_b):.6g} to {min(hi_a, hi_b):.6g} m) but no "
                    "bearing, seal or coupling joins them (directly or through other lines "
                    "or housings); add the connection, or move one line", where)


def check_rotating_parts(layout: LineLayout, disk_nodes: Sequence[tuple[int, float]],
                         where: str) -> None:
    """Refuse a non-zero speed ratio on a line without polar inertia.

    ``disk_nodes`` holds ``(node, Ip)`` of every disk. A line that turns but has neither a
    gyroscopic shaft element nor a disk with a polar moment of inertia is almost always a
    casing or frame whose ``speed_ratio = 0`` was forgotten.
    """
    for k, (line, first) in enumerate(zip(layout.lines, layout.first_node, strict=True)):
        if line.speed_ratio == 0.0 or line.has_polar_inertia:
            continue
        on_line = [ip for n, ip in disk_nodes if first <= n < first + line.n_nodes and ip > 0]
        if not on_line:
            raise ModelError(
                f"line {line.name!r} has speed_ratio {line.speed_ratio:g} but no rotating "
                "parts (no gyroscopic shaft element, no disk with Ip > 0); set speed_ratio "
                "= 0 for a casing or frame", f"{where}.lines[{k}]")
