"""Assembly of a :class:`~rotorsim.model.rotor.Rotor` into sparse global matrices."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.assembly.dof_map import DofMap, dof_label
from rotorsim.assembly.nonlinear import NonlinearAssembly
from rotorsim.assembly.sparse import SparsityPattern
from rotorsim.assembly.system_damping import modal_damping_matrix
from rotorsim.elements.base import (
    DOF_NAMES,
    DOFS_PER_NODE,
    ElementMatrices,
    FloatArray,
    NonlinearElement,
)
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import shaft_matrices
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor


@dataclass(frozen=True, eq=False)
class SystemMatrices:
    """Global CSR matrices on the free DOFs at one speed.

    The equation of motion is ``M q'' + (C + W G) q' + K q = f``.
    """

    M: sp.csr_matrix
    C: sp.csr_matrix
    G: sp.csr_matrix
    K: sp.csr_matrix


@dataclass(frozen=True, eq=False)
class RotorSystem:
    """Assembled rotor: DOF map, shared sparsity pattern and matrix data.

    Speed-independent contributions are summed once; bearings whose coefficients depend on
    speed are scattered into the same pattern by :meth:`matrices`. ``nonlinear`` holds the
    nonlinear elements (rolling bearings) with their DOF indices, when given to
    :func:`assemble`.
    """

    dof_map: DofMap
    nodes_pos: FloatArray
    pattern: SparsityPattern
    constant: dict[str, FloatArray]
    variable_bearings: tuple[tuple[int, BearingElement], ...]
    structural_mass: FloatArray
    summary: dict[str, object]
    nonlinear: NonlinearAssembly | None = None
    node_line: NDArray[np.int64] | None = None
    """Line index of every node of a machine (``-1`` off the lines); ``None``: one line
    turning at the reference speed."""
    line_names: tuple[str, ...] = ()
    """Names of the lines of a machine (``()`` for one line at ratio 1)."""
    line_ratios: tuple[float, ...] = ()
    """Speed ratio of every line of a machine [-]."""

    @property
    def n_free(self) -> int:
        return self.dof_map.n_free

    @cached_property
    def mass_diagonal(self) -> FloatArray:
        """Diagonal of the structural mass on all DOFs (``(n_dof,)``, kg or kg m^2), formed
        once: modal analyses classify the modes of every speed with it."""
        return self.dof_map.expand(self.pattern.matrix(self.structural_mass).diagonal())

    def matrices(self, speed: float = 0.0) -> SystemMatrices:
        """Global ``M, C, G, K`` at spin speed ``speed`` [rad/s]."""
        data = {k: v.copy() for k, v in self.constant.items()} if self.variable_bearings else \
            self.constant
        for group, bearing in self.variable_bearings:
            mats = bearing_matrices(bearing, speed, self.node_speed_ratio)
            for key in ("M", "C", "K"):
                data[key] = data[key] + self.pattern.scatter(group, getattr(mats, key)[None])
        return SystemMatrices(**{k: self.pattern.matrix(v) for k, v in data.items()})

    @property
    def node_speed_ratio(self) -> FloatArray | None:
        """Speed ratio of every node [-] (its line's, 0 off the lines); ``None`` for one
        line at the reference speed."""
        if self.node_line is None:
            return None
        return np.array([*self.line_ratios, 0.0])[self.node_line]

    def speed_ratio_of(self, node: int) -> float:
        """Speed ratio of ``node`` [-] (1 on a one-line rotor)."""
        ratios = self.node_speed_ratio
        return 1.0 if ratios is None else float(ratios[node])

    def line_index(self, name: str, where: str) -> int:
        """Index of the line called ``name``; a ModelError naming ``where`` if none."""
        names = self.line_names or ("shaft",)
        if name not in names:
            raise ModelError(f"no line named {name!r} (lines: {', '.join(names)})", where)
        return names.index(name)

    def line_ratio(self, name: str, where: str) -> float:
        """Speed ratio of the line called ``name`` [-]."""
        k = self.line_index(name, where)
        return float(self.line_ratios[k]) if self.line_ratios else 1.0

    def line_node_mask(self, name: str, where: str) -> NDArray[np.bool_]:
        """Boolean mask ``(n_nodes,)`` of the nodes of line ``name``."""
        k = self.line_index(name, where)
        if self.node_line is None:
            n_line = int(self.summary.get("shaft_elements", 0)) + 1  # type: ignore[call-overload]
            return np.arange(self.dof_map.n_nodes) < n_line
        return np.asarray(self.node_line == k)

    def dofs_of(self, node: int, dofs: tuple[str, ...] = DOF_NAMES) -> NDArray[np.int64]:
        """Free-DOF indices of ``dofs`` at ``node`` (fixed ones are skipped)."""
        full = [self.dof_map.index(node, d) for d in dofs]
        idx = self.dof_map.full_to_free[full]
        return idx[idx >= 0]


_MIRROR_Y = np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])
"""The reflection ``y -> -y`` on ``ux, uy, uz, rx, ry, rz`` (rotations are pseudo-vectors)."""


def bearing_matrices(bearing: BearingElement, speed: float,
                     node_speed_ratio: FloatArray | None) -> ElementMatrices:
    """Matrices of a speed-dependent bearing at the relative speed of its two nodes.

    On a machine the journal (node ``n``) turns at ``r_n W`` and the sleeve (``n_link`` or
    ground) at ``r_link W``; the coefficients are those at ``|r_n - r_link| W``. A journal
    turning backwards relative to its sleeve sees the mirror image of the forward bearing:
    the reflection ``y -> -y`` reverses the sense of rotation, so its matrices are
    ``P A(|W|) P`` with ``P = diag(1, -1, 1, -1, 1, -1)`` per node (the cross-coupled terms
    change sign, the direct ones do not).
    """
    if node_speed_ratio is None:
        return bearing.matrices(speed)
    nodes = bearing.nodes
    relative = relative_speed_ratio(bearing, node_speed_ratio)
    mats = bearing.matrices(abs(relative) * speed)
    if relative * speed >= 0:
        return mats
    p = np.tile(_MIRROR_Y, len(nodes))
    flip = p[:, None] * p[None, :]
    return ElementMatrices(M=mats.M * flip, C=mats.C * flip, G=mats.G * flip, K=mats.K * flip)


def relative_speed_ratio(bearing: BearingElement, node_speed_ratio: FloatArray | None
                         ) -> float:
    """Speed of the journal (node ``n``) relative to the sleeve (``n_link`` or ground) per
    unit reference speed [-]; 1 on a one-line rotor (``node_speed_ratio`` None)."""
    if node_speed_ratio is None:
        return 1.0
    nodes = bearing.nodes
    return float(node_speed_ratio[nodes[0]]) - (
        float(node_speed_ratio[nodes[1]]) if len(nodes) > 1 else 0.0)


def _element_dofs(nodes: NDArray[np.int64]) -> NDArray[np.int64]:
    """Global DOF indices ``(E, 6 * nodes_per_element)`` from node numbers ``(E, k)``."""
    local = np.arange(DOFS_PER_NODE)
    return (DOFS_PER_NODE * nodes[:, :, None] + local).reshape(nodes.shape[0], -1)


def _stack(mats: list[ElementMatrices]) -> ElementMatrices:
    return ElementMatrices(*(np.stack([getattr(m, k) for m in mats]) for k in "MCGK"))


def assemble(rotor: Rotor, nonlinear: Sequence[NonlinearElement] = ()) -> RotorSystem:
    """Assemble the global sparse matrices of ``rotor``.

    Parameters
    ----------
    rotor : Rotor
        The model.
    nonlinear : sequence of NonlinearElement, optional
        Nonlinear elements (e.g. :class:`~rotorsim.elements.rolling.element.RollingBearing`)
        on nodes of ``rotor``, besides ``rotor.nonlinear_elements``; all are indexed in
        ``RotorSystem.nonlinear``. Their DOFs that are fixed or unconnected stay at zero.

    Returns
    -------
    RotorSystem
        DOF map, shared CSR pattern and the speed-independent matrix data.

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> from rotorsim.elements.shaft import ShaftElement
    >>> rotor = Rotor([ShaftElement(L=0.5, idl=0.0, odl=0.05, material=steel)] * 2)
    >>> system = assemble(rotor)
    >>> system.matrices().M.shape
    (18, 18)
    """
    if not isinstance(rotor, Rotor):
        raise ModelError(f"expected a Rotor, got {type(rotor).__name__}", "assemble")
    fixed = [DOFS_PER_NODE * n + DOF_NAMES.index(d) for n, d in rotor.fixed]
    damped = rotor.damping is not None and rotor.damping.active
    system = _assemble(rotor, fixed, with_damping=False)  # system damping on the final DOFs
    inactive = _unconnected_dofs(system)
    if inactive.size or damped:
        system = _assemble(rotor, [*fixed, *inactive.tolist()])
        system.summary["inactive_dofs"] = [dof_label(i, short=True) for i in inactive]
    elements = (*rotor.nonlinear_elements, *nonlinear)
    if not elements:
        return system
    gathered = NonlinearAssembly.build(elements, system.dof_map.full_to_free, rotor.n_nodes)
    summary = {**system.summary, "nonlinear_elements": len(gathered.elements)}
    return dataclasses.replace(system, nonlinear=gathered, summary=summary)


def _unconnected_dofs(system: RotorSystem) -> NDArray[np.int64]:
    """Free DOFs with no mass, damping or stiffness at all (e.g. rotations of a housing
    point mass): they are removed like fixed DOFs and listed in ``summary``."""
    touched = np.zeros(system.n_free, dtype=bool)
    rows = np.repeat(np.arange(system.n_free), np.diff(system.pattern.indptr))
    for data in system.constant.values():
        touched[rows[data != 0]] = True
    for group, _ in system.variable_bearings:
        pos = system.pattern.positions[group]
        touched[rows[pos[pos >= 0]]] = True
    return system.dof_map.free[~touched]


def _assemble(rotor: Rotor, fixed: list[int], with_damping: bool = True) -> RotorSystem:
    dof_map = DofMap(rotor.n_nodes, fixed, node_names=tuple(
        rotor.node_name(n) if rotor.node_line[n] >= 0 else ""
        for n in range(rotor.n_nodes)) if rotor.multi_line else ())
    groups: list[tuple[NDArray[np.int64], ElementMatrices]] = []

    ratios = rotor.node_speed_ratio if rotor.multi_line else None
    shaft = rotor.shaft_elements
    if shaft:  # none in a rigid rotor (a disk or point mass on its bearings)
        shaft_nodes = np.array([el.nodes for el in shaft], dtype=np.int64)
        groups.append((_element_dofs(shaft_nodes),
                       _spinning(shaft_matrices(shaft), shaft_nodes[:, 0], ratios)))
    for kind in (rotor.disk_elements, rotor.point_mass_elements):
        if kind:
            nodes = np.array([el.nodes for el in kind], dtype=np.int64)
            groups.append((_element_dofs(nodes),
                           _spinning(_stack([el.matrices() for el in kind]), nodes[:, 0],
                                     ratios)))
    for foundation in rotor.foundations:  # support structures: structural mass too
        nodes = np.array([foundation.nodes], dtype=np.int64)
        groups.append((_element_dofs(nodes), _stack([foundation.matrices()])))
    n_structural = len(groups)
    variable: list[tuple[int, BearingElement]] = []
    constant_bearings: dict[int, list[BearingElement]] = {}
    for b in rotor.bearing_elements:
        if b.speed_dependent:
            nodes = np.array([b.nodes], dtype=np.int64)
            groups.append((_element_dofs(nodes), _stack([bearing_matrices(b, 0.0, ratios)])))
            variable.append((len(groups) - 1, b))
        else:
            constant_bearings.setdefault(len(b.nodes), []).append(b)
    for same_size in constant_bearings.values():
        nodes = np.array([b.nodes for b in same_size], dtype=np.int64)
        groups.append((_element_dofs(nodes), _stack([b.matrices(0.0) for b in same_size])))

    variable_groups = {g for g, _ in variable}
    pattern, constant, structural_mass = _scatter(groups, dof_map, variable_groups,
                                                  n_structural)
    damping = rotor.damping
    if with_damping and damping is not None and damping.active:
        if damping.modal_ratios:
            extra = modal_damping_matrix(pattern.matrix(constant["M"]),
                                         pattern.matrix(constant["K"]),
                                         tuple(damping.modal_ratios), f"Rotor '{rotor.tag}'")
            zero = np.zeros((1, *extra.shape))
            groups.append((dof_map.free[None, :], ElementMatrices(zero, extra[None], zero,
                                                                  zero)))
            pattern, constant, structural_mass = _scatter(groups, dof_map, variable_groups,
                                                          n_structural)
        constant["C"] = constant["C"] + damping.alpha * constant["M"] \
            + damping.beta * constant["K"]
    return RotorSystem(
        dof_map=dof_map,
        nodes_pos=rotor.nodes_pos,
        pattern=pattern,
        constant=constant,
        variable_bearings=tuple(variable),
        structural_mass=structural_mass,
        summary={**rotor.summary(), "inactive_dofs": [], **({"line_speed_ratios": {
            line.name: line.speed_ratio for line in rotor.layout.lines}}
            if rotor.multi_line else {})},
        node_line=rotor.node_line if rotor.multi_line else None,
        line_names=tuple(line.name for line in rotor.layout.lines) if rotor.multi_line
        else (),
        line_ratios=tuple(line.speed_ratio for line in rotor.layout.lines)
        if rotor.multi_line else (),
    )


def _scatter(groups: list[tuple[NDArray[np.int64], ElementMatrices]], dof_map: DofMap,
             variable_groups: set[int], n_structural: int
             ) -> tuple[SparsityPattern, dict[str, FloatArray], FloatArray]:
    """The shared pattern of ``groups`` and the constant matrix data on it (the
    speed-dependent bearings' groups are only placed), with the structural mass."""
    free_dofs = [dof_map.full_to_free[dofs] for dofs, _ in groups]
    pattern = SparsityPattern.from_blocks(dof_map.n_free, free_dofs)
    constant = {k: np.zeros(pattern.nnz) for k in "MCGK"}
    structural_mass = np.zeros(pattern.nnz)
    for g, (_, mats) in enumerate(groups):
        if g in variable_groups:
            continue
        for k in "MCGK":
            constant[k] += pattern.scatter(g, getattr(mats, k))
        if g < n_structural:
            structural_mass += pattern.scatter(g, mats.M)
    return pattern, constant, structural_mass


def _spinning(mats: ElementMatrices, first_nodes: NDArray[np.int64],
              ratios: FloatArray | None) -> ElementMatrices:
    """Element matrices with each element's gyroscopic matrix scaled by its line's speed
    ratio: ``G(W) = W sum_k r_k G_k`` (DESIGN section 12). ``None``: one line at ratio 1."""
    if ratios is None:
        return mats
    r = ratios[first_nodes][:, None, None]
    return ElementMatrices(M=mats.M, C=mats.C, G=mats.G * r, K=mats.K)
