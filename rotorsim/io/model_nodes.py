"""Node layout of a model file being built: line node positions, housing nodes, and the
resolution of ``node`` / ``z`` / ``line`` / ``link_line`` keys to global node numbers."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.io.schema_types import Linked, Located

Z_TOLERANCE = 1e-9
"""Largest distance [m] between a given ``z`` and the node it is mapped to."""


@dataclass(frozen=True)
class Nodes:
    """Node layout of a model being built: line node positions and housing nodes.

    ``lines`` holds ``(name, first node, node count)`` of each ``[lines.NAME]`` table of a
    machine; it is empty for a one-line model (``[[shaft]]``), whose items name no line.
    """

    z: np.ndarray
    housings: frozenset[int]
    lines: tuple[tuple[str, int, int], ...] = ()

    @property
    def n_shaft(self) -> int:
        return int(self.z.size)

    @property
    def n_total(self) -> int:
        return self.n_shaft + len(self.housings)

    def shaft_node(self, item: Located, where: str) -> int:
        """Node of an item that must sit on a shaft line (by node number or z)."""
        first, count = self._line(item.line, where)
        if item.z is not None:
            return self._at(item.z, f"{where}.z", first, count)
        assert item.node is not None
        if item.node >= count:
            what = f"a node of line {item.line!r}" if item.line else "a shaft node"
            raise ModelError(f"node {item.node} is not {what} (0..{count - 1})",
                             f"{where}.node")
        return first + item.node

    def any_node(self, item: Located, where: str) -> int:
        """Node of an item that may also sit on a housing node (by its global number)."""
        if item.z is None and item.node is not None and item.line is None:
            return self.check(item.node, f"{where}.node")
        return self.shaft_node(item, where)

    def link(self, item: Linked, node: int, where: str) -> int | None:
        """The node an item's ``n_link`` / ``link_line`` names, or None (ground)."""
        if item.link_line is None:
            link = None if item.n_link is None else self.check(item.n_link, f"{where}.n_link")
        else:
            first, count = self._line(item.link_line, f"{where}.link_line", key="link_line")
            if item.n_link is not None:
                if item.n_link >= count:
                    raise ModelError(f"node {item.n_link} is not a node of line "
                                     f"{item.link_line!r} (0..{count - 1})", f"{where}.n_link")
                link = first + item.n_link
            else:
                if item.link_z is None and node >= self.n_shaft:
                    raise ModelError("give link_z or n_link: the bearing's own node is a "
                                     "housing node with no axial position", where)
                z = self.z[node] if item.link_z is None else item.link_z
                link = self._at(float(z), f"{where}.link_z", first, count)
        if link == node:
            raise ModelError(f"must differ from the bearing node ({node})", f"{where}.n_link")
        return link

    def check(self, node: int, where: str) -> int:
        if node < self.n_shaft or node in self.housings:
            return node
        raise ModelError(f"node {node} is neither a shaft node (0..{self.n_shaft - 1}) nor a "
                         "housing node with a point mass", where)

    def _line(self, name: str | None, where: str, key: str = "line") -> tuple[int, int]:
        """First node and node count of the line ``name`` (the whole shaft: one line)."""
        if not self.lines:
            if name is not None:
                raise ModelError(f"{key} = {name!r} but the model has one shaft line "
                                 "([[shaft]]); give [lines.NAME] tables for several lines",
                                 f"{where}.{key}" if key == "line" else where)
            return 0, self.n_shaft
        names = [n for n, _, _ in self.lines]
        if name is None:
            raise ModelError(f"give {key} = one of {', '.join(names)} (the model has "
                             "several lines)", where)
        if name not in names:
            raise ModelError(f"no line named {name!r} (lines: {', '.join(names)})",
                             f"{where}.{key}" if key == "line" else where)
        _, first, count = self.lines[names.index(name)]
        return first, count

    def _at(self, z: float, where: str, first: int = 0, count: int | None = None) -> int:
        count = self.n_shaft if count is None else count
        z_line = self.z[first:first + count]
        gap = np.abs(z_line - z)
        node = int(np.argmin(gap))
        if gap[node] <= Z_TOLERANCE:
            return first + node
        near = np.argsort(gap)[:2]
        listed = ", ".join(f"{first + i} at {z_line[i]:.6g} m" for i in sorted(near))
        raise ModelError(f"{z:.6g} m is not a node position; nearest nodes: {listed}", where)
