"""Numbering of the global DOFs and of the free (unconstrained) subset, and their labels."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import SupportsInt

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.base import DOF_NAMES, DOFS_PER_NODE
from rotorsim.errors import ModelError

IntArray = NDArray[np.int64]


def dof_label(index: SupportsInt, *, short: bool = False,
              node_names: tuple[str, ...] = ()) -> str:
    """Label of the global DOF ``index`` (``6 * node + local``), the one place that spells it.

    ``"node 8 uy"`` (the default) labels the DOFs of results files (their ``dof_labels``
    datasets) and of results in memory (``TransientResult.dof_labels``,
    ``PeriodicResult.dof_labels``). ``short=True`` gives ``"8:uy"``, the compact form of
    messages and of the labels that result fields and summaries carry
    (:meth:`DofMap.names`, ``StaticResult.restrained_dofs``, ``summary["inactive_dofs"]``);
    it stays as it is so that files written before keep their content.

    Examples
    --------
    On a machine of several lines, ``node_names`` (:attr:`DofMap.node_names`) adds the
    line and local node of each node: ``"node 20 (HP:3) uy"``.

    >>> dof_label(49), dof_label(49, short=True)
    ('node 8 uy', '8:uy')
    >>> dof_label(49, node_names=("LP:0",) * 8 + ("HP:0",))
    'node 8 (HP:0) uy'
    """
    node, local = divmod(int(index), DOFS_PER_NODE)
    if short:
        return f"{node}:{DOF_NAMES[local]}"
    where = f" ({node_names[node]})" if node_names and node_names[node] else ""
    return f"node {node}{where} {DOF_NAMES[local]}"


@dataclass(frozen=True, eq=False)
class DofMap:
    """Global DOF numbering ``6 * node + local`` and the free DOFs kept by the solvers.

    Parameters
    ----------
    n_nodes : int
        Number of nodes.
    fixed : iterable of int
        Global indices held at zero.

    Examples
    --------
    >>> dm = DofMap(2, fixed=[2, 8])
    >>> dm.n_free, dm.index(1, "uy"), dm.free_index(1, "uy")
    (10, 7, 6)
    """

    n_nodes: int
    fixed: Iterable[int] = ()
    node_names: tuple[str, ...] = ()
    """``"LINE:local"`` of every node of a machine of several lines (``""`` off the lines);
    empty for a one-line rotor."""
    free: IntArray = field(init=False, repr=False)
    full_to_free: IntArray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        fixed = np.unique(np.asarray(list(self.fixed), dtype=np.int64))
        if fixed.size and (fixed[0] < 0 or fixed[-1] >= self.ndof):
            raise ModelError(f"fixed DOF index outside 0..{self.ndof - 1}", "DofMap")
        object.__setattr__(self, "fixed", fixed)
        names = tuple(str(n) for n in self.node_names)
        if names and len(names) != self.n_nodes:
            raise ModelError(f"node_names has {len(names)} entries for {self.n_nodes} nodes",
                             "DofMap")
        object.__setattr__(self, "node_names", names)
        mask = np.ones(self.ndof, dtype=bool)
        mask[fixed] = False
        free = np.flatnonzero(mask).astype(np.int64)
        full_to_free = np.full(self.ndof, -1, dtype=np.int64)
        full_to_free[free] = np.arange(free.size)
        object.__setattr__(self, "free", free)
        object.__setattr__(self, "full_to_free", full_to_free)

    @property
    def ndof(self) -> int:
        return DOFS_PER_NODE * self.n_nodes

    @property
    def n_free(self) -> int:
        return int(self.free.size)

    def index(self, node: int, dof: str | int) -> int:
        """Global index of ``dof`` (name or local number) at ``node``."""
        local = DOF_NAMES.index(dof) if isinstance(dof, str) else int(dof)
        if not 0 <= node < self.n_nodes:
            raise ModelError(f"node {node} outside 0..{self.n_nodes - 1}", "DofMap")
        if not 0 <= local < DOFS_PER_NODE:
            raise ModelError(f"local DOF {dof!r} outside {DOF_NAMES}", "DofMap")
        return DOFS_PER_NODE * node + local

    def free_index(self, node: int, dof: str | int) -> int:
        """Index among the free DOFs; raises if the DOF is fixed."""
        i = int(self.full_to_free[self.index(node, dof)])
        if i < 0:
            raise ModelError(f"DOF {dof!r} of node {node} is fixed", "DofMap")
        return i

    def column(self, kept: NDArray, node: int, dof: str | int, where: str) -> int:
        """Position of ``(node, dof)`` among the kept DOF indices ``kept`` (of a result);
        a :class:`ModelError` naming ``where`` and the kept nodes when it was not kept."""
        hit = np.flatnonzero(np.asarray(kept) == self.index(node, dof))
        if hit.size == 0:
            nodes = sorted({int(i) // DOFS_PER_NODE for i in kept})
            raise ModelError(f"DOF {dof} of node {node} was not kept; kept nodes: {nodes} "
                             "(choose them with the 'nodes' option)", where)
        return int(hit[0])

    def expand(self, values: NDArray) -> NDArray:
        """Place free-DOF values (first axis ``n_free``) into all DOFs, zeros where fixed."""
        values = np.asarray(values)
        out = np.zeros((self.ndof, *values.shape[1:]), dtype=values.dtype)
        out[self.free] = values
        return out

    def label(self, index: SupportsInt) -> str:
        """Results-file label of the global DOF ``index`` (:func:`dof_label`)."""
        return dof_label(index, node_names=self.node_names)

    def names(self) -> list[str]:
        """Short labels ``"node:dof"`` (``"8:uy"``) of all DOFs (:func:`dof_label`)."""
        return [dof_label(i, short=True) for i in range(self.ndof)]
