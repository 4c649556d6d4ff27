"""What a rotor transient records and when it stops: the rotor side of
:class:`~rotorsim.time_integration.output.OutputSpec` and of
:class:`~rotorsim.time_integration.steady.SteadyDetector`.

The integrator knows unknowns and a monotone segment counter; this module maps the options
of :func:`~rotorsim.analyses.transient.transient.transient` onto them:

- kept DOFs and their velocities (those of the nonlinear DOFs are always recorded, since
  the bearing loads need them, but returned only on request);
- the reducers of ``rs.Output(reducers=...)`` on the kept DOFs (through the basis rows
  after a Craig-Bampton reduction, so they are physical), per shaft revolution
  ``floor(phi / 2 pi)`` for the peak-to-peak, on ``(ux, uy)`` pairs for the radial
  amplitude;
- the steady-state stop of ``rs.SteadyStop``, per shaft revolution.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from rotorsim.analyses.transient.speed_profile import BoundSpeed
from rotorsim.assembly.reduction import ReducedBasis
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError
from rotorsim.options import Output, SteadyStop
from rotorsim.results.transient_state import radial_pairs
from rotorsim.time_integration.base import State
from rotorsim.time_integration.integrate import IntegrationResult
from rotorsim.time_integration.output import OutputSpec, Reducer
from rotorsim.time_integration.steady import SteadyDetector

WHERE = "transient"
TWO_PI = 2.0 * math.pi


def revolutions(profile: BoundSpeed) -> Callable[[State], float]:
    """``state -> phi(t) / 2 pi``, the shaft revolutions of the schedule."""
    return lambda state: profile.angle(state.t) / TWO_PI


def output_spec(out: Output, system: RotorSystem, kept: np.ndarray,
                basis: ReducedBasis | None, profile: BoundSpeed) -> OutputSpec:
    """The integrator's output: samples, kept unknowns, velocities and reducers."""
    nl = system.nonlinear
    rows = None if basis is None else basis.T[kept]
    if out.velocities:
        velocities: Any = True
    elif nl is None:
        velocities = False
    else:  # the bearing loads need them; the leading reduced coordinates are the nl DOFs
        velocities = nl.dofs if basis is None else np.arange(basis.boundary.size)
    after = -math.inf if out.after is None else float(out.after)
    reducers = tuple(_reducer(name, system, kept, rows, profile, after)
                     for name in out.reducers)
    times = None if out.times is None else np.asarray(out.times, dtype=float)
    return OutputSpec(times=times, every=None if times is not None else out.every,
                      dofs=kept if basis is None else None, velocities=velocities,
                      reducers=reducers)


def _reducer(name: str, system: RotorSystem, kept: np.ndarray, rows: FloatArray | None,
             profile: BoundSpeed, after: float) -> Reducer:
    columns = np.arange(kept.size)
    if name == "max_amplitude":
        pairs = radial_pairs(system.dof_map.free[kept])
        if not pairs.nodes.size:
            raise ModelError("max_amplitude needs a node with both ux and uy kept",
                             f"{WHERE}.output.reducers")
        columns = np.column_stack([pairs.x, pairs.y]).ravel()
    kind = "max_abs" if name == "max_abs" else name
    segment = revolutions(profile) if name == "peak_to_peak" else None
    selection: dict[str, Any] = ({"dofs": tuple(int(i) for i in kept[columns])}
                                 if rows is None else {"transform": rows[columns]})
    return Reducer(kind, "q", after=after, name=name, segment=segment,  # type: ignore[arg-type]
                   segment_label="revolution", **selection)


def steady_detector(steady: SteadyStop | None, out_nodes: Sequence[int] | None,
                    system: RotorSystem, basis: ReducedBasis | None,
                    profile: BoundSpeed) -> SteadyDetector | None:
    """The stop predicate of ``steady`` (None without), on the watched free DOFs."""
    if steady is None:
        return None
    if not isinstance(steady, SteadyStop):
        raise ModelError(f"expected rs.SteadyStop or None, got {type(steady).__name__}",
                         f"{WHERE}.steady")
    nodes = steady.nodes or out_nodes or range(system.dof_map.n_nodes)
    watched: list[int] = []
    for node in nodes:
        if not 0 <= int(node) < system.dof_map.n_nodes:
            raise ModelError(f"node {node} outside 0..{system.dof_map.n_nodes - 1}",
                             f"{WHERE}.steady.nodes")
        watched.extend(int(i) for i in system.dofs_of(int(node), tuple(steady.dofs)))
    if not watched:
        raise ModelError(f"no free DOF {list(steady.dofs)} at nodes {list(nodes)}",
                         f"{WHERE}.steady")
    idx = np.asarray(watched, dtype=np.int64)
    selection: dict[str, Any] = ({"dofs": idx} if basis is None
                                 else {"transform": basis.T[idx]})
    return SteadyDetector(revolutions(profile), rtol=steady.rtol, atol=steady.atol,
                          revolutions=steady.revolutions, **selection)


def stop_record(run: IntegrationResult, detector: SteadyDetector | None,
                profile: BoundSpeed) -> dict[str, Any] | None:
    """``options["stopped"]`` of a run that stopped early (None when it did not): the
    reason, the time, the revolution (the last one completed) and for a steady stop the
    relative change of the peak-to-peak over the last revolution."""
    if not run.stopped:
        return None
    t = float(run.state.t)
    record: dict[str, Any] = {"reason": run.stopped, "t": t,
                              "revolution": math.floor(profile.angle(t) / TWO_PI)}
    if detector is not None:  # the last closed revolution, which ends at t
        record.update(criterion="steady", revolution=detector.segment_index,
                      relative_change=float(detector.change))
    return record


def expanded(run: IntegrationResult, basis: ReducedBasis, kept: np.ndarray
             ) -> IntegrationResult:
    """A reduced run's samples on the kept free DOFs (``q = T x``); velocities likewise, or
    those of the boundary (nonlinear) DOFs only, the leading reduced coordinates."""
    rows = basis.T[kept]
    v, v_dofs = run.v, run.v_dofs
    if v is not None and v_dofs is not None and v_dofs.size == basis.size:
        v, v_dofs = v @ rows.T, kept
    elif v is not None:
        v_dofs = basis.boundary
    return dataclasses.replace(run, q=run.q @ rows.T, v=v, v_dofs=v_dofs,
                               dofs=np.asarray(kept, dtype=np.int64))


LOAD_CHUNK = 2048
"""Samples per evaluation of the bearing loads after a run: the tangents the elements
return with their forces (``(S, n, n)`` each) then take a bounded amount of memory, not
one proportional to a long run's length."""


def bearing_loads(run: IntegrationResult, system: RotorSystem, angle: FloatArray,
                  speed: FloatArray) -> FloatArray:
    """Load ``[Fx, Fy, Fz, Mx, My]`` (k, b, 5) on the inner ring of every nonlinear
    bearing at every sample, evaluated :data:`LOAD_CHUNK` samples at a time."""
    nl = system.nonlinear
    assert nl is not None
    cols = np.searchsorted(run.dofs, nl.dofs)
    v = bearing_velocities(run, system)
    if v is None:  # recorded with the samples whenever there are nonlinear DOFs
        raise AssertionError("the bearing loads need the velocities of the bearing DOFs")
    q = run.q[:, cols]
    loads = np.empty((run.t.size, len(nl.elements), 5))
    for start in range(0, run.t.size, LOAD_CHUNK):
        part = slice(start, start + LOAD_CHUNK)
        out = nl.evaluate(q[part], v[part], angle[part], speed[part])
        loads[part] = np.stack([f[:, :5] for f in out.element_forces], axis=1)
    return loads


def bearing_velocities(run: IntegrationResult, system: RotorSystem) -> FloatArray | None:
    """Velocities (k, nl.k) of the nonlinear DOFs from a run's records (None without)."""
    nl = system.nonlinear
    if nl is None or run.v is None:
        return None
    vdofs = run.dofs if run.v_dofs is None else run.v_dofs
    column = {int(d): i for i, d in enumerate(vdofs)}
    return run.v[:, [column[int(d)] for d in nl.dofs]]


def kept_velocities(run: IntegrationResult, out: Output) -> FloatArray | None:
    """The velocities the result returns: those of the kept DOFs on request, else None."""
    return run.v if out.velocities else None
