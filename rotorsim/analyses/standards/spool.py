"""The spool an API check is made on: one rotor of one shaft line, or one rotating line of a
machine of several (:class:`~rotorsim.model.lines.ShaftLine`).

On a machine every analysis runs at the reference speed ``W`` and each line turns at its
``speed_ratio r`` times it; a spool's unbalance excites at its own speed ``|r| W``. The API
unbalance check of a spool is made in the spool's own speeds (its operating range and MCS,
its critical speeds where its 1X line crosses a mode), with the unbalance at the anti-nodes
of the mode on the spool. :func:`spool_of` resolves the spool and refuses what API 617 does
not define.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor


@dataclass(frozen=True)
class Spool:
    """One spool of a rotor.

    Attributes
    ----------
    name : str
        The line's name (``"shaft"`` for a rotor of one line).
    ratio : float
        Its speed per unit reference speed (1 for a rotor of one line).
    nodes : int array
        Its global node numbers, in order along the line.
    mass : float
        Mass of its shaft elements and of the disks on it [kg] (a rotor of one line: the
        rotor's mass).
    machine : bool
        True when the rotor has several lines.
    """

    name: str
    ratio: float
    nodes: NDArray[np.int64]
    mass: float
    machine: bool

    def bearing_nodes(self, rotor: Rotor) -> list[int]:
        """Nodes of the spool where a bearing acts (its own or an inter-shaft bearing)."""
        on = set(self.nodes.tolist())
        return sorted({int(n) for b in rotor.bearing_elements
                       for n in (b.n, b.n_link) if n is not None and n in on})


def spool_of(rotor: Rotor, spool: str | None, where: str) -> Spool:
    """The spool ``spool`` of ``rotor`` (its only line when ``spool`` is None).

    Raises
    ------
    ModelError
        ``rotor`` not a Rotor; a machine of several lines without ``spool``; no line of
        that name; a line that does not turn or turns against the reference
        (counter-rotating: its unbalance drives backward whirl, for which the API anti-node
        placement is not implemented here).
    """
    if not isinstance(rotor, Rotor):
        raise ModelError(f"expected a Rotor, got {type(rotor).__name__}", where)
    layout = rotor.layout
    lines = layout.lines
    if len(lines) == 1:
        if spool not in (None, lines[0].name):
            raise ModelError(f"no line named {spool!r}: the rotor has one line, "
                             f"{lines[0].name!r}", where)
        return Spool(lines[0].name, 1.0, np.arange(max(rotor.n_shaft_nodes, 1), dtype=np.int64),
                     float(rotor.m), False)
    names = ", ".join(line.name for line in lines)
    if spool is None:
        raise ModelError(f"a machine of {len(lines)} lines ({names}): name the spool to "
                         "check (spool=...), each spool is checked at its own speeds", where)
    i = layout.index(spool)
    line = lines[i]
    if line.speed_ratio == 0:
        raise ModelError(f"line {spool!r} does not rotate (speed ratio 0): no unbalance "
                         f"response to check (rotating lines: {_rotating(rotor)})", where)
    if line.speed_ratio < 0:
        raise ModelError(f"line {spool!r} turns against the reference (speed ratio "
                         f"{line.speed_ratio:g}): the API anti-node placement for the "
                         "backward whirl its unbalance drives is not implemented", where)
    first = int(layout.first_node[i])
    nodes = np.arange(first, first + line.n_nodes, dtype=np.int64)
    on = set(nodes.tolist())
    mass = sum(el.mass for el in line.elements) + sum(
        d.m for d in rotor.disk_elements if d.n in on)
    return Spool(line.name, float(line.speed_ratio), nodes, float(mass), True)


def _rotating(rotor: Rotor) -> str:
    return ", ".join(line.name for line in rotor.layout.lines if line.speed_ratio != 0)
