"""The sides of an event checked by shooting on the full model
(``rs.verify_events(..., measure="shooting")``).

On each side of an event, the nearest branch points (never past a neighbouring event, at
most ``reach`` points away) whose orbit the full finite-element model also has: shooting
(:func:`~rotorsim.verification.full_shooting.shoot_full_model`) from the harmonic-balance
state converges to a periodic orbit of the time-integrated model next to it. Points next
to a fold may have none (the truncated series moves the fold); they are skipped and said
so. The multipliers of that orbit are the eigenvalues of its monodromy matrix, with an
error estimate from a second integration at twice the steps.

The event's multiplier on each side is the one of its kind with the largest modulus: real
and positive for a fold or branch point, real and negative for a period doubling, a complex
pair for Neimark-Sacker (:func:`~rotorsim.verification.mode_growth.kind_of`). The event is
**confirmed** when that multiplier is inside the unit circle on one side and outside on
the other, each by more than half its change between the two step sizes (1.5 times the
Richardson estimate of the error of the finer one: ``|mu_h/2 - mu| ~ |mu_h - mu_h/2| / 3``
for a second-order scheme). No growth margin is needed: the multipliers are computed, not
measured from growth over a few periods, so the saddles of a lightly damped rotor's folds
(``|mu| = 1.001 ... 1.02``) are resolved. Where harmonic balance's Floquet multipliers put a
side on the other side of the circle than shooting, the reason says so; the verdict follows
the full model.

References
----------
Seydel (2010), *Practical Bifurcation and Stability Analysis*, sections 7.1-7.4; seed 002
section 3.5.3.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorsim.errors import ConvergenceError
from rotorsim.results.event_verification import EventCheck, SideCheck
from rotorsim.results.periodic import PeriodicResult
from rotorsim.verification.event_modes import KINDS
from rotorsim.verification.full_shooting import FullOrbit, shoot_full_model, speed_problem
from rotorsim.verification.mode_growth import kind_of

Shot = FullOrbit | str


NEUTRAL = 1e-6
"""Multipliers within this of the unit circle are neutral modes, not crossings: undamped
modes (the torsion of a shaft without material damping), whose moduli the
average-acceleration scheme keeps at 1 to round-off."""


def kind_multiplier(multipliers: np.ndarray, kind: str) -> int | None:
    """Index of the multiplier of the event's ``kind`` with the largest modulus among
    ``multipliers`` (by decreasing modulus), neutral ones (:data:`NEUTRAL`) left out; None
    when there is none."""
    wanted = KINDS.get(kind, kind)
    for j, mu in enumerate(multipliers):
        if abs(abs(mu) - 1.0) > NEUTRAL and kind_of(complex(mu)) == wanted:
            return j
    return None


def shoot_point(result: PeriodicResult, point: int, run: dict[str, Any]) -> Shot:
    """The full model's orbit next to branch point ``point``, or why there is none."""
    system = run["system"]
    free = system.dof_map.free
    held = np.flatnonzero(np.isin(free, result.held_dofs)).astype(np.int64)
    problem, keep = speed_problem(system, float(result.speed[point]), run["excitation"],
                                  float(result.options.get("shaft_angle", 0.0)), held)
    q, v = result.state(point, 0.0)
    omega = float(result.fundamental[point])
    lateral = np.isin(result.dofs % 6, (0, 1))
    scale = float(np.max(result.peak_to_peak[point][lateral]))
    try:
        return shoot_full_model(problem, q[free][keep], v[free][keep], 2.0 * np.pi / omega,
                                run["steps_per_period"], scale_q=scale,
                                scale_v=scale * omega)
    except ConvergenceError as exc:
        return str(exc)


def shooting_event(result: PeriodicResult, number: int, candidates: tuple[list[int], list[int]],
                   run: dict[str, Any], shots: dict[int, Shot]) -> EventCheck:
    """The verdict on event ``number`` from its sides' candidates (nearest first);
    ``shots`` caches the orbits by point.

    The nearest converged side on each side is taken first; while the pair shows no
    resolved crossing, the next converged point is added on one side and then the other
    (the exact event may lie a little away from harmonic balance's), and every new pair
    is tried, nearest first."""
    ev = result.bifurcations[number]
    found: tuple[list[SideCheck], list[SideCheck]] = ([], [])
    left = [list(points) for points in candidates]
    skipped: list[str] = []
    names = ("before", "after")

    def extend(k: int) -> bool:
        while left[k]:
            p = left[k].pop(0)
            if p not in shots:
                shots[p] = shoot_point(result, p, run)
            shot = shots[p]
            if isinstance(shot, str):
                skipped.append(f"{names[k]}: point {p} ({float(result.parameter[p]):.6g} "
                               f"rad/s) has no orbit of the full model next to it ({shot})")
                continue
            found[k].append(_side(result, p, shot, ev.kind, run["margin"]))
            return True
        return False

    extend(0)
    extend(1)
    turn = 0
    while found[0] and found[1]:
        pairs = sorted(((b, a) for b in found[0] for a in found[1]),
                       key=lambda pair: abs(pair[1].point - pair[0].point))
        for b, a in pairs:
            if not _problems(ev, b, a):
                return _verdict(ev, number, b, a, skipped)
        if not (extend(turn) or extend(1 - turn)):
            break
        turn = 1 - turn
    if not (found[0] and found[1]):
        k = 0 if not found[0] else 1
        missing = "no branch point" if not candidates[k] else "no converged orbit"
        return EventCheck(ev, number, found[0][0] if found[0] else None,
                          found[1][0] if found[1] else None, False,
                          "; ".join([f"{missing} on one side of the event", *skipped]))
    return _verdict(ev, number, found[0][0], found[1][0], skipped)


def _side(result: PeriodicResult, point: int, orbit: FullOrbit, kind: str, margin: float
          ) -> SideCheck:
    nan = float("nan")
    floquet = result.multipliers[point]
    ordered = floquet[np.argsort(-np.abs(floquet), kind="stable")]
    jf = kind_multiplier(ordered, kind)
    mode = complex(nan) if jf is None else complex(ordered[jf])
    j = kind_multiplier(orbit.multipliers, kind)
    measured = complex(nan) if j is None else complex(orbit.multipliers[j])
    error = nan if j is None else 0.5 * float(orbit.accuracy[j]) + 1e-9
    same = math.isfinite(abs(mode)) and math.isfinite(abs(measured)) and (
        (abs(mode) > 1.0) == (abs(measured) > 1.0))
    message = "" if same else (
        f"Floquet's multiplier of the event's kind {_show(mode)} and shooting's "
        f"{_show(measured)} lie on different sides of the unit circle")
    return SideCheck(point, float(result.parameter[point]), float(result.max_multiplier[point]),
                     int(np.sum(np.abs(floquet) > 1.0 + margin)), abs(measured), nan,
                     np.zeros(0), np.zeros(0), orbit.moved, nan, same, message, mode,
                     measured, None, error)


def _problems(ev: Any, before: SideCheck, after: SideCheck) -> list[str]:
    """Why the pair does not confirm the event (empty: it does)."""
    problems = []
    for name, side in (("before", before), ("after", after)):
        if not math.isfinite(abs(side.measured)):
            problems.append(f"{name}: the full model's orbit has no multiplier of the kind "
                            f"of a {ev.kind.replace('_', ' ')}")
        elif not abs(abs(side.measured) - 1.0) > side.accuracy:
            problems.append(f"{name}: its multiplier {_show(side.measured)} is within its "
                            f"error {side.accuracy:.2g} of the unit circle")
    if not problems and (abs(before.measured) > 1.0) == (abs(after.measured) > 1.0):
        where = "outside" if abs(before.measured) > 1.0 else "inside"
        problems.append(f"the full model's multiplier of its kind stays {where} the unit "
                        f"circle")
    return problems


def _verdict(ev: Any, number: int, before: SideCheck, after: SideCheck,
             skipped: list[str]) -> EventCheck:
    problems = _problems(ev, before, after)
    numbers = (f"shooting on the full model: {_show(before.measured)} -> "
               f"{_show(after.measured)} (+- {before.accuracy:.1g}, {after.accuracy:.1g}) at "
               f"{before.parameter:.6g} and {after.parameter:.6g} rad/s; harmonic balance's "
               f"Floquet {_show(before.mode)} -> {_show(after.mode)}")
    notes = [s.message for s in (before, after) if s.message] + skipped
    if problems:
        return EventCheck(ev, number, before, after, False,
                          "; ".join([*problems, numbers, *notes]))
    return EventCheck(ev, number, before, after, True, "; ".join([numbers, *notes]))


def _show(mu: complex) -> str:
    if not math.isfinite(abs(mu)):
        return "none"
    if abs(mu.imag) <= 1e-9 * max(abs(mu), 1e-300):
        return f"{mu.real:.5g}"
    return f"|{abs(mu):.5g}|"
