"""Only confirmed bifurcations: sign changes checked against a finer discretisation.

Every event of a branch starts as a *candidate*: a sign change of a test function between
two consecutive points ``i, j`` (the ``lam`` component of the tangent for folds, the sign of
the bordered determinant for branch points, the count of multipliers outside the unit
circle for period doublings and Neimark-Sacker points, :mod:`.events`). On a rotor whose
bearings open and close contacts, many such changes are artefacts of the discretisation:

* a sample of the AFT grid passes a contact onset between the two points, and the
  sampled Jacobian changes abruptly (its determinant, or a multiplier of a lightly damped
  mode sitting near the unit circle, changes sign in a thin transition or a jump);
* Hill's or Hsu's multipliers carry errors of their own (second order in the sampling;
  the truncation of a Craig-Bampton reduced Floquet model) that move a nearly neutral
  multiplier across ``|mu| = 1 + tol``.

Every candidate, folds included, is confirmed when it survives a finer discretisation (a
turning point of the branch that the finer grid does not turn is an aliasing artefact):
both bracket points are corrected again on an AFT grid with
:data:`~.refined.REFINE` times the samples (:class:`~.refined.SamplingCheck`: at their own
parameter where no fold is next to them, else on the hyperplane through each point normal
to its tangent, well posed at folds), with :data:`~.refined.REFINE` times the
fixed-interface modes when the Floquet model is reduced, and the same test must still
change in the same way between them (or between their outer neighbours ``i - 1``,
``j + 1``, when the finer grid moves the event across a bracket point).

A branch point must also be a crossing of +1 by a real multiplier (:mod:`.crossings`): on
the branch's own multipliers (checked first, it costs nothing), on the finer sampling, and
with :data:`MORE_HARMONICS` times the harmonics. When one edge of an unstable window fails,
so does the other. Confirmed candidates are then located; an event whose test function
jumps across zero (it does not fall to :data:`DIP` of its bracket values) or crosses it
:data:`STEEP` times more steeply than between its points is an artefact too, and so is the
other edge of its window.

Artefacts are never reported as bifurcations: ``result.unresolved`` lists them, merged per
kind over adjacent intervals, with the interval and the reason, so that nothing is
silently dropped.

References
----------
Y. A. Kuznetsov, Elements of Applied Bifurcation Theory, 3rd ed., Springer 2004, section
10.2 (test functions must have regular zeros); R. Seydel, Practical Bifurcation and
Stability Analysis, Springer 2010, section 5.4 (validating detected bifurcations).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.analyses.periodic.crossings import (
    KIND_INDEX,
    missing_crossing,
    window_partners,
)
from rotorsim.analyses.periodic.events import floquet_events, unstable_counts
from rotorsim.analyses.periodic.refined import HARMONIC_ITER, SamplingCheck
from rotorsim.analyses.periodic.stability import StabilityModel
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.bifurcation import (
    BifurcationEvent,
    BifurcationOptions,
    detect_bifurcations,
)
from rotorsim.harmonic_balance.residual import HBResidual, continuation_function
from rotorsim.solvers.continuation import Branch

DIP = 1e-2
"""A located event is a zero of its test function when ``|value|`` there is at most
``DIP`` times the smaller ``|value|`` at its bracket ends (a regular zero falls to the
location tolerance; a jump keeps its size)."""

STEEP = 100.0
"""A located zero whose slope exceeds ``STEEP`` times the mean slope between its bracket
points is a thin non-smooth transition (:func:`~rotorsim.solvers.continuation_locate.
steepness`), not a regular zero: a smooth test function over one continuation step varies
its slope by a small factor."""

MORE_HARMONICS = 1.5
"""A branch point must also survive ``ceil(MORE_HARMONICS H)`` harmonics (with the finer
sampling): its determinant counts the truncated Hill problem's exponents at 0, which the
truncation can create or remove where the orbit is poorly resolved (next to contact
onsets, :mod:`.crossings`)."""

RELATIVE_TOL = 1e-5
"""Events are located to this fraction of the step between their bracket points (tighter
brackets reach the corrector's own error in the probes' abscissae: probes then fall
outside the bracket and the event stayed "not located" at 1e-7 of its bracket)."""

@dataclass(frozen=True)
class Candidate:
    """A sign change of the test function of ``kind`` between branch points ``i < j``."""

    kind: str
    i: int
    j: int


@dataclass(frozen=True)
class Artefact:
    """A candidate that did not survive its check, and why."""

    kind: str
    i: int
    j: int
    lam: tuple[float, float]
    reason: str

    def record(self) -> dict[str, Any]:
        """Plain-data description for ``result.events``."""
        return {"kind": self.kind, "status": "unresolved", "between": list(self.lam),
                "points": [self.i, self.j], "reason": self.reason}


def candidates(branch: Branch, multipliers: np.ndarray | None,
               tol: float) -> list[Candidate]:
    """Sign changes of every test function between consecutive points (module docstring);
    ``multipliers`` (P, r) with NaN rows where Floquet failed, or None."""
    out = [Candidate("fold", i, j) for i, j in _changes(branch.tangents[:, -1])]
    out += [Candidate("branch_point", i, j)
            for i, j in _changes(branch.det_sign.astype(float))]
    if multipliers is not None and multipliers.size:
        valid = np.flatnonzero(np.all(np.isfinite(multipliers), axis=1))
        counts = np.array([unstable_counts(multipliers[i], tol) for i in valid]).reshape(-1, 2)
        for kind, c in KIND_INDEX.items():
            for a in np.flatnonzero(np.diff(counts[:, c]) != 0) if counts.size else ():
                out.append(Candidate(kind, int(valid[a]), int(valid[a + 1])))
    return sorted(out, key=lambda c: (c.i, c.kind))


def is_regular_zero(value: float, ends: tuple[float, float]) -> bool:
    """Whether a located test value is a zero rather than a jump (:data:`DIP`)."""
    size = min(abs(ends[0]), abs(ends[1]))
    return math.isfinite(value) and abs(value) <= DIP * size


def _irregular(event: BifurcationEvent) -> str:
    """Why a located event is not a regular zero of its test function ("" if it is).

    The multiplier test ``|mu|_k - (1 + tol)`` is floored at ``-tol`` by the neutral
    multipliers of undamped modes, so only its steepness is judged."""
    floquet = event.kind in KIND_INDEX
    if math.isinf(event.steepness) or not (
            floquet or is_regular_zero(event.value, event.test_values)):
        return "the test function jumps across zero (a non-smooth point, not a bifurcation)"
    if event.steepness > STEEP:
        return (f"the test function crosses zero {event.steepness:.3g} times more steeply "
                "than between the points (a contact onset crossed by an AFT sample, not a "
                "bifurcation)")
    return ""


def _changes(values: FloatArray) -> list[tuple[int, int]]:
    """Pairs of consecutive valid points (finite, nonzero) with opposite signs."""
    valid = np.flatnonzero(np.isfinite(values) & (values != 0.0))
    signs = np.sign(values[valid])
    change = np.flatnonzero(signs[1:] != signs[:-1])
    return [(int(valid[k]), int(valid[k + 1])) for k in change]


@dataclass(frozen=True)
class Review:
    """Located events that passed every check, and the artefacts (merged per kind into
    clusters of consecutive intervals)."""

    events: tuple[BifurcationEvent, ...]
    artefacts: tuple[Artefact, ...]
    stats: dict[str, float]


def confirmed_events(residual: HBResidual, branch: Branch, model: StabilityModel | None,
                     multipliers: np.ndarray) -> Review:
    """Candidates of ``branch`` checked on the fine grid, the survivors located, and the
    located ones kept when they are regular zeros (module docstring)."""
    fun = continuation_function(residual, "omega")
    floquet = multipliers if model is not None and multipliers.size else None
    tol = model.tol if model is not None else 0.0
    found = candidates(branch, floquet, tol)
    own, checks = _checked(residual, branch, model, floquet, found)

    def windows() -> dict[Any, str]:   # from each edge's own verdict: no chains
        return {} if floquet is None else window_partners(found, own, floquet, tol)

    window = windows()
    keep = {(c.kind, c.i, c.j) for c in found if not (own[c] or window.get(c))}
    events = list(detect_bifurcations(fun, branch, options=BifurcationOptions(
        kinds=("fold", "branch_point"), relative_tol=RELATIVE_TOL, screen_jumps=True),
        pairs=keep)) \
        if keep else []
    if model is not None and keep:
        events += floquet_events(fun, branch, model, multipliers, pairs=keep,
                                 relative_tol=RELATIVE_TOL)
    located = {}
    for e in events:
        c = Candidate(e.kind, e.index, e.next_index)
        located[c] = e
        own[c] = "" if e.kind == "fold" else _irregular(e)
    window = windows()       # a window whose edge turned out irregular is not resolved
    reasons = {c: own[c] or window.get(c, "") for c in own}
    artefacts = [_artefact(branch, c, r) for c, r in reasons.items() if r]
    regular = [e for c, e in located.items() if not reasons[c]]
    stats = {"candidates": float(len(found)), "confirmed": float(len(regular)),
             "confirmation_evaluations": float(sum(
                 k.stats.residual_evaluations for k in checks.values()))}
    return Review(tuple(sorted(regular, key=lambda e: (e.index, float(e.lam)))),
                  merged(artefacts), stats)


def _checked(residual: HBResidual, branch: Branch, model: StabilityModel | None,
             floquet: np.ndarray | None, found: list[Candidate]
             ) -> tuple[dict[Any, str], dict[str, SamplingCheck]]:
    """Each candidate's own verdict ("" or the reason) and the checks used: a branch point
    on the branch's multipliers first (free), then with more harmonics and samples; the
    other kinds with more samples."""
    checks = {"sampling": SamplingCheck(residual, branch, model)}
    tol = model.tol if model is not None else 0.0
    own: dict[Any, str] = {}
    for c in found:
        if c.kind != "branch_point":
            own[c] = checks["sampling"].confirms(c, floquet)
            continue
        own[c] = "" if floquet is None else missing_crossing(c, floquet, tol)
        if not own[c]:
            if "harmonics" not in checks:
                checks["harmonics"] = _harmonic_check(residual, branch, model, checks)
            own[c] = checks["harmonics"].confirms(c, floquet)
    return own, checks


def _harmonic_check(residual: HBResidual, branch: Branch, model: StabilityModel | None,
                    checks: dict[str, SamplingCheck]) -> SamplingCheck:
    """The finer discretisation with more harmonics, or the sampling check alone where
    the larger problem cannot be built (Hill's pencil beyond the memory limit)."""
    try:
        return SamplingCheck(residual, branch, model, harmonics=math.ceil(
            MORE_HARMONICS * residual.harmonics), max_iter=HARMONIC_ITER)
    except ModelError:
        return checks["sampling"]


def merged(artefacts: list[Artefact]) -> tuple[Artefact, ...]:
    """Artefacts of one kind on overlapping or adjacent intervals joined into one."""
    out: list[Artefact] = []
    for a in sorted(artefacts, key=lambda a: (a.kind, a.i)):
        last = out[-1] if out else None
        if last is not None and last.kind == a.kind and a.i <= last.j:
            count = _count(last.reason) + 1
            out[-1] = Artefact(a.kind, last.i, max(last.j, a.j),
                               (min(last.lam[0], a.lam[0]), max(last.lam[1], a.lam[1])),
                               f"{count} sign changes; {_why(last.reason)}")
        else:
            out.append(a)
    return tuple(sorted(out, key=lambda a: a.i))


def _count(reason: str) -> int:
    head = reason.split(" sign changes; ", 1)
    return int(head[0]) if len(head) == 2 and head[0].isdigit() else 1


def _why(reason: str) -> str:
    return reason.split(" sign changes; ", 1)[-1]


def _artefact(branch: Branch, c: Candidate, reason: str) -> Artefact:
    lam = (float(branch.lam[c.i]), float(branch.lam[c.j]))
    return Artefact(c.kind, c.i, c.j, (min(lam), max(lam)), reason)
