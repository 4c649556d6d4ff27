"""Result of a static analysis: deflection, bearing reactions and shaft internal forces."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.assembly.dof_map import DofMap
from rotorsim.elements.base import DOF_NAMES
from rotorsim.errors import ModelError, Status

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class StaticResult:
    """Static equilibrium ``K q = f`` of a rotor under gravity and point loads.

    Internal forces follow one sign convention: at a cross-section, the section resultant is
    the force and moment that the part of the shaft at larger ``z`` exerts on the part at
    smaller ``z``. Hence axial force is tension-positive, and the bending moments are
    ``M_x = E I d(rx)/dz = -E I d^2 uy/dz^2`` and ``M_y = E I d(ry)/dz = E I d^2 ux/dz^2``
    (Euler-Bernoulli limit): a shaft sagging under gravity along ``-y`` has ``M_x < 0`` at
    midspan. Shear is ``V_y = dM_x/dz`` and ``V_x = -dM_y/dz`` between loads.

    Attributes
    ----------
    displacement : array (ndof,)
        Displacements [m] and rotations [rad] on ALL DOFs (zeros at fixed ones).
    load : array (ndof,)
        Applied load (gravity + point loads) on all DOFs [N, N m]; on fixed DOFs it is the
        part of the weight carried directly by the constraint (zero without a Rotor).
    dof_map : DofMap
    nodes_pos : array (n_nodes,)
        Axial node positions [m].
    speed : float
        Spin speed at which the bearing stiffness was evaluated [rad/s].
    bearing_nodes : int array (n_bearings,) or None
        Shaft node of each bearing (``None`` when solved from a RotorSystem alone).
    bearing_forces : array (n_bearings, 3) or None
        Force exerted by each bearing on its shaft node, (x, y, z) [N].
    bearing_moments : array (n_bearings, 3) or None
        Moment exerted by each bearing on its shaft node (tilting stiffness ``krr``) [N m].
    constraint_reactions : array (ndof,) or None
        Force/moment exerted on the structure by fixed DOFs and by the DOFs held to remove
        free rigid-body motions [N, N m] (zero at free DOFs up to round-off).
    element_z : array (n_elements, 2) or None
        Axial positions of the left and right end of each shaft element [m].
    shear_force : array (n_elements, 2, 2) or None
        ``[..., 0] = V_x``, ``[..., 1] = V_y`` at each element end [N].
    bending_moment : array (n_elements, 2, 2) or None
        ``[..., 0] = M_x`` (bending in the y-z plane), ``[..., 1] = M_y`` [N m].
    axial_force, torque : array (n_elements, 2) or None
        ``N`` (tension positive) [N] and ``M_z`` [N m] at each element end.
    free_rigid_motions : tuple of str
        Rigid-body motions of the whole rotor that nothing restrains (each orthogonal to the
        load, else the analysis raises); they were removed by holding ``restrained_dofs``.
    restrained_dofs : tuple of str
        ``"node:dof"`` held at zero to remove the free rigid motions.
    residual : float
        ``||K q - f|| / ||f||`` on the free DOFs.
    options, stats, status, summary
        Options used, cost counters, status and model summary.
    element_loads, contact_angles : dict of str to array (Z,)
        With rolling bearings: the load [N] and contact angle [rad] of every rolling element
        of each bearing (by tag) at the equilibrium.
    """

    displacement: FloatArray
    load: FloatArray
    dof_map: DofMap
    nodes_pos: FloatArray
    speed: float
    bearing_nodes: NDArray[np.int64] | None
    bearing_forces: FloatArray | None
    bearing_moments: FloatArray | None
    constraint_reactions: FloatArray | None
    element_z: FloatArray | None
    shear_force: FloatArray | None
    bending_moment: FloatArray | None
    axial_force: FloatArray | None
    torque: FloatArray | None
    free_rigid_motions: tuple[str, ...]
    restrained_dofs: tuple[str, ...]
    residual: float
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)
    element_loads: dict[str, FloatArray] = field(default_factory=dict)
    contact_angles: dict[str, FloatArray] = field(default_factory=dict)

    def deflection(self, dof: str = "uy") -> FloatArray:
        """Displacement ``dof`` of every node, shape ``(n_nodes,)`` [m or rad].

        Examples
        --------
        >>> r = _example()
        >>> r.deflection("uy").tolist()
        [0.0, -0.001]
        """
        if dof not in DOF_NAMES:
            raise ModelError(f"unknown DOF {dof!r}, use one of {DOF_NAMES}", "deflection")
        return self.displacement.reshape(-1, 6)[:, DOF_NAMES.index(dof)]

    @property
    def applied_force(self) -> FloatArray:
        """Resultant of the applied forces (x, y, z) over all nodes [N].

        Examples
        --------
        >>> _example().applied_force.tolist()
        [0.0, -10.0, 0.0]
        """
        return np.asarray(self.load.reshape(-1, 6)[:, :3].sum(axis=0))

    @property
    def bending_moment_magnitude(self) -> FloatArray | None:
        """``sqrt(M_x^2 + M_y^2)`` at each element end, shape ``(n_elements, 2)`` [N m]."""
        if self.bending_moment is None:
            return None
        return np.asarray(np.hypot(self.bending_moment[..., 0], self.bending_moment[..., 1]))


def _example() -> StaticResult:
    """A two-node result used by the doctests."""
    q = np.zeros(12)
    q[7] = -1e-3
    load = np.zeros(12)
    load[7] = -10.0
    return StaticResult(
        displacement=q, load=load, dof_map=DofMap(2), nodes_pos=np.array([0.0, 1.0]),
        speed=0.0, bearing_nodes=None, bearing_forces=None, bearing_moments=None,
        constraint_reactions=None, element_z=None, shear_force=None, bending_moment=None,
        axial_force=None, torque=None, free_rigid_motions=(), restrained_dofs=(),
        residual=0.0,
    )
