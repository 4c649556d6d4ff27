"""The torsional loads of a torque-driven rotor and its polar inertia.

The torsional DOFs ``rz`` of the shaft nodes are angles ``theta_i`` relative to the frame
that turns with the rigid spin ``phi(t)``. In that frame the torsional equations read
``M_t theta'' + C_t theta' + K_t theta = T(t) - M_t 1 W'(t)``: the torques applied at the
nodes minus the inertial load of the accelerating frame (the same construction as a base
excitation, seed 002 eq 3.43, here for a rotation; Friswell et al., *Dynamics of Rotating
Machines*, CUP 2010, ch. 2 on torsional vibration, and Genta, *Dynamics of Rotating
Systems*, Springer 2005, on torsional vibration of a driven rotor). With ``J_p = 1^T M_t 1``
the spin equation makes the sum of these loads vanish, so the rigid torsion mode stays at
rest and the torque distribution (motor at one end, loads at the other) and its
pulsations excite the torsional modes.

The polar inertia is ``1^T M 1`` over the ``rz`` DOFs of the shaft nodes (the assembled
mass matrix) when they are all free, else the sum over the elements
(:func:`element_polar_inertia`, a fixed ``rz`` then ties its node rigidly to the spin).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.analyses.transient.speed_profile import BoundSpeed, SpeedProfile, as_speed_profile
from rotorsim.analyses.transient.torque_drive import BoundTorqueDrive, TorqueDrive
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOF_NAMES, DOFS_PER_NODE, FloatArray
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor

RZ = DOF_NAMES.index("rz")
_GL_X, _GL_W = np.polynomial.legendre.leggauss(3)  # exact for the quartic of a taper


def shaft_node_count(system: RotorSystem) -> int:
    """Nodes on the rotating shaft line (0..n-1; housing nodes come after)."""
    return int(system.summary.get("shaft_elements", 0) or 0) + 1  # type: ignore[call-overload]


def spin_field(system: RotorSystem) -> tuple[FloatArray, bool]:
    """Unit rotation about the spin axis on the free DOFs (``rz = 1`` at every shaft
    node) and whether every shaft ``rz`` is free.

    On a machine of several lines each line turns by its speed ratio per unit reference
    rotation (``rz = r_k``; casings at 0), so ``e^T M e = sum_k r_k^2 I_k`` is the inertia
    the drive sees through the prescribed ratios.
    """
    dm = system.dof_map
    ratios = system.node_speed_ratio
    if ratios is None:
        nodes = np.arange(shaft_node_count(system))
        values = np.ones(nodes.size)
    else:
        nodes = np.flatnonzero(ratios != 0.0)
        values = ratios[nodes]
    free = dm.full_to_free[DOFS_PER_NODE * nodes + RZ]
    e = np.zeros(system.n_free)
    e[free[free >= 0]] = values[free >= 0]
    return e, bool(np.all(free >= 0))


def model_polar_inertia(system: RotorSystem) -> float:
    """``1^T M 1`` over the free ``rz`` DOFs of the shaft nodes [kg m^2]."""
    e, _ = spin_field(system)
    return float(e @ (system.matrices(0.0).M @ e))


def element_polar_inertia(rotor: Rotor) -> float:
    """Polar inertia of the shaft elements (``rho pi/32 int (d_o^4 - d_i^4) dz``, linear
    taper, exact 3-point Gauss rule) and of the disks (``Ip``) [kg m^2]."""
    ratio = rotor.node_speed_ratio  # a machine: each part weighted by its ratio squared
    total = float(sum(d.Ip * ratio[d.n] ** 2 for d in rotor.disk_elements))
    if rotor.shaft_elements:
        geo = np.array([(e.idl, e.odl, e.idr, e.odr, e.L, e.material.rho)
                        for e in rotor.shaft_elements], dtype=float)
        x = 0.5 * (1.0 + _GL_X)
        do = geo[:, 1, None] + (geo[:, 3, None] - geo[:, 1, None]) * x
        di = geo[:, 0, None] + (geo[:, 2, None] - geo[:, 0, None]) * x
        polar = np.pi / 32.0 * (do**4 - di**4) @ (0.5 * _GL_W)
        weight = ratio[[int(e.nodes[0]) for e in rotor.shaft_elements]] ** 2
        total += float(np.sum(geo[:, 5] * geo[:, 4] * polar * weight))
    return total


def bind_speed(speed: float | SpeedProfile | TorqueDrive | Callable[[float], float],
               system: RotorSystem, rotor: Rotor | None, span: tuple[float, float],
               resolution: int) -> BoundSpeed:
    """The speed profile on the span of a transient; a :class:`TorqueDrive` gets the
    model's polar inertia and its nodes are checked against the shaft."""
    if not isinstance(speed, TorqueDrive):
        return as_speed_profile(speed).bind(span[0], span[1], resolution)
    n_shaft = shaft_node_count(system)
    for a in speed.torques:
        if a.node >= n_shaft:
            raise ModelError(f"node {a.node} is not a shaft node (0..{n_shaft - 1})",
                             a.label)
    _, all_free = spin_field(system)
    if all_free:
        inertia, source = model_polar_inertia(system), "model mass matrix"
    elif rotor is not None:
        inertia, source = element_polar_inertia(rotor), "shaft and disk elements"
    else:
        inertia, source = None, "none"
    return speed.bind(span[0], span[1], resolution, model_inertia=inertia, source=source)


@dataclass(frozen=True, eq=False)
class TorsionLoad:
    """``T(t) - M_t 1 W'(t)`` on the free DOFs [N m] (module docstring).

    ``inertial`` (n,) is ``M e`` with ``e`` the unit spin field, plus the inertia the
    drive adds beyond the model's at its node; ``positions`` the free index of the ``rz``
    DOF of each applied torque (-1 when fixed: the constraint takes it).
    """

    drive: BoundTorqueDrive
    inertial: FloatArray
    positions: np.ndarray

    @classmethod
    def build(cls, system: RotorSystem, drive: BoundTorqueDrive, mass: Any
              ) -> TorsionLoad | None:
        """The torsional load of ``drive`` on ``system`` (``mass`` its ``M`` on the free
        DOFs); None without free torsional DOFs."""
        e, all_free = spin_field(system)
        if not np.any(e):
            return None
        inertial: FloatArray = np.asarray(mass @ e, dtype=np.float64).reshape(-1)
        full = DOFS_PER_NODE * np.array([a.node for a in drive.drive.torques]) + RZ
        positions = system.dof_map.full_to_free[full]
        if all_free:
            inertial[positions[0]] += drive.inertia - float(e @ inertial)
        return cls(drive, inertial, positions)

    def __call__(self, t: float) -> FloatArray:
        f = self.inertial * -self.drive.acceleration(t)
        _, torques = self.drive.node_torques(t)
        held = self.positions >= 0
        np.add.at(f, self.positions[held], torques[held])
        return f
