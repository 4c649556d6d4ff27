"""The input of :func:`rotorsim.verify_events`: the model assembled, the branch and the
options checked (each error names what is wrong), the branch's excitation for the
transient."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from rotorsim.assembly.system import RotorSystem, assemble
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.options import Excitation
from rotorsim.results.periodic import PeriodicResult

WHERE = "verify_events"


def _system(model: Any) -> RotorSystem:
    if isinstance(model, RotorSystem):
        return model
    if not isinstance(model, Rotor) and hasattr(model, "rotor"):
        model = model.rotor.with_nonlinear(tuple(getattr(model, "rolling_bearings", ())))
    if not isinstance(model, Rotor):
        raise ModelError(f"expected a Rotor, RotorSystem or Model, got "
                         f"{type(model).__name__}", f"{WHERE}.model")
    return assemble(model)


def _check_input(system: RotorSystem, result: Any, events: Sequence[int] | None
                 ) -> list[int]:
    """The event numbers to check; ModelError naming what is wrong with the input."""
    if not isinstance(result, PeriodicResult):
        raise ModelError(f"expected a PeriodicResult, got {type(result).__name__}",
                         f"{WHERE}.result")
    if not result.has_stability:
        raise ModelError("the branch has no Floquet multipliers: run rs.periodic with "
                         "stability (the default 'auto'), not stability=None",
                         f"{WHERE}.result")
    if result.parameter_name != "speed" or result.options.get("base") is not None:
        raise ModelError("only speed branches forced by unbalance, gravity and constant "
                         "loads can be integrated at constant speed (not a frequency branch "
                         "or a housing excitation)", f"{WHERE}.result")
    if result.approximation:
        raise ModelError(f"the branch neglects something the transient keeps "
                         f"({result.approximation})", f"{WHERE}.result")
    if system.dof_map.ndof != result.dof_map.ndof:
        raise ModelError(f"the model has {system.dof_map.ndof} DOFs, the branch "
                         f"{result.dof_map.ndof}: not the model of this branch",
                         f"{WHERE}.model")
    lateral = [6 * n + k for n in range(system.dof_map.n_nodes) for k in (0, 1, 3, 4)]
    if not np.all(np.isin(np.setdiff1d(lateral, result.held_dofs), result.dofs)):
        raise ModelError("the branch kept only some nodes: the transient needs the state "
                         "on all DOFs (run rs.periodic with nodes=None)", f"{WHERE}.result")
    count = len(result.bifurcations)
    if events is None:
        return list(range(count))
    numbers = []
    for i, e in enumerate(events):
        if not (isinstance(e, int | np.integer) and not isinstance(e, bool)
                and 0 <= int(e) < count):
            raise ModelError(f"{e!r} is not an index of the branch's {count} "
                             "bifurcations", f"{WHERE}.events[{i}]")
        numbers.append(int(e))
    return numbers


def _check_options(steps: int, iterations: int, periods: int, perturbation: float,
                   margin: float, tolerance: float, reach: int) -> None:
    for name, value, low in (("steps_per_period", steps, 20), ("iterations", iterations, 2),
                             ("periods", periods, 0), ("reach", reach, 1)):
        if not (isinstance(value, int | np.integer) and not isinstance(value, bool)
                and value >= low):
            raise ModelError(f"must be an integer >= {low}, got {value!r}",
                             f"{WHERE}.{name}")
    bounds = {"perturbation": (perturbation, 0.1), "margin": (margin, 1.0),
              "tolerance": (tolerance, 10.0)}
    for name, (number, high) in bounds.items():
        if not (isinstance(number, int | float) and 0 < number <= high):
            raise ModelError(f"must be in (0, {high}], got {number!r}", f"{WHERE}.{name}")


def _excitation(result: PeriodicResult) -> Excitation:
    """The branch's unbalance, gravity and loads, for the transient."""
    o = result.options
    return Excitation(unbalance=[(int(n), float(me), float(a)) for n, me, a in o["unbalance"]],
                      gravity=o["gravity"], direction=tuple(o["direction"]),
                      loads=[(int(n), str(d), float(v)) for n, d, v in o["loads"]])
