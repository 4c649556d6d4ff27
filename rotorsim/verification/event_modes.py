"""The two sides of an event measured along its critical Floquet mode
(``rs.verify_events(..., measure="floquet")``).

For an event whose sides show a Floquet crossing (:func:`~.periodic_events._sides`), the
side with more multipliers outside ``1 + margin`` is the unstable one; its mode of largest
``|mu|`` among those of the event's kind outside ``1 + margin`` is the critical mode (the
largest of all when none is of its kind: a fold inside a stretch made unstable by a period
doubling crosses +1 with a smaller real multiplier than the doubling's, which does not
change there), and the stable side follows the mode of the same shape
(:meth:`~.floquet_modes.BranchModes.follow`). Each side is measured by
:func:`~.mode_growth.mode_growth` and judged by :func:`~.mode_growth.side_verdict`; the event
also needs the unstable side's multiplier to be of its kind (real positive for a fold or a
branch point, real negative for a period doubling, a complex pair for Neimark-Sacker).
Without a crossing nothing is integrated: the sides are reported with their Floquet numbers
and the event is not confirmed.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorsim.errors import ConvergenceError
from rotorsim.results.event_verification import SideCheck
from rotorsim.results.periodic import PeriodicResult
from rotorsim.verification.floquet_modes import BranchModes, PointModes
from rotorsim.verification.mode_growth import kind_of, mode_growth, side_verdict
from rotorsim.verification.period_map import PeriodMap

KINDS = {"fold": "fold or branch point", "branch_point": "fold or branch point",
         "period_doubling": "period_doubling", "neimark_sacker": "neimark_sacker"}


def retried(measure: Any, result: PeriodicResult, point: int, run: dict[str, Any],
            periods_run: list[int], failures: list[str]) -> Any:
    """``measure(period_map)``, again with half the time step when Newton fails in a step
    (a contact that closes within a step); None and the error in ``failures`` when it
    fails twice."""
    for steps in (run["steps_per_period"], 2 * run["steps_per_period"]):
        pm = PeriodMap(run["system"], float(result.speed[point]),
                       2.0 * np.pi / float(result.fundamental[point]), run["excitation"],
                       float(result.options.get("shaft_angle", 0.0)), steps)
        try:
            return measure(pm)
        except ConvergenceError as exc:
            error = exc
        finally:
            periods_run.extend(pm.periods_run)
    failures.append(f"the transient failed at T/{2 * run['steps_per_period']}: {error}")
    return None


def mode_sides(result: PeriodicResult, modes: BranchModes,
               points: tuple[int | None, int | None], crossing: bool, column: int,
               run: dict[str, Any], measured: dict[tuple[int, int], SideCheck],
               periods_run: list[int], kind: str = ""
               ) -> tuple[SideCheck | None, SideCheck | None]:
    """The sides of one event of ``kind`` (module docstring); ``measured`` caches
    ``(point, mode)``."""
    before, after = points
    if before is None or after is None or not crossing:
        return (None if before is None else _unmeasured(result, before, run["margin"]),
                None if after is None else _unmeasured(result, after, run["margin"]))
    counts = [int(np.sum(np.abs(result.multipliers[p]) > 1.0 + run["margin"]))
              for p in (before, after)]
    found = {p: modes.at(p) for p in (before, after)}
    unstable = before if counts[0] > counts[1] else after
    stable = after if unstable == before else before
    j = critical_mode(found[unstable].multipliers, kind, run["margin"])
    chosen = {unstable: j, stable: modes.follow(found[unstable], j, found[stable])}
    out = []
    for p in (before, after):
        key = (p, chosen[p])
        if key not in measured:
            measured[key] = _measure(result, found[p], chosen[p], modes, column, run,
                                     periods_run)
        out.append(measured[key])
    return out[0], out[1]


def critical_mode(multipliers: np.ndarray, kind: str, margin: float) -> int:
    """Index of the critical mode among ``multipliers`` (by decreasing modulus) of the
    unstable side: the first outside ``1 + margin`` of the event's ``kind``, else 0."""
    wanted = KINDS.get(kind, kind)
    for j, mu in enumerate(multipliers):
        if abs(mu) <= 1.0 + margin:
            break
        if kind_of(complex(mu)) == wanted:
            return j
    return 0


def _unmeasured(result: PeriodicResult, point: int, margin: float) -> SideCheck:
    nan = float("nan")
    unstable = int(np.sum(np.abs(result.multipliers[point]) > 1.0 + margin))
    return SideCheck(point, float(result.parameter[point]), float(result.max_multiplier[point]),
                     unstable, nan, nan, np.zeros(0), np.zeros(0), nan, nan, False,
                     "not integrated: no Floquet crossing to follow")


def _measure(result: PeriodicResult, point: PointModes, j: int, modes: BranchModes,
             column: int, run: dict[str, Any], periods_run: list[int]) -> SideCheck:
    """Time integration along mode ``j`` at one branch point."""
    p = point.point
    q0, v0 = result.state(p, 0.0)
    ptp = result.peak_to_peak[p]
    lateral = float(np.max(ptp[np.isin(result.dofs % 6, (0, 1))]))
    size = run["perturbation"] * lateral
    failures: list[str] = []
    found = retried(lambda pm: mode_growth(pm, q0, v0, modes, point, j, size,
                                           run["periods"]),
                    result, p, run, periods_run, failures)
    nan, unstable = float("nan"), int(np.sum(np.abs(result.multipliers[p]) > 1.0 + run["margin"]))
    args = (p, float(result.parameter[p]), float(result.max_multiplier[p]), unstable, nan)
    if found is None:
        return SideCheck(*args, nan, np.zeros(0), np.zeros(0), nan, nan, False,
                         "; ".join(failures), complex(point.multipliers[j]))
    growth, qb = found
    deviation = np.abs(qb[:, column] - q0[column]) / float(
        ptp[np.searchsorted(result.dofs, column)])
    c = growth.coordinates
    message = side_verdict(growth, run["margin"])
    return SideCheck(*args, abs(growth.measured), np.zeros(0),
                     np.abs(c[1:]) / np.maximum(np.abs(c[:-1]), np.finfo(float).tiny),
                     float(deviation[1]), float(deviation.max()), not message, message,
                     growth.floquet, growth.measured, c)


def mode_problems(kind: str, before: SideCheck, after: SideCheck, margin: float
                  ) -> list[str]:
    """The event's kind against the unstable side's multiplier."""
    side = before if abs(before.mode) > abs(after.mode) else after
    if not (math.isfinite(abs(side.mode)) and abs(side.mode) > 1.0 + margin):
        return []
    found = kind_of(side.mode)
    if found == KINDS.get(kind, kind):
        return []
    return [f"a {kind.replace('_', ' ')} needs a multiplier crossing as a "
            f"{KINDS.get(kind, kind).replace('_', ' ')}, the unstable side's is a "
            f"{found.replace('_', ' ')} ({side.mode:.4g})"]


def mode_text(before: SideCheck, after: SideCheck) -> str:
    """The numbers of a confirmed event."""
    return (f"critical mode: Floquet {_size(before.mode)} -> {_size(after.mode)}, measured "
            f"{_size(before.measured)} -> {_size(after.measured)} along free transients "
            f"({before.parameter:.6g} and {after.parameter:.6g} rad/s)")


def _size(mu: complex) -> str:
    if abs(mu.imag) <= 1e-9 * max(abs(mu), 1e-300):
        return f"{mu.real:.4g}"
    return f"|{abs(mu):.4g}|"
