"""The equation of motion of a rotor transient as a rotor-agnostic second-order problem.

``M q'' + (C + W(t) G + C_b(W)) q' + (K + K_b(W)) q + r(q, q', phi(t), W(t)) = f(t)``: the
assembled matrices (dense up to :data:`DENSE_STEPPING` free DOFs), the bearings tabulated
over speed as speed terms when the speed varies (:mod:`~.variable_bearings`), the nonlinear
elements (and a torque drive's slip damping) as the restoring force, and the loads:
gravity, point loads, unbalance with its ``W'`` term, base excitation, user forces and a
torque drive's torsional loads (:class:`~.loads.TransientLoads`).
"""

from __future__ import annotations

from typing import cast

import numpy as np

from rotorsim.analyses.transient.loads import (
    BaseExcitation,
    RestoringForce,
    TransientLoads,
)
from rotorsim.analyses.transient.speed_profile import BoundSpeed
from rotorsim.analyses.transient.torque_damping import with_torque_damping
from rotorsim.analyses.transient.torque_drive import BoundTorqueDrive
from rotorsim.analyses.transient.torsion_loads import TorsionLoad
from rotorsim.analyses.transient.variable_bearings import (
    SpeedDependentBearings,
    without_variable_bearings,
)
from rotorsim.assembly.loads import (
    gravity_load,
    nodal_load,
    rigid_translation,
    unbalance_amplitudes,
    unbalance_speed_ratios,
)
from rotorsim.assembly.system import RotorSystem, SystemMatrices
from rotorsim.errors import ModelError
from rotorsim.options import Excitation
from rotorsim.time_integration.problem import SecondOrderProblem

WHERE = "transient"
DENSE_STEPPING = 400
"""Up to this many free DOFs the matrices are dense: a step's few matrix-vector products
then cost less than scipy.sparse's call overhead."""


def rotor_problem(system: RotorSystem, profile: BoundSpeed, t0: float, ex: Excitation
                  ) -> tuple[SecondOrderProblem, TransientLoads]:
    """The equation of motion of ``system`` for a run at ``profile`` from ``t0`` with the
    excitation ``ex``, and its load function (module docstring)."""
    unbalance, forces = ex.unbalance, ex.forces
    base = cast("BaseExcitation | None", ex.base)  # checked by _groups
    description = profile.describe()
    constant_speed = description["kind"] == "constant"
    variable = None
    if system.variable_bearings and not constant_speed:
        variable = SpeedDependentBearings.from_system(system)
        mats = SystemMatrices(**without_variable_bearings(system, profile.speed(t0)))
    else:
        mats = system.matrices(profile.speed(t0) if constant_speed else 0.0)
    constant = np.zeros(system.n_free)
    if ex.gravity is not None:
        constant += gravity_load(system, ex.gravity, ex.direction)
    for i, (node, dof, value) in enumerate(ex.loads):
        constant += nodal_load(system, int(node), str(dof), float(value),
                               where=f"loads[{i}]")
    if forces is not None and not callable(forces):
        raise ModelError("forces must be a callable f(t) -> array (n_free,)", WHERE)
    base_load = None
    if base is not None:
        e = rigid_translation(system.dof_map.n_nodes, base.direction)[system.dof_map.free]
        base_load = -(mats.M @ e)
    loads_fn = TransientLoads(
        n=system.n_free, speed=profile, constant=constant,
        unbalance=unbalance_amplitudes(system, unbalance) if unbalance else None,
        unbalance_ratio=unbalance_speed_ratios(system, unbalance) if unbalance else None,
        base=base_load, base_acceleration=None if base is None else base.acceleration,
        forces=forces, torsion=TorsionLoad.build(system, profile, mats.M)
        if isinstance(profile, BoundTorqueDrive) else None)
    loads_fn(t0)  # fail early on bad callbacks
    restoring = with_torque_damping(None if system.nonlinear is None else
                                    RestoringForce(system.nonlinear, profile), system, profile)
    has_gyro = mats.G.nnz > 0
    M, K, C, G = (m.toarray() if system.n_free <= DENSE_STEPPING else m
                  for m in (mats.M, mats.K, mats.C, mats.G))
    problem = SecondOrderProblem(
        mass=M, stiffness=K, damping=C, restoring=restoring, load=loads_fn,
        gyroscopic=G if has_gyro else None, speed_terms=variable,
        speed=profile.speed if has_gyro or variable is not None else None)
    return problem, loads_fn
