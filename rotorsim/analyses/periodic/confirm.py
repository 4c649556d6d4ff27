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
both bracket points are corrected again on an AFT grid with :data:`REFINE` times the
samples (at their own parameter where no fold is next to them, else on the hyperplane
through each point normal to its tangent, well posed at folds), with :data:`REFINE`
times the fixed-interface modes when the Floquet model is reduced, and the same test
must still change in the same way between them (or between their outer neighbours
``i - 1``, ``j + 1``, when the finer grid moves the event across a bracket point). When one
edge of an unstable window fails, so does the other. Confirmed candidates are then
located; an event whose test function jumps across zero (it does not fall to :data:`DIP`
of its bracket values) or crosses it :data:`STEEP` times more steeply than between its
points is an artefact too.

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

import itertools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rotorsim.analyses.periodic.events import floquet_events, unstable_counts
from rotorsim.analyses.periodic.stability import StabilityModel, stability_model
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.bifurcation import (
    BifurcationEvent,
    BifurcationOptions,
    detect_bifurcations,
)
from rotorsim.harmonic_balance.residual import HBResidual, continuation_function
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    ScaledSystem,
    Tangent,
    correct,
    tangent,
)
from rotorsim.solvers.stats import Stats

REFINE = 2
"""Sampling factor of the confirmation grid (``N -> REFINE N``)."""

DIP = 1e-2
"""A located event is a zero of its test function when ``|value|`` there is at most
``DIP`` times the smaller ``|value|`` at its bracket ends (a regular zero falls to the
location tolerance; a jump keeps its size)."""

STEEP = 100.0
"""A located zero whose slope exceeds ``STEEP`` times the mean slope between its bracket
points is a thin non-smooth transition (:func:`~rotorsim.solvers.continuation_locate.
steepness`), not a regular zero: a smooth test function over one continuation step varies
its slope by a small factor."""

RELATIVE_TOL = 1e-5
"""Events are located to this fraction of the step between their bracket points (tighter
brackets reach the corrector's own error in the probes' abscissae: probes then fall
outside the bracket and the event stayed "not located" at 1e-7 of its bracket)."""

HOLD_SLOPE = 0.5
"""A branch point is corrected on the finer grid at its own parameter (every Newton
iteration at one ``omega``: one condensation) when the parameter component of its tangent
is at least this fraction of the largest one of its neighbours (no fold next to it, where
``dR/dx`` is singular); otherwise, or if that fails, on its tangent's normal hyperplane."""

MAX_ITER = 6
"""Newton iterations of a fine-grid correction (from a converged coarse point)."""

KIND_INDEX = {"period_doubling": 0, "neimark_sacker": 1}


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


@dataclass
class _FinePoint:
    """A branch point corrected on the fine grid: tangent, and multiplier counts (computed
    when a period-doubling or Neimark-Sacker candidate first asks)."""

    tangent: Tangent | None
    x: FloatArray
    lam: float
    model: StabilityModel | None
    _counts: tuple[tuple[int, int] | None] | None = None

    @property
    def counts(self) -> tuple[int, int] | None:
        if self._counts is None:
            self._counts = (self._floquet(),)
        return self._counts[0]

    def _floquet(self) -> tuple[int, int] | None:
        if self.model is None:
            return None
        try:
            mu = self.model.floquet(self.x, self.lam).multipliers
        except (ModelError, ConvergenceError, np.linalg.LinAlgError):
            return None
        return unstable_counts(mu, self.model.tol)


@dataclass
class SamplingCheck:
    """Re-evaluates branch points on a grid of ``REFINE`` times the samples.

    Parameters
    ----------
    residual : HBResidual
        The residual the branch was traced with.
    branch : Branch
    model : StabilityModel, optional
        The branch's Floquet model; its method and reduction are kept on the fine grid.
    """

    residual: HBResidual
    branch: Branch
    model: StabilityModel | None
    stats: Stats = field(default_factory=Stats)
    _points: dict[int, _FinePoint | None] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.fine = self.residual.with_discretization(
            samples=REFINE * self.residual.samples)
        b = self.branch
        self.system = ScaledSystem(continuation_function(self.fine, "omega", terms=True),
                                   b.x_scale, b.r_scale, b.lam_scale)
        self.corrector = CorrectorOptions(b.options.tol, min(MAX_ITER, b.options.max_iter),
                                          b.options.max_backtracks,
                                          stall_tol=b.options.stall_tol)
        self.fine_model = None
        if self.model is not None:
            m = self.model
            if m.residual is m.main or m.modes < 0:
                self.fine_model = StabilityModel(self.fine, self.fine, m.method, m.modes, m.tol)
            else:  # a reduced Floquet model: twice the fixed-interface modes as well
                self.fine_model = stability_model(
                    self.fine, m.method, modes=REFINE * m.modes, tol=m.tol,
                    omega_max=float(np.max(self.branch.lam)))

    def confirms(self, candidate: Candidate, coarse: np.ndarray | None) -> str:
        """"" when ``candidate`` survives the fine grid, else the reason it does not
        (``coarse``: the branch's multipliers (P, r), for the direction of a count
        change). A fold must turn the finer branch too (the parameter component of the
        finer tangent changes sign). The fine grid may move an event across a bracket
        point: the change is also sought between the neighbours ``i - 1`` and ``j + 1``."""
        last = len(self.branch) - 1
        reason = ""
        for i, j in ((candidate.i, candidate.j),
                     (max(candidate.i - 1, 0), min(candidate.j + 1, last))):
            reason = self._changes(candidate, i, j, coarse)
            if not reason:
                return ""
        return reason

    def _changes(self, candidate: Candidate, i: int, j: int,
                 coarse: np.ndarray | None) -> str:
        """"" when the fine test changes between points ``i`` and ``j`` as the coarse
        one does across ``candidate``."""
        lo, hi = self._point(i), self._point(j)
        if lo is None or hi is None:
            return "a bracket point does not converge on the finer sampling"
        if candidate.kind in ("branch_point", "fold"):
            if lo.tangent is None or hi.tangent is None:
                return "no tangent on the finer sampling"
            if candidate.kind == "fold":   # the finer branch turns between them too
                changed = lo.tangent.t[-1] * hi.tangent.t[-1] < 0
            else:
                changed = lo.tangent.det_sign * hi.tangent.det_sign < 0
        else:
            if lo.counts is None or hi.counts is None or coarse is None \
                    or self.model is None:
                return "no multipliers on the finer sampling"
            c = KIND_INDEX[candidate.kind]
            step = (unstable_counts(coarse[candidate.j], self.model.tol)[c]
                    - unstable_counts(coarse[candidate.i], self.model.tol)[c])
            changed = (hi.counts[c] - lo.counts[c]) * step > 0
        if changed:
            return ""
        return f"the sign change disappears with {REFINE} times the samples"

    def _point(self, i: int) -> _FinePoint | None:
        if i not in self._points:
            self._points[i] = self._correct(i)
        return self._points[i]

    def _correct(self, i: int) -> _FinePoint | None:
        b = self.branch
        y0 = self.system.to_y(b.x[i], float(b.lam[i]))
        border = b.tangents[i]
        corr = None
        if abs(border[-1]) >= HOLD_SLOPE * _steepest(b.tangents, i):
            # at the point's own parameter: one condensation for the whole correction
            e_lam = np.zeros(y0.size)
            e_lam[-1] = 1.0
            corr = correct(self.system, y0, e_lam, float(y0[-1]), self.corrector,
                           self.stats, hold_parameter=True)
        if corr is None or not corr.converged or corr.evaluation is None:
            # on the hyperplane through the point normal to its tangent: well posed at folds
            corr = correct(self.system, y0, border, float(border @ y0), self.corrector,
                           self.stats)
        if not corr.converged or corr.evaluation is None:
            return None
        tan = tangent(corr.evaluation, b.tangents[i], self.stats)
        x, lam = self.system.from_y(corr.y)
        return _FinePoint(tan, x, lam, self.fine_model)


def _steepest(tangents: FloatArray, i: int) -> float:
    """Largest ``|t_lam|`` among point ``i`` and its neighbours."""
    return float(np.max(np.abs(tangents[max(i - 1, 0): i + 2, -1])))


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
    found = candidates(branch, floquet, model.tol if model is not None else 0.0)
    check = SamplingCheck(residual, branch, model)
    reasons = {c: check.confirms(c, floquet) for c in found}
    if floquet is not None:
        reasons.update(_windows(found, reasons, floquet, model.tol))  # type: ignore[union-attr]
    artefacts = [_artefact(branch, c, r) for c, r in reasons.items() if r]
    keep = {(c.kind, c.i, c.j) for c, r in reasons.items() if not r}
    events = list(detect_bifurcations(fun, branch, options=BifurcationOptions(
        kinds=("fold", "branch_point"), relative_tol=RELATIVE_TOL, screen_jumps=True),
        pairs=keep)) \
        if keep else []
    if model is not None and keep:
        events += floquet_events(fun, branch, model, multipliers, pairs=keep,
                                 relative_tol=RELATIVE_TOL)
    regular = []
    for e in events:
        reason = "" if e.kind == "fold" else _irregular(e)
        if reason:
            artefacts.append(_artefact(branch, Candidate(e.kind, e.index, e.next_index),
                                       reason))
        else:
            regular.append(e)
    stats = {"candidates": float(len(found)), "confirmed": float(len(regular)),
             "confirmation_evaluations": float(check.stats.residual_evaluations)}
    return Review(tuple(sorted(regular, key=lambda e: (e.index, float(e.lam)))),
                  merged(artefacts), stats)


def _windows(found: list[Candidate], reasons: dict[Candidate, str], coarse: np.ndarray,
             tol: float) -> dict[Candidate, str]:
    """A multiplier leaving the unit circle and coming back bounds an unstable window:
    when one edge of a window is an artefact, the other edge is unresolved too."""
    out: dict[Candidate, str] = {}
    for kind, c in KIND_INDEX.items():
        edges = [f for f in found if f.kind == kind]
        for a, b in itertools.pairwise(edges):
            up = (unstable_counts(coarse[a.j], tol)[c] - unstable_counts(coarse[a.i], tol)[c])
            down = (unstable_counts(coarse[b.j], tol)[c] - unstable_counts(coarse[b.i], tol)[c])
            if up * down >= 0 or bool(reasons[a]) == bool(reasons[b]):
                continue
            lone = b if reasons[a] else a
            out[lone] = "the other edge of its unstable window did not survive the check"
    return out


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
