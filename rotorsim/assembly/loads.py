"""Load vectors on the free DOFs of an assembled rotor: gravity, unbalance, point loads.

All vectors are in the DOF order of ``system.dof_map.free`` (length ``system.n_free``);
``system.dof_map.expand`` maps them back to all DOFs.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOF_NAMES, DOFS_PER_NODE, FloatArray, as_float_array
from rotorsim.elements.shaft import shaft_matrices
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor

STANDARD_GRAVITY = 9.80665
"""Standard acceleration of gravity [m/s^2]."""

ComplexArray = NDArray[np.complex128]


def unit_direction(direction: ArrayLike, where: str = "direction") -> FloatArray:
    """Normalised 3-vector ``(x, y, z)``; raises :class:`ModelError` if not finite or zero.

    Examples
    --------
    >>> unit_direction((0.0, -2.0, 0.0)).tolist()
    [0.0, -1.0, 0.0]
    """
    d = as_float_array(direction, "value", where)
    if d.shape != (3,) or not np.all(np.isfinite(d)) or not np.any(d):
        raise ModelError(f"must be 3 finite components, not all zero; got {direction!r}", where)
    return d / np.linalg.norm(d)


def rigid_translation(n_nodes: int, direction: ArrayLike) -> FloatArray:
    """All-DOF field ``(6 n_nodes,)`` of a unit rigid translation along ``direction``."""
    field = np.zeros((n_nodes, DOFS_PER_NODE))
    field[:, :3] = unit_direction(direction)
    return field.ravel()


def consistent_gravity(mass_blocks: FloatArray, g: float, direction: ArrayLike) -> FloatArray:
    """Consistent gravity load ``g M_e e`` of each element block.

    ``e`` is the unit rigid translation along ``direction``, the direction in which gravity
    acts, so the weight points along ``direction``.

    Parameters
    ----------
    mass_blocks : array (E, d, d)
        Element mass matrices, ``d = 6 * nodes per element``.
    g : float
        Acceleration of gravity [m/s^2].
    direction : 3 floats
        Direction of gravity (normalised here).

    Returns
    -------
    array (E, d)
        Nodal forces [N] and moments [N m] of each element.

    Examples
    --------
    >>> M = np.diag([2.0, 2.0, 2.0, 0.1, 0.1, 0.2])[None]
    >>> consistent_gravity(M, 10.0, (0, -1, 0))[0, :3].tolist()
    [0.0, -20.0, 0.0]
    """
    mass_blocks = np.asarray(mass_blocks, dtype=float)
    e = rigid_translation(mass_blocks.shape[-1] // DOFS_PER_NODE, direction)
    return np.asarray(g * (mass_blocks @ e))


def gravity_load(
    system: RotorSystem,
    g: float = STANDARD_GRAVITY,
    direction: ArrayLike = (0.0, -1.0, 0.0),
    *,
    rotor: Rotor | None = None,
) -> FloatArray:
    """Consistent gravity load ``g M_struct e`` on the free DOFs.

    ``e`` is the unit rigid translation along ``direction`` (where gravity points, so the
    default ``-y`` gives ``f_y = -m g``); ``M_struct`` is the mass of the shaft, disks and
    point masses (bearing added mass has no weight). Distributed shaft mass gives consistent
    nodal forces and moments (``q L / 2`` and ``+-q L^2 / 12`` per element).

    Parameters
    ----------
    system : RotorSystem
        The assembled model. Alone, the load is ``g M_ff e_f`` from the assembled free-DOF
        mass matrix, which misses the mass coupling to fixed DOFs that move in the gravity
        direction (e.g. a fixed ``uy`` with gravity along y).
    g : float
        Acceleration of gravity [m/s^2].
    direction : 3 floats
        Direction in which gravity acts (normalised); default ``-y``.
    rotor : Rotor, optional
        The model ``system`` was assembled from. Given, the load is exact in every case:
        the all-DOF element loads (:func:`gravity_load_all_dofs`) restricted to the free DOFs.

    Returns
    -------
    array (n_free,)
        Forces [N] and moments [N m].

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> from rotorsim.elements.shaft import ShaftElement
    >>> from rotorsim.assembly.system import assemble
    >>> rotor = Rotor([ShaftElement(L=0.5, idl=0.0, odl=0.05, material=steel)] * 2)
    >>> f = gravity_load(assemble(rotor))
    >>> bool(np.isclose(f[1::6].sum(), -STANDARD_GRAVITY * rotor.m))
    True
    """
    if np.ndim(as_float_array(g, "value", "gravity")) or not np.isfinite(g):
        raise ModelError(f"must be a finite number, got {g!r}", "gravity")
    if rotor is not None:
        if rotor.ndof != system.dof_map.ndof:
            raise ModelError(f"rotor has {rotor.ndof} DOFs, system {system.dof_map.ndof}",
                             "gravity_load")
        return np.asarray(gravity_load_all_dofs(rotor, g, direction)[system.dof_map.free])
    e = rigid_translation(system.dof_map.n_nodes, direction)[system.dof_map.free]
    mass = system.pattern.matrix(system.structural_mass)
    return np.asarray(g * (mass @ e))


def gravity_load_all_dofs(
    rotor: Rotor, g: float = STANDARD_GRAVITY, direction: ArrayLike = (0.0, -1.0, 0.0)
) -> FloatArray:
    """Consistent gravity load ``(rotor.ndof,)`` on all DOFs, fixed ones included [N, N m].

    Sums :func:`consistent_gravity` of the shaft elements, disks and point masses.

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> from rotorsim.elements.shaft import ShaftElement
    >>> rotor = Rotor([ShaftElement(L=0.5, idl=0.0, odl=0.05, material=steel)])
    >>> f = gravity_load_all_dofs(rotor)
    >>> bool(np.isclose(f[1], f[7])), bool(np.isclose(f[3], -f[9]))
    (True, True)
    """
    out = np.zeros(rotor.ndof)
    shaft = rotor.shaft_elements
    groups: list[tuple[NDArray[np.int64], FloatArray]] = [
        (np.array([el.nodes for el in shaft]), shaft_matrices(shaft).M)
    ] if shaft else []  # a rigid rotor has none
    for kind in (rotor.disk_elements, rotor.point_mass_elements):
        if kind:
            groups.append((np.array([el.nodes for el in kind]),
                           np.stack([el.matrices().M for el in kind])))
    for foundation in rotor.foundations:
        groups.append((np.array([foundation.nodes]), foundation.matrices().M[None]))
    for nodes, mass in groups:
        dofs = (DOFS_PER_NODE * nodes[:, :, None] + np.arange(DOFS_PER_NODE)).reshape(
            nodes.shape[0], -1)
        np.add.at(out, dofs, consistent_gravity(mass, g, direction))
    return out


def _node_dofs(system: RotorSystem, node: Any, dofs: tuple[str, ...], where: str) -> NDArray:
    """Free indices of ``dofs`` at ``node``; ModelError if the node or a DOF is invalid/fixed."""
    n_nodes = system.dof_map.n_nodes
    if isinstance(node, bool) or not isinstance(node, int | np.integer) \
            or not 0 <= node < n_nodes:
        raise ModelError(f"node {node!r} is not a node of the rotor (0..{n_nodes - 1})", where)
    for dof in dofs:
        if dof not in DOF_NAMES:
            raise ModelError(f"unknown DOF {dof!r} at node {node}, use one of {DOF_NAMES}", where)
    idx = system.dof_map.full_to_free[[system.dof_map.index(int(node), d) for d in dofs]]
    if np.any(idx < 0):
        fixed = [d for d, i in zip(dofs, idx, strict=True) if i < 0]
        raise ModelError(f"DOF {', '.join(fixed)} of node {node} is fixed; cannot load it",
                         where)
    return idx


def unbalance_amplitudes(
    system: RotorSystem, unbalance: Sequence[tuple[int, float, float]]
) -> ComplexArray:
    """Unbalance force amplitudes per unit ``W^2`` on the free DOFs, shape ``(n_free,)``.

    ``F_x = me e^{i a}``, ``F_y = -i me e^{i a}`` for each ``(node, me, a)``; multiply by
    ``W^2`` to get :func:`unbalance_load`. Validation as in :func:`unbalance_load`.
    """
    if isinstance(unbalance, str) or not isinstance(unbalance, Sequence) or not unbalance:
        raise ModelError("give a non-empty list of (node, magnitude_kg_m, phase_rad)",
                         "unbalance")
    out = np.zeros(system.n_free, dtype=complex)
    for i, item in enumerate(unbalance):
        where = f"unbalance[{i}]"
        try:
            node, magnitude, phase = item
        except (TypeError, ValueError):
            raise ModelError(f"expected (node, magnitude_kg_m, phase_rad), got {item!r}",
                             where) from None
        ix, iy = _node_dofs(system, node, ("ux", "uy"), where)
        if not np.isfinite(magnitude) or magnitude < 0:
            raise ModelError(f"magnitude at node {node} must be finite and >= 0 [kg m], "
                             f"got {magnitude!r}", where)
        if not np.isfinite(phase):
            raise ModelError(f"phase at node {node} must be finite [rad], got {phase!r}", where)
        amp = magnitude * np.exp(1j * phase)
        out[ix] += amp
        out[iy] += -1j * amp
    return out


def spool_groups(system: RotorSystem, unbalance: Sequence[tuple[int, float, float]]
                 ) -> dict[float, list[tuple[int, float, float]]]:
    """The unbalances grouped by the speed ratio of their line, in order of appearance.

    An unbalance on a line that does not turn (ratio 0: a casing) is refused: it would
    excite nothing, and is almost always a node number on the wrong line.
    """
    out: dict[float, list[tuple[int, float, float]]] = {}
    for i, item in enumerate(unbalance):
        ratio = system.speed_ratio_of(int(item[0]))
        if ratio == 0.0:
            raise ModelError(f"node {item[0]} does not rotate (speed ratio 0: a casing or "
                             "housing node); an unbalance must sit on a turning line",
                             f"unbalance[{i}]")
        out.setdefault(ratio, []).append(tuple(item))  # type: ignore[arg-type]
    return out


def unbalance_speed_ratios(system: RotorSystem,
                           unbalance: Sequence[tuple[int, float, float]]) -> FloatArray | None:
    """Speed ratio of the line under every free DOF, for unbalances on spools that turn at
    different speeds; ``None`` when every unbalance turns at the reference speed."""
    if list(spool_groups(system, unbalance)) == [1.0]:
        return None
    ratios = system.node_speed_ratio
    assert ratios is not None  # a ratio other than 1 needs lines
    return np.repeat(ratios, DOFS_PER_NODE)[system.dof_map.free]


def unbalance_load(
    system: RotorSystem,
    unbalance: Sequence[tuple[int, float, float]],
    speed: float,
) -> ComplexArray:
    """Complex amplitudes of the unbalance forces at spin speed ``speed``.

    With ``x(t) = Re(X e^{i W t})``, an unbalance ``me`` at angle ``a`` gives
    ``F_x = me W^2 e^{i a}`` and ``F_y = -i me W^2 e^{i a}``, i.e. the rotating force
    ``me W^2 [cos(W t + a), sin(W t + a)]``.

    Parameters
    ----------
    system : RotorSystem
        The assembled model.
    unbalance : list of (node, magnitude, phase)
        Node number, mass-eccentricity product [kg m] and angle [rad] of each unbalance.
    speed : float
        Spin speed W [rad/s].

    Returns
    -------
    complex array (n_free,)
        Force amplitudes [N].

    Raises
    ------
    ModelError
        Naming ``unbalance[i]`` and the node for a node outside the rotor, a fixed ``ux`` or
        ``uy``, or a non-finite or negative magnitude.

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> from rotorsim.elements.shaft import ShaftElement
    >>> from rotorsim.assembly.system import assemble
    >>> system = assemble(Rotor([ShaftElement(L=0.5, idl=0.0, odl=0.05, material=steel)]))
    >>> f = unbalance_load(system, [(1, 1e-3, 0.0)], speed=100.0)
    >>> complex(f[6]), complex(f[7])
    ((10+0j), -10j)
    """
    if not np.isfinite(speed):
        raise ModelError(f"speed must be finite, got {speed!r}", "unbalance_load")
    return unbalance_amplitudes(system, unbalance) * float(speed) ** 2


def nodal_load(
    system: RotorSystem, node: int, dof: str, value: float, *, where: str | None = None
) -> FloatArray:
    """Point force or moment ``value`` on ``dof`` of ``node``, as a free-DOF vector.

    Parameters
    ----------
    system : RotorSystem
        The assembled model.
    node : int
        Node number.
    dof : str
        One of ``ux, uy, uz`` (force [N]) or ``rx, ry, rz`` (moment [N m]).
    value : float
        Magnitude [N or N m].
    where : str, optional
        Name of the load in error messages, e.g. ``"loads[2]"``.

    Returns
    -------
    array (n_free,)

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> from rotorsim.elements.shaft import ShaftElement
    >>> from rotorsim.assembly.system import assemble
    >>> system = assemble(Rotor([ShaftElement(L=0.5, idl=0.0, odl=0.05, material=steel)]))
    >>> float(nodal_load(system, 1, "uy", -50.0)[7])
    -50.0
    """
    where = where or f"load at node {node}"
    (index,) = _node_dofs(system, node, (dof,), where)
    if not np.isfinite(value):
        raise ModelError(f"value on {dof} of node {node} must be finite, got {value!r}", where)
    out = np.zeros(system.n_free)
    out[index] = value
    return out
