"""Bifurcations of a periodic branch checked by time integration next to them.

:func:`verify_events` takes each event a :func:`rotorsim.periodic` branch reports and, on a
branch point on each side of it, measures the largest Floquet multiplier with
:func:`rotorsim.transient` on the full finite-element model (module
:mod:`rotorsim.verification.period_map`): a code path that shares nothing with harmonic
balance and its Floquet methods (Hill, Hsu, shooting on a reduced stability model) but the
element forces. With ``measure="floquet"`` the perturbation is instead the event's critical
Floquet eigenvector, followed by its left-eigenvector coordinate
(:mod:`rotorsim.verification.event_modes`, :mod:`~rotorsim.verification.mode_growth`): the
eigenvector comes from the stability model, the growth from the time integrator.

The sides. An event lies between branch points ``index`` and ``index + 1``. Its sides are
searched among the points between the neighbouring events (never past another event), at
most ``reach`` points away, nearest first, for a pair whose Floquet multipliers differ in
the number ``n`` of ``|mu| > 1 + margin``: a crossing large enough to measure in a few
periods. Without such a pair the event is not confirmed (the branch's own multipliers show
no measurable crossing next to it) and the nearest pair is still measured and reported.

The measurements at each side (from the harmonic-balance state ``(q0, v0)`` at phase 0,
the shaft angle ``options["shaft_angle"]``, the branch's unbalance, gravity and loads):

* ``local``: power iteration on the period map linearised at ``(q0, v0)`` by finite
  differences (``iterations`` one-period transients), the counterpart of Floquet's
  monodromy at the same state;
* ``trajectory``: growth of the difference of two free transients over ``periods``
  periods, from ``(q0, v0)`` and from ``(q0, v0)`` plus the perturbation;
* ``defect``: how far the transient is from the harmonic-balance state after one period
  (the truncation error of harmonic balance), and ``drift``: the farthest over the free run.

The perturbation: the orbit's state a quarter period ahead, less its mean, weighted by
``1 + (z - z_mid) / L`` along the shaft (so that it has mirror-symmetric and antisymmetric
parts: symmetry-breaking branch points grow from the latter), scaled to ``perturbation``
times the largest peak-to-peak of the orbit.

A side agrees with Floquet when, for ``max |mu|_F > 1 + margin`` (unstable),
the measurement exceeds ``1 + margin / 2`` and ``|ln rho - ln max |mu|_F| <=
tolerance * ln max |mu|_F``; for a stable side (``<= 1 + margin``), when it stays below
``1 + margin``. An event is confirmed when its sides show a Floquet crossing and both
measurements agree on both sides; a fold also needs its two orbits to stay apart: the sum
of the two drifts (defects without a free run) below their separation.

References
----------
Seydel (2010), *Practical Bifurcation and Stability Analysis*, sections 7.1-7.2 (monodromy
and multipliers of the period map); seed 002 section 3.5.3 (Floquet stability of rotor
orbits).
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from rotorsim.assembly.system import RotorSystem
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.results.event_verification import EventCheck, EventVerification, SideCheck
from rotorsim.results.periodic import PeriodicResult
from rotorsim.verification.event_input import (
    _check_input,
    _check_options,
    _excitation,
    _system,
)
from rotorsim.verification.event_modes import mode_problems, mode_sides, mode_text, retried
from rotorsim.verification.floquet_modes import BranchModes
from rotorsim.verification.full_branch import trace_unconfirmed
from rotorsim.verification.period_map import (
    FloatArray,
    linearised_growth,
    trajectory_growth,
)
from rotorsim.verification.shooting_sides import shooting_event

WHERE = "verify_events"


def verify_events(model: Rotor | RotorSystem | Any, result: PeriodicResult, *,
                  events: Sequence[int] | None = None, steps_per_period: int = 200,
                  iterations: int = 12, periods: int = 12, perturbation: float = 1e-3,
                  margin: float = 0.02, tolerance: float = 0.5, reach: int = 8,
                  measure: str = "orbit", trace: bool = False) -> EventVerification:
    """Check the bifurcations of a periodic branch by time integration next to them.

    Parameters
    ----------
    model : Rotor, RotorSystem or Model
        The model the branch was traced on (with its rolling bearings).
    result : PeriodicResult
        A speed branch of :func:`rotorsim.periodic` with stability, all nodes kept
        (``nodes=None``).
    events : sequence of int, optional
        Indices into ``result.bifurcations`` (default all).
    steps_per_period : int
        Constant time steps per period of the non-dissipative average-acceleration scheme.
    iterations : int
        Periods of power iteration on the linearised period map, per side.
    periods : int
        Periods of the two free transients per side (0: no free transient).
    perturbation : float
        Size of the perturbation relative to the orbit's largest peak-to-peak (small: the
        measurement is of the linearised map).
    margin : float
        Smallest ``max |mu| - 1`` counted as measurably unstable.
    tolerance : float
        Largest relative difference of ``ln max |mu|`` between measurement and Floquet on
        an unstable side.
    reach : int
        Branch points searched on each side of an event.
    measure : {"orbit", "floquet", "shooting"}
        "orbit": the measurements above along the orbit's own shape; "floquet": the growth
        of each event's critical Floquet mode along ``periods`` periods of two free
        transients per side (:mod:`rotorsim.verification.mode_growth`; ``iterations`` and
        ``tolerance`` are not used, ``perturbation`` sizes the mode). An event without a
        Floquet crossing is then reported without integration. "shooting": on each side
        the full model's own periodic orbit next to the branch's, found by shooting, and
        its multipliers from the monodromy matrix (:mod:`~.shooting_sides`; the event is
        confirmed when its multiplier of the event's kind crosses the unit circle between
        the sides by more than its error; ``steps_per_period`` and ``reach`` are used,
        ``margin`` only to count ``SideCheck.unstable``).
    trace : bool
        With ``measure="shooting"``: trace the full model's own branch by shooting
        continuation through the events the point-wise check leaves unconfirmed (a cluster
        of folds whose sheets the truncated series shifts), and confirm each that the full
        branch has in the same place of its sequence of events
        (:func:`~.full_branch.trace_unconfirmed`; minutes on a 150-DOF rotor).

    Returns
    -------
    EventVerification
        One :class:`~rotorsim.results.event_verification.EventCheck` per event, confirmed
        or not, with the reason and the numbers.

    Raises
    ------
    ModelError
        A result that is not a speed branch with stability and all nodes, a housing
        excitation or an approximation, a model with other DOFs, an event index out of
        range, bad options.

    Notes
    -----
    "Not confirmed" is not proof that an event is spurious. With ``measure="orbit"`` the
    perturbation follows the orbit's own lateral shape and the norm takes the lateral
    translations, so a mode the orbit does not contain, such as the rigid axial translation
    that grows past the clearance rotor's axial pitchforks near 353 rad/s
    (docs/validation.md case 26), is not seen: ``measure="floquet"`` follows that mode.
    Where the harmonic-balance orbit is far from the real trajectory (its truncation error
    next to contact onsets) the transient may contradict Floquet's multipliers.

    Examples
    --------
    >>> import rotorsim as rs
    >>> rotor = rs.Rotor([rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=rs.Material(
    ...     name="steel", E=211e9, G_s=81.2e9, rho=7810))] * 2, bearing_elements=[
    ...     rs.BearingElement(n=0, kxx=1e7, cxx=1e3), rs.BearingElement(n=2, kxx=1e7, cxx=1e3)])
    >>> branch = rs.periodic(rotor, start=100.0, stop=120.0, harmonics=1,
    ...                      unbalance=[(1, 1e-4, 0.0)], nodes=None)
    >>> len(rs.verify_events(rotor, branch))     # a linear rotor has no events
    0
    """
    clock = time.perf_counter()
    system = _system(model)
    numbers = _check_input(system, result, events)
    _check_options(steps_per_period, iterations, periods, perturbation, margin, tolerance,
                   reach)
    if measure not in ("orbit", "floquet", "shooting"):
        raise ModelError(f"must be 'orbit', 'floquet' or 'shooting', got {measure!r}",
                         f"{WHERE}.measure")
    if not isinstance(trace, bool):
        raise ModelError(f"must be True or False, got {trace!r}", f"{WHERE}.trace")
    if trace and measure != "shooting":
        raise ModelError(f"trace=True follows the full model's branch by shooting: it needs "
                         f"measure='shooting', got {measure!r}", f"{WHERE}.trace")
    if measure == "floquet" and periods < 2:
        raise ModelError(f"must be an integer >= 2 with measure='floquet', got {periods!r}",
                         f"{WHERE}.periods")
    excitation = _excitation(result)
    options = {"steps_per_period": int(steps_per_period), "iterations": int(iterations),
               "periods": int(periods), "perturbation": float(perturbation),
               "margin": float(margin), "tolerance": float(tolerance), "reach": int(reach),
               "measure": measure}
    run = {"system": system, "excitation": excitation, **options}
    measured: dict[tuple[int, int], SideCheck] = {}
    periods_run: list[int] = []
    checks = []
    modes = BranchModes(system, result, WHERE) if measure == "floquet" else None
    shots: dict[int, Any] = {}
    for number in numbers:
        if measure == "shooting":
            checks.append(shooting_event(result, number, _candidates(result, number, reach),
                                         run, shots))
            continue
        before, after, crossing = _sides(result, number, margin, reach)
        column = _column(result, number)
        if modes is not None:
            pair = mode_sides(result, modes, (before, after), crossing, column, run,
                              measured, periods_run, result.bifurcations[number].kind)
            checks.append(_verdict(result, number, pair[0], pair[1], crossing, margin,
                                   modes=True))
            continue
        sides = []
        for point in (before, after):
            if point is not None and (point, column) not in measured:
                measured[point, column] = _measure(result, point, column, run, periods_run)
            sides.append(None if point is None else measured[point, column])
        checks.append(_verdict(result, number, sides[0], sides[1], crossing, margin))
    notes: list[str] = []
    if trace and measure == "shooting":
        checks = trace_unconfirmed(result, checks, run, shots, notes=notes)
    stats = {"periods": float(sum(periods_run)), "points": float(len(measured) + len(shots)),
             "wall_time": time.perf_counter() - clock}
    return EventVerification(tuple(checks), options, stats, tuple(notes))


# ------------------------------------------------------------------------------ sides
def _sides(result: PeriodicResult, number: int, margin: float, reach: int
           ) -> tuple[int | None, int | None, bool]:
    """Branch points before and after event ``number``, and whether their Floquet
    multipliers cross ``1 + margin`` (module docstring)."""
    ev = result.bifurcations[number]
    before, after = _candidates(result, number, reach)
    counts = np.sum(np.abs(result.multipliers) > 1.0 + margin, axis=1)
    pairs = sorted(((a, b) for a in before for b in after),
                   key=lambda p: (ev.index - p[0]) + (p[1] - ev.index - 1))
    for a, b in pairs:
        if counts[a] != counts[b]:
            return a, b, True
    return (before[0] if before else None), (after[0] if after else None), False


def _candidates(result: PeriodicResult, number: int, reach: int
                ) -> tuple[list[int], list[int]]:
    """Branch points before and after event ``number``, nearest first, at most ``reach``
    on each side and never past a neighbouring event."""
    ev = result.bifurcations[number]
    others = [b.index for k, b in enumerate(result.bifurcations) if k != number]
    lo = max([i + 1 for i in others if i < ev.index], default=0)
    hi = min([i for i in others if i > ev.index], default=len(result) - 1)
    return (list(range(ev.index, max(lo, ev.index - reach + 1) - 1, -1)),
            list(range(ev.index + 1, min(hi, ev.index + reach) + 1)))


def _column(result: PeriodicResult, number: int) -> int:
    """ALL-DOF index of the translation that moves most at the event."""
    ev = result.bifurcations[number]
    translation = np.isin(result.dofs % 6, (0, 1))
    j = int(np.argmax(np.where(translation, ev.peak_to_peak, -np.inf)))
    return int(result.dofs[j])


# ------------------------------------------------------------------------------ measuring
def _perturbation(result: PeriodicResult, point: int, size: float
                  ) -> tuple[FloatArray, FloatArray]:
    q0, _ = result.state(point, 0.0)
    q1, v1 = result.state(point, 0.5 * np.pi)
    mean = np.zeros_like(q0)
    mean[result.dofs] = result.coefficients[point, 0]
    z = np.repeat(result.nodes_pos, 6)
    weight = 1.0 + (z - 0.5 * (z.max() + z.min())) / max(float(np.ptp(z)), 1e-12)
    dq, dv = weight * (q1 - mean), weight * v1
    translation = np.isin(np.arange(q0.size) % 6, (0, 1))
    ptp = float(np.max(result.peak_to_peak[point][np.isin(result.dofs % 6, (0, 1))]))
    scale = size * ptp / max(float(np.max(np.abs(dq[translation]))), 1e-300)
    return scale * dq, scale * dv


def _measure(result: PeriodicResult, point: int, column: int, run: dict[str, Any],
             periods_run: list[int]) -> SideCheck:
    """Time integration at one branch point (module docstring)."""
    q0, v0 = result.state(point, 0.0)
    ptp = float(result.peak_to_peak[point, np.searchsorted(result.dofs, column)])
    direction = _perturbation(result, point, run["perturbation"])
    floquet = float(result.max_multiplier[point])
    unstable = int(np.sum(np.abs(result.multipliers[point]) > 1.0 + run["margin"]))
    nan, empty = float("nan"), np.zeros(0)
    failures: list[str] = []
    local = retried(lambda pm: linearised_growth(pm, q0, v0, direction, run["iterations"]),
                     result, point, run, periods_run, failures)
    rho_l, factors_l = (nan, empty) if local is None else (local.rho, local.factors)
    free = None if not run["periods"] else retried(
        lambda pm: trajectory_growth(pm, q0, v0, direction, run["periods"]),
        result, point, run, periods_run, failures)
    rho_t, factors_t, defect, drift = nan, empty, nan, nan
    if free is not None:
        deviation = np.abs(free[1][:, column] - q0[column]) / ptp
        rho_t, factors_t = free[0].rho, free[0].factors
        defect, drift = float(deviation[1]), float(deviation.max())
    ok = not failures and _agrees(rho_l, floquet, run["margin"], run["tolerance"]) and (
        not run["periods"] or _agrees(rho_t, floquet, run["margin"], run["tolerance"]))
    message = "; ".join(failures) if failures else "" if ok else (
        f"measured max|mu| {rho_l:.4g} (linearised period map), {rho_t:.4g} (free "
        f"transient) against Floquet {floquet:.4g}")
    return SideCheck(point, float(result.parameter[point]), floquet, unstable, rho_l, rho_t,
                     factors_l, factors_t, defect, drift, ok, message)


def _agrees(measured: float, floquet: float, margin: float, tolerance: float) -> bool:
    """Measured growth per period against Floquet's ``max |mu|`` (module docstring)."""
    if not math.isfinite(measured):
        return False
    if floquet > 1.0 + margin:
        return measured > 1.0 + 0.5 * margin and abs(
            math.log(measured) - math.log(floquet)) <= tolerance * math.log(floquet)
    return measured <= 1.0 + margin


# ------------------------------------------------------------------------------ verdict
def _verdict(result: PeriodicResult, number: int, before: SideCheck | None,
             after: SideCheck | None, crossing: bool, margin: float, modes: bool = False
             ) -> EventCheck:
    ev = result.bifurcations[number]
    if before is None or after is None:
        return EventCheck(ev, number, before, after, False,
                          "no branch point on one side of the event (end of the branch)")
    separation = float("nan")
    problems = []
    if not crossing:
        problems.append(f"the branch's Floquet multipliers show no crossing of "
                        f"|mu| = 1 + {margin:g} next to it (max|mu| {before.floquet:.4g} at "
                        f"point {before.point}, {after.floquet:.4g} at point {after.point}, "
                        f"no other event in between)")
    for name, side in (("before", before), ("after", after)):
        if not side.agrees:
            problems.append(f"{name} (point {side.point}, {side.parameter:.6g} rad/s): "
                            f"{side.message}")
    if modes:
        problems.extend(mode_problems(ev.kind, before, after, margin))
    elif ev.kind == "fold":
        column = _column(result, number)
        qa, _ = result.state(before.point, 0.0)
        qb, _ = result.state(after.point, 0.0)
        ptp = float(np.max(result.peak_to_peak[[before.point, after.point],
                                               np.searchsorted(result.dofs, column)]))
        separation = abs(float(qa[column] - qb[column])) / ptp
        spread = before.drift + after.drift
        if math.isfinite(spread) and not spread < separation:
            problems.append(f"the transients move {spread:.3g} (relative) from their "
                            f"orbits, not less than the {separation:.3g} between the two "
                            "orbits of the fold")
    if problems:
        return EventCheck(ev, number, before, after, False, "; ".join(problems), separation)
    if modes:
        return EventCheck(ev, number, before, after, True, mode_text(before, after),
                          separation)
    text = (f"Floquet max|mu| {before.floquet:.4g} -> {after.floquet:.4g}; measured "
            f"{before.local:.4g} -> {after.local:.4g} (linearised period map)")
    if math.isfinite(before.trajectory):
        text += f", {before.trajectory:.4g} -> {after.trajectory:.4g} (free transient)"
    return EventCheck(ev, number, before, after, True, text, separation)
