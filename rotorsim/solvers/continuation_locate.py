"""Locate a sign change of a test function between two points of a continued branch.

Between branch points ``y_0`` and ``y_1`` (scaled unknowns) a point at abscissa ``s`` along
the chord ``u = (y_1 - y_0) / |y_1 - y_0|`` is found by re-correcting the cubic Hermite
interpolant of the two points and their tangents on the hyperplane orthogonal to the chord
of the *current* bracket. The Illinois (modified regula falsi) iteration shrinks the bracket
around the sign change. Two safeguards keep the probes on the traced branch near a branch
point, where a second branch crosses the hyperplane: the Hermite start is O(h^4) close to
the branch, and a probe whose tangent leaves the cone of the bracket's end tangents (plus
``CONE_SLACK``) is refused and replaced by bisection. Where no fold is in or next to the
bracket (:data:`HOLD_RATIO`, :meth:`Segment.held`) a probe may instead be corrected at the
parameter of its start, which a residual with work cached per parameter value (the
condensation of harmonic balance) evaluates once per probe instead of once per iteration.

References
----------
M. Dowell, P. Jarratt, BIT 11 (1971) 168-174 (the Illinois method). E. L. Allgower,
K. Georg, Introduction to Numerical Continuation Methods, SIAM 2003, section 8.1.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from rotorsim.errors import ConvergenceError
from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    Evaluation,
    FloatArray,
    ScaledSystem,
    Tangent,
    correct,
    tangent,
)
from rotorsim.solvers.stats import Stats

TestFunction = Callable[[FloatArray, Evaluation, Tangent, FloatArray], "tuple[float, Any]"]
"""``test(y, evaluation, tangent, border) -> (value, data)`` at a corrected point."""

DRIFT = 0.1
"""Largest move of a probe's corrector from its Hermite start, relative to the bracket
chord, under the "drift" guard of :meth:`Segment.probe`."""

CONE_SLACK = 0.05
"""Extra angle [rad] allowed between a probe's tangent and the bracket chord beyond twice
the end tangents' own angles to it."""

HOLD_RATIO = 0.5
"""A probe of a segment with ``hold`` is corrected at the parameter of its start (one
evaluation of the parameter-dependent work per probe, e.g. the condensation of a
harmonic-balance residual with one LU per harmonic, instead of one per Newton iteration)
when the parameter components of the bracket's end tangents have one sign and the smaller
is at least this fraction of the larger: the branch crosses the parameter's hyperplanes
at a similar angle all along the bracket, with no fold in or next to it. Otherwise, or if
that correction fails, the probe is corrected on the chord's normal hyperplane."""


@dataclass(frozen=True, eq=False)
class SegmentPoint:
    """A corrected point: abscissa ``s`` on the segment chord, scaled ``y``, unit tangent
    ``t`` oriented along the segment, test ``value`` and the test's extra ``data``."""

    s: float
    y: FloatArray
    t: FloatArray
    value: float
    data: Any = None
    corrected: bool = True


@dataclass(frozen=True, eq=False)
class Segment:
    """The branch between two of its points, with a test function to evaluate on it."""

    system: ScaledSystem
    corrector: CorrectorOptions
    origin: FloatArray
    direction: FloatArray
    test: TestFunction
    guard: str = "cone"
    hold: bool = False
    _polished: dict[int, SegmentPoint] = field(default_factory=dict, repr=False)

    @classmethod
    def between(cls, system: ScaledSystem, corrector: CorrectorOptions, y0: FloatArray,
                y1: FloatArray, test: TestFunction, guard: str = "cone") -> Segment:
        """Segment from ``y0`` to ``y1`` (scaled); ``guard`` is the probes' safeguard
        ("cone" or "drift", see :meth:`probe`)."""
        chord = y1 - y0
        return cls(system, corrector, y0, chord / np.linalg.norm(chord), test, guard)

    def held(self, lo: SegmentPoint, hi: SegmentPoint) -> Segment:
        """This segment with its probes and polished points corrected at the parameter
        of their start (``hold``) when its corrected ends ``lo`` and ``hi`` show no fold
        in between (:data:`HOLD_RATIO`); else this segment."""
        a, b = float(lo.t[-1]), float(hi.t[-1])
        if a * b > 0.0 and min(abs(a), abs(b)) >= HOLD_RATIO * max(abs(a), abs(b)):
            return replace(self, hold=True, _polished={})
        return self

    def endpoint(self, y: FloatArray) -> SegmentPoint | None:
        """Re-correct a branch point (its chord hyperplane) and evaluate the test there."""
        return self._corrected(y, self.direction, None)

    def probe(self, lo: SegmentPoint, hi: SegmentPoint, s: float) -> SegmentPoint | None:
        """Point near abscissa ``s`` in ``(lo.s, hi.s)``; None if it cannot be corrected
        or leaves the bracket, or fails the guard: its tangent leaves the cone of the
        bracket ("cone"), or the corrector moved it farther than :data:`DRIFT` times the
        bracket from the Hermite start ("drift": at a branch point the traced branch's
        tangent is ill-determined, the bordered Jacobian being nearly singular, while the
        start stays O(h^4) close to the branch)."""
        start, v, length = _hermite(lo, hi, s)
        cone = 2.0 * max(_angle(lo.t, v), _angle(hi.t, v)) + CONE_SLACK
        guard = cone if self.guard == "cone" else None
        point = self._corrected(start, v, guard, hold=True) if self.hold else None
        if point is None:   # not held, or not converged at the start's parameter
            point = self._corrected(start, v, guard)
        if point is None or not lo.s < point.s < hi.s:
            return None
        if self.guard == "drift" and np.linalg.norm(point.y - start) > DRIFT * length:
            return None
        return point

    def estimate(self, lo: SegmentPoint, hi: SegmentPoint, s: float) -> SegmentPoint | None:
        """The cubic Hermite interpolant of the corrected points ``lo`` and ``hi`` at
        abscissa ``s``, *not* corrected: one evaluation and one factorisation for the
        tangent and the test. Between corrected points ``w`` apart it lies ``O(w^4)`` from
        the branch where the branch is smooth, so on a bracket already narrowed to
        :data:`ESTIMATE_WIDTH` of the segment its test value is that of the branch to far
        below the location tolerance, and free of the corrector's noise at a nearly
        singular Jacobian (a contact kink between them is caught by :func:`illinois`).
        None if the evaluation fails."""
        target = s
        for _ in range(3):  # the interpolant's abscissa, on the segment's chord, at s
            start, v, _ = _hermite(lo, hi, s)
            s += target - float(self.direction @ (start - self.origin))
        stats = Stats()
        try:
            ev = self.system.evaluate(start, stats)
        except ConvergenceError:
            return None
        tan = tangent(ev, v, stats)
        if tan is None:
            return None
        value, data = self.test(start, ev, tan, v)
        return SegmentPoint(float(self.direction @ (start - self.origin)), start, tan.t,
                            value, data, corrected=False)

    def polished(self, point: SegmentPoint) -> SegmentPoint:
        """``point`` corrected onto the branch (at its parameter with ``hold``, else or if
        that fails on the chord hyperplane) if it is an estimate; the estimate itself if
        the correction fails."""
        if point.corrected:
            return point
        if id(point) not in self._polished:
            corrected = None
            if self.hold:
                corrected = self._corrected(point.y, self.direction, None, hold=True)
            if corrected is None:
                corrected = self._corrected(point.y, self.direction, None)
            self._polished[id(point)] = corrected if corrected is not None else point
        return self._polished[id(point)]

    def _corrected(self, start: FloatArray, border: FloatArray,
                   cone: float | None, hold: bool = False) -> SegmentPoint | None:
        """``start`` corrected on the hyperplane normal to ``border`` through it (or at its
        parameter, ``hold``), its tangent oriented along ``border`` and the test there."""
        stats = Stats()
        if hold:
            e_lam = np.zeros(start.size)
            e_lam[-1] = 1.0
            corr = correct(self.system, start, e_lam, float(start[-1]), self.corrector,
                           stats, hold_parameter=True)
        else:
            corr = correct(self.system, start, border, float(border @ start),
                           self.corrector, stats)
        if not corr.converged or corr.evaluation is None:
            return None
        tan = tangent(corr.evaluation, border, stats)
        if tan is None or (cone is not None and _angle(tan.t, border) > cone):
            return None
        value, data = self.test(corr.y, corr.evaluation, tan, border)
        s = float(self.direction @ (corr.y - self.origin))
        return SegmentPoint(s, corr.y, tan.t, value, data)


Anchors = tuple[SegmentPoint, SegmentPoint]
"""The last two corrected bracket ends: the cubic on which estimates are taken."""


def illinois(segment: Segment, lo: SegmentPoint, hi: SegmentPoint, tol: float,
             max_iter: int, estimate: float = 0.0, scale: float | None = None
             ) -> tuple[SegmentPoint, SegmentPoint]:
    """Shrink the bracket ``[lo, hi]`` (opposite test signs) to width ``tol`` in ``s``.

    Returns the final bracket (equal points if the test vanished exactly). A refused probe
    is replaced by the bisection point; if that fails too the iteration stops early. Once
    the bracket is at most ``estimate`` wide, the probes are uncorrected points of the cubic
    Hermite interpolant of the last two corrected bracket ends (:meth:`Segment.estimate`);
    pass the final points through :meth:`Segment.polished`. An estimated zero where the
    corrected test function is not small against ``scale`` (default: the smaller bracket
    value at entry; :data:`CONSISTENT`) is a zero of the cubic only, and the iteration
    restarts from the anchors with corrected probes.
    """
    return _illinois(segment, lo, hi, tol, max_iter, estimate, scale, None)[:2]


def _illinois(segment: Segment, lo: SegmentPoint, hi: SegmentPoint, tol: float,
              max_iter: int, estimate: float, scale: float | None,
              anchors: Anchors | None) -> tuple[SegmentPoint, SegmentPoint, Anchors | None]:
    """:func:`illinois`, continued from the ``anchors`` of an earlier call (an estimated
    bracket end has no tangent of the branch to interpolate from), and returning them."""
    scale = min(abs(lo.value), abs(hi.value)) if scale is None else scale
    f_lo, f_hi = lo.value, hi.value
    side = 0
    if lo.corrected and hi.corrected:
        anchors = (lo, hi)
    used = 0
    while used < max_iter:
        used += 1
        if hi.s - lo.s <= tol:
            break
        s = hi.s - f_hi * (hi.s - lo.s) / (f_hi - f_lo)
        mid = 0.5 * (lo.s + hi.s)
        s = s if lo.s < s < hi.s else mid
        new = None
        if lo.corrected and hi.corrected:
            anchors = (lo, hi)
        if hi.s - lo.s <= estimate and anchors is not None:
            # on the one cubic between the last corrected ends: the tangents of estimates
            # are those of points off the branch, meaningless next to a branch point
            new = segment.estimate(*anchors, s)
            new = new if new is not None and lo.s < new.s < hi.s else None
        new = new if new is not None else segment.probe(lo, hi, s)
        new = new if new is not None else segment.probe(lo, hi, mid)
        if new is None:
            break
        if new.value == 0.0:
            return new, new, anchors
        if (new.value > 0.0) == (hi.value > 0.0):
            hi, f_hi = new, new.value
            f_lo = 0.5 * f_lo if side == -1 else f_lo
            side = -1
        else:
            lo, f_lo = new, new.value
            f_hi = 0.5 * f_hi if side == 1 else f_hi
            side = 1
    if anchors is not None and not (lo.corrected and hi.corrected) \
            and not _consistent(segment, lo, hi, scale):
        # a zero of the interpolated test function the branch does not have (a contact
        # kink between the anchors): corrected probes from the anchors instead
        return _illinois(segment, *anchors, tol, max_iter - used, 0.0, None, None)
    return lo, hi, anchors


CONSISTENT = 0.1
"""An estimated zero (:func:`illinois`) is accepted when the test function at the point
corrected from it is at most this fraction of the smaller bracket value at entry. On the
clearance rotor of issue 16 it was 1e-4 to 6e-3 of it where the cubic follows the branch
(the corrector's noise next to a branch point), and 0.81 where a contact kink between the
anchors put a zero on the cubic only."""


def _consistent(segment: Segment, lo: SegmentPoint, hi: SegmentPoint,
                scale: float) -> bool:
    best = segment.polished(lo if abs(lo.value) <= abs(hi.value) else hi)
    return abs(best.value) <= CONSISTENT * scale


SCREEN_ITERATIONS = 6
"""Illinois iterations before a bracket is judged a zero or a jump (:func:`screened`)."""
JUMP_RATIO = 0.1
"""After the screening iterations a regular zero has shrunk ``|test|`` below this fraction
of the smaller bracket value (Illinois converges superlinearly on it); a jump has not."""


def screened(segment: Segment, lo: SegmentPoint, hi: SegmentPoint, tol: float,
             max_iter: int, estimate: float = 0.0
             ) -> tuple[SegmentPoint, SegmentPoint, bool]:
    """:func:`illinois` (``estimate`` passed on), stopped early on a jump:
    ``(lo, hi, regular)``.

    A test function that changes sign by jumping (a non-smooth point of a sampled
    contact law, not a bifurcation) would use up ``max_iter`` probes; after
    :data:`SCREEN_ITERATIONS` the bracket values tell a regular zero (``|test|`` fallen
    below :data:`JUMP_RATIO` of the ends) from a jump, which is returned unlocated.
    """
    size = min(abs(lo.value), abs(hi.value))
    lo, hi, anchors = _illinois(segment, lo, hi, tol, min(SCREEN_ITERATIONS, max_iter),
                                estimate, size, None)
    if hi.s - lo.s <= tol or lo is hi:
        return lo, hi, True
    if min(abs(lo.value), abs(hi.value)) > JUMP_RATIO * size:
        return lo, hi, False
    lo, hi, _ = _illinois(segment, lo, hi, tol, max(max_iter - SCREEN_ITERATIONS, 0),
                          estimate, size, anchors)
    return lo, hi, True


STEEP_FLOOR = 1e-4
"""Narrowest bracket, relative to the first, over which :func:`steepness` takes a slope:
the abscissae of corrected probes carry the corrector's error, so slopes over brackets
narrower than this are noise (a regular zero located to 1e-7 of its bracket showed
"slopes" 80 times its mean); a jump still shows ``1 / STEEP_FLOOR`` times the mean."""


def steepness(lo: SegmentPoint, hi: SegmentPoint, ends: tuple[float, float],
              length: float) -> float:
    """Slope of the test function across the final bracket ``[lo, hi]`` over its mean
    slope across the first bracket (``ends`` over chord ``length``): about 1 at a regular
    zero, the ratio of the bracket to the width of a thin transition (a contact onset
    crossed by one AFT sample) there."""
    width = max(hi.s - lo.s, STEEP_FLOOR * length)
    mean = abs(ends[1] - ends[0]) / length if length > 0 else math.inf
    if width <= 0.0 or not mean > 0.0:
        return 1.0
    return abs(hi.value - lo.value) / width / mean


ESTIMATE_WIDTH = 1e-2
"""Bracket width, relative to the segment's chord, below which :func:`illinois` probes
with uncorrected Hermite points (:meth:`Segment.estimate`): their distance to the branch,
``O(w^4)`` in the width ``w`` of a bracket between corrected points, is then about 1e-8 of
the chord's curvature term, far below the 1e-5 location tolerance of events."""


def _hermite(lo: SegmentPoint, hi: SegmentPoint, s: float
             ) -> tuple[FloatArray, FloatArray, float]:
    """Cubic Hermite interpolant of ``lo`` and ``hi`` (values, tangents) at abscissa
    ``s``, the unit chord and its length."""
    chord = hi.y - lo.y
    length = float(np.linalg.norm(chord))
    v = chord / length
    sigma = (s - lo.s) / (hi.s - lo.s)
    s2, s3 = sigma * sigma, sigma * sigma * sigma
    start = ((2 * s3 - 3 * s2 + 1) * lo.y + (s3 - 2 * s2 + sigma) * length * lo.t
             + (3 * s2 - 2 * s3) * hi.y + (s3 - s2) * length * hi.t)
    return start, v, length


def _angle(a: FloatArray, b: FloatArray) -> float:
    """Angle between unit vectors [rad]."""
    return 2.0 * math.asin(min(1.0, 0.5 * float(np.linalg.norm(a - b))))
