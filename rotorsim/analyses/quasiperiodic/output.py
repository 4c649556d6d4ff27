"""A :class:`~rotorsim.results.quasi_periodic.QuasiPeriodicResult` from the tori of a
branch: kept DOFs, amplitudes on the torus grid, stability events."""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.quasiperiodic.beyond import motion_beyond
from rotorsim.analyses.quasiperiodic.stability import STABILITY_TOL
from rotorsim.errors import ModelError, Status
from rotorsim.results.quasi_periodic import QuasiPeriodicResult, TorusEvent

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
DOFS_PER_NODE = 6


def check_nodes(n_nodes: int, nodes: Sequence[int] | None) -> None:
    """ModelError for a kept node outside ``0 .. n_nodes - 1`` (before any solve)."""
    for node in nodes or ():
        if isinstance(node, bool) or not 0 <= int(node) < n_nodes:
            raise ModelError(f"node {node!r} outside 0..{n_nodes - 1}", "periodic.nodes")


def kept_columns(branch: Any, nodes: Sequence[int] | None) -> tuple[IntArray, IntArray]:
    """Active columns and ALL-DOF indices of the kept DOFs: those of ``nodes`` (all when
    None) plus the bearing DOFs."""
    point = branch.points[0]
    dm = point.system.dof_map
    active_all = dm.free[point.rotor_problem.active]
    if nodes is None:
        keep = np.ones(active_all.size, dtype=bool)
    else:
        check_nodes(dm.n_nodes, nodes)
        chosen = [np.zeros(0, dtype=np.int64)]
        for node in nodes:
            chosen.append(DOFS_PER_NODE * int(node) + np.arange(DOFS_PER_NODE))
        keep = np.isin(active_all, np.concatenate(chosen))
        keep[point.rotor_problem.problem.nl_dofs] = True
    columns = np.flatnonzero(keep).astype(np.int64)
    return columns, active_all[columns].astype(np.int64)


def stability_events(speed: FloatArray, exponents: FloatArray, frequencies: FloatArray,
                     tol: float = STABILITY_TOL) -> tuple[TorusEvent, ...]:
    """Changes of stability between consecutive points: the growth per revolution
    ``exponent 2 pi / W`` crosses ``tol`` (the crossing interpolated linearly)."""
    g = exponents * 2 * np.pi / speed - tol
    out = []
    for i in range(speed.size - 1):
        a, b = g[i], g[i + 1]
        if not (np.isfinite(a) and np.isfinite(b)) or (a < 0) == (b < 0):
            continue
        at = speed[i] + (speed[i + 1] - speed[i]) * a / (a - b)
        kind = "loss_of_stability" if b >= 0 else "regain_of_stability"
        out.append(TorusEvent(kind, float(at), i, (float(exponents[i]),
                                                   float(exponents[i + 1])),
                              float(frequencies[i + 1])))
    return tuple(out)


LYAPUNOV_PERIODS = 20
"""Shaft revolutions of the Lyapunov estimate attached to a stability change (its
resolution is about ``1 / T``: growth rates of the order of ``W / 20`` and up)."""
TONE_TOL = 1e-3
"""A critical frequency within this fraction of ``W`` of a tone (or half a tone) is that
tone (or half)."""


def character(frequency: float, tones: FloatArray, w1: float) -> str:
    """``"fold"``, ``"doubling"`` or ``"third frequency"`` of a critical exponent with
    ``|Im lam| = frequency`` [rad/s] against the tone frequencies ``tones`` [rad/s]
    (:class:`~rotorsim.results.quasi_periodic.TorusEvent`)."""
    if not np.isfinite(frequency):
        return ""
    lattice = np.abs(np.concatenate([[0.0], np.asarray(tones, dtype=float)]))
    tol = TONE_TOL * w1
    if np.min(np.abs(frequency - lattice)) <= tol:
        return "fold"
    if np.min(np.abs(frequency - lattice / 2)) <= tol:
        return "doubling"
    return "third frequency"


def with_evidence(events: Sequence[TorusEvent], branch: Any) -> tuple[TorusEvent, ...]:
    """``events`` with the Lyapunov exponent of the unstable side's torus, the character
    of the critical exponent and, for a loss of stability, what the motion is there
    (:func:`~.beyond.motion_beyond`, unless ``branch.beyond`` is None)."""
    out = []
    for ev in events:
        unstable = ev.index + 1 if ev.kind == "loss_of_stability" else ev.index
        point = branch.points[unstable]
        h = point.solution.aft.harmonics
        estimate = point.stability(periods=LYAPUNOV_PERIODS)
        beyond = getattr(branch, "beyond", None)
        motion = motion_beyond(point, branch.unbalance, branch.excitation, settle=beyond[0],
                               record=beyond[1]) \
            if beyond is not None and ev.kind == "loss_of_stability" else None
        out.append(dataclasses.replace(
            ev, lyapunov=float(estimate.exponent),
            character=character(ev.frequency, h.frequencies(point.speed, point.vc_frequency),
                                point.speed), motion=motion))
    return tuple(out)


def quasi_periodic_result(branch: Any, nodes: Sequence[int] | None, options: dict[str, Any],
                          clock: float) -> QuasiPeriodicResult:
    """The result of ``branch`` (a :class:`~.branch.QuasiPeriodicBranch`) keeping ``nodes``
    (``clock``: the run's start time)."""
    columns, dofs = kept_columns(branch, nodes)
    first = branch.points[0]
    X = np.stack([p.solution.X[:, columns] for p in branch.points])
    samples = np.stack([first.solution.aft.to_samples(x) for x in X])
    speed = branch.speeds
    freq = np.array([s.exponents.critical_frequency if s is not None else np.nan
                     for s in branch.stability])
    system, plan = first.system, first.rotor_problem.plan
    held = np.setdiff1d(np.arange(system.n_free), first.rotor_problem.active)
    return QuasiPeriodicResult(
        speed=speed, vc_frequency=np.array([p.vc_frequency for p in branch.points]),
        vc_order=float(first.rotor_problem.vc_order),
        tones=np.asarray(first.solution.aft.harmonics.k, dtype=np.int64), dofs=dofs,
        coefficients=X, max_abs=np.abs(samples).max(axis=1),
        peak_to_peak=np.ptp(samples, axis=1), exponents=branch.exponents,
        exponents_converged=np.array([s is not None and s.converged
                                      for s in branch.stability]),
        stability_method="hill" if np.isfinite(branch.exponents).any() else "none",
        events=with_evidence(stability_events(speed, branch.exponents, freq), branch),
        stability_tol=STABILITY_TOL,
        exponents_checked=np.array([s is not None and s.checked for s in branch.stability],
                                   dtype=bool),
        iterations=np.array([p.solution.iterations for p in branch.points], dtype=np.int64),
        residuals=np.array([p.solution.residual for p in branch.points]),
        held_dofs=system.dof_map.free[held].astype(np.int64), dof_map=system.dof_map,
        nodes_pos=np.asarray(system.nodes_pos, dtype=float),
        second="vc" if plan is None else plan.second,
        approximation="" if plan is None else plan.approximation, options=options,
        stats={"points": float(len(branch)), "stability_time": branch.stability_time,
               "wall_time": time.perf_counter() - clock},
        status=Status.OK if branch.status == "ok" else Status.NOT_CONVERGED, reason=branch.reason,
        summary=dict(system.summary))
