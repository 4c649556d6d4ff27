"""Craig-Bampton reduction of a rotor transient (:mod:`rotorsim.assembly.reduction`).

The nonlinear DOFs stay physical (the leading reduced coordinates); the interior is
represented by constraint modes, the lowest fixed-interface modes and the static responses
to the run's load shapes (constant loads, both phases of the unbalance, base excitation), so
the static start is exact. The accuracy is reported with the run: the lowest natural
frequencies of the full and reduced systems with the bearings replaced by their nominal
tangent.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from rotorsim.analyses.statics.nonlinear_static import nominal_tangent
from rotorsim.analyses.transient.loads import RestoringForce, TransientLoads
from rotorsim.assembly.reduction import ReducedBasis, accuracy, craig_bampton
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError
from rotorsim.time_integration.integrate import IntegrationResult
from rotorsim.time_integration.problem import SecondOrderProblem


def reduce_problem(system: RotorSystem, problem: SecondOrderProblem, loads: TransientLoads,
                   num_modes: int, speed: float,
                   modes: tuple[FloatArray, FloatArray] | None = None,
                   check: bool = True, interior: tuple[Any, Any, Any] | None = None,
                   basis: ReducedBasis | None = None
                   ) -> tuple[SecondOrderProblem, ReducedBasis, dict[str, Any]]:
    """The reduced problem, its basis and the accuracy report (``modes``: the
    fixed-interface modes when already computed; ``check`` False leaves out the frequency
    check, for a caller that checks the basis otherwise; ``interior``: ``K_ii``, ``M_ii``
    and the factorisation of ``K_ii`` when already computed, as for
    :func:`~rotorsim.assembly.reduction.craig_bampton`; ``basis``: the basis itself when
    already built on the nonlinear DOFs with :func:`load_shapes`, the other arguments
    but ``num_modes`` then unused)."""
    nl = system.nonlinear
    if nl is None or not isinstance(problem.restoring, RestoringForce):
        raise ModelError("reduction keeps the nonlinear DOFs physical: the model has none",
                         "transient.reduction")
    if basis is None:
        basis = craig_bampton(system, nl.dofs, num_modes, static_loads=load_shapes(loads),
                              speed=speed, modes=modes, interior=interior)
    freq = accuracy(system, basis, nominal_tangent(system), speed=speed) if check else None
    T = basis.T
    reduced = {name: None if getattr(problem, name) is None else basis.reduce(
        getattr(problem, name)) for name in ("mass", "stiffness", "damping", "gyroscopic")}
    restoring = RestoringForce(nl, problem.restoring.speed,
                               index=np.arange(nl.k, dtype=np.int64), size=basis.size)
    new = SecondOrderProblem(mass=reduced["mass"], stiffness=reduced["stiffness"],
                             damping=reduced["damping"], restoring=restoring,
                             load=lambda t: T.T @ loads(t), gyroscopic=reduced["gyroscopic"],
                             speed=problem.speed)
    report: dict[str, Any] = {"fixed_interface_modes": int(basis.frequencies.size),
                              "requested_modes": int(num_modes), "size": basis.size,
                              "full_size": system.n_free, "static_vectors": basis.n_static,
                              "highest_mode": float(basis.frequencies[-1])
                              if basis.frequencies.size else 0.0}
    if freq is not None:
        report |= {"max_relative_error": freq["max_relative_error"],
                   "check_frequencies_full": np.asarray(freq["full"]).tolist(),
                   "check_frequencies_reduced": np.asarray(freq["reduced"]).tolist()}
    return new, basis, report


def load_shapes(loads: TransientLoads) -> list[FloatArray]:
    """The load shapes whose static responses a transient's basis holds: the constant
    loads, both phases of the unbalance and the base excitation (the non-zero ones)."""
    shapes = [loads.constant]
    if loads.unbalance is not None:
        shapes += [loads.unbalance.real, loads.unbalance.imag]
    if loads.base is not None:
        shapes.append(loads.base)
    return [s for s in shapes if np.any(s)]


def expand_run(run: IntegrationResult, basis: ReducedBasis, kept: FloatArray
               ) -> IntegrationResult:
    """The run's samples on the kept free DOFs (``q = T x``)."""
    rows = basis.T[np.asarray(kept, dtype=np.int64)]
    q = run.q @ rows.T
    v = None if run.v is None else run.v @ rows.T
    return dataclasses.replace(run, q=q, v=v, dofs=np.asarray(kept, dtype=np.int64))
