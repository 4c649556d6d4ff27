"""The speed damping of the drive torques on the torsional DOFs (slip damping of a motor).

A torque law ``T(W)`` acting at a node that twists with velocity ``theta'`` (relative to
the rigid spin) sees the speed ``W + theta'``; to first order it adds ``(dT/dW) theta'``
at that node. For a motor in its stable branch (``dT_m/dW < 0``, above the breakdown
speed of an induction motor) this is a damper ``c = -dT_m/dW`` on the drive node: the
"electrical damping" of the static motor characteristic (Dresig & Holzweissig, *Dynamics
of Machinery*, Springer 2010, on drive systems with motor characteristics; Laschet,
*Simulation von Antriebssystemen*, Springer 1988, on motor models in drive trains). A fan adds
``c = dT_L/dW = 2 c_fan W`` at its node. Below the breakdown speed an induction motor's
slope is positive: the term is a negative damping, as the quasi-static characteristic
says (a dynamic motor model would be needed to do better).

The damping changes with the speed, so it is a restoring term ``r = -s(t) theta'`` with
the local damping tangent ``-s(t)`` (:class:`~rotorsim.time_integration.local_tangent.
LocalMatrix`) on the ``rz`` DOFs of the torque nodes: the steppers update their
factorisation by a low-rank solve.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.analyses.transient.torque_drive import BoundTorqueDrive
from rotorsim.analyses.transient.torque_laws import ConstantTorque, PulsatingTorque
from rotorsim.analyses.transient.torsion_loads import RZ
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.time_integration.local_tangent import LocalMatrix


@dataclass(frozen=True, eq=False)
class TorqueDamping:
    """``r = -s(t) theta'`` on the free ``rz`` DOFs ``positions`` of the torque nodes;
    ``gather[i]`` places applied torque ``i`` among them (-1: its ``rz`` is fixed)."""

    drive: BoundTorqueDrive
    positions: np.ndarray
    gather: np.ndarray
    size: int

    @classmethod
    def build(cls, system: RotorSystem, drive: BoundTorqueDrive) -> TorqueDamping | None:
        """None when switched off, when no torque depends on the speed or when no torque
        node has a free ``rz``."""
        torques = drive.drive.torques
        if not drive.drive.torque_damping or not any(_speed_dependent(a.law)
                                                     for a in torques):
            return None
        full = DOFS_PER_NODE * np.array([a.node for a in torques], dtype=np.int64) + RZ
        free = system.dof_map.full_to_free[full]
        held = free >= 0
        if not np.any(held):
            return None
        positions, inverse = np.unique(free[held], return_inverse=True)
        gather = np.full(free.size, -1, dtype=np.int64)
        gather[held] = inverse
        return cls(drive, positions.astype(np.int64), gather, system.n_free)

    def coefficients(self, t: float) -> FloatArray:
        """Damping ``c = -sum dT_signed/dW`` [N m s/rad] at each of ``positions``."""
        _, slopes = self.drive.slopes(t)
        c = np.zeros(self.positions.size)
        on = self.gather >= 0
        np.add.at(c, self.gather[on], -slopes[on])
        return c

    def __call__(self, q: FloatArray, v: FloatArray, t: float
                 ) -> tuple[FloatArray, None, LocalMatrix]:
        c = self.coefficients(t)
        r = np.zeros(self.size)
        r[self.positions] = c * v[self.positions]
        return r, None, LocalMatrix.trusted(self.size, self.positions, np.diag(c))


def with_torque_damping(restoring: Any, system: RotorSystem, profile: object) -> Any:
    """``restoring`` (the nonlinear elements' force, or None) with the torque damping of
    a torque drive added (:class:`~.loads.RestoringForce` ``damping``)."""
    if not isinstance(profile, BoundTorqueDrive):
        return restoring
    damping = TorqueDamping.build(system, profile)
    if damping is None or restoring is None:
        return restoring if damping is None else damping
    restoring.damping = damping
    return restoring


def _speed_dependent(law: object) -> bool:
    if isinstance(law, ConstantTorque):
        return False
    if isinstance(law, PulsatingTorque):
        return _speed_dependent(law.base)
    return True
