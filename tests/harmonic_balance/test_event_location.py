"""Cheap probes of event location (issue 16): a corrector that holds the parameter bit for
bit, and uncorrected Hermite estimates on a known branch."""

from __future__ import annotations

import math

import numpy as np

from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    ScaledSystem,
    correct,
)
from rotorsim.solvers.continuation_locate import Segment, SegmentPoint, _hermite, illinois
from rotorsim.solvers.stats import Stats


def circle(x, lam):
    """x^2 + lam^2 = 1: the unit circle, a smooth branch with known points."""
    return (np.array([x[0] ** 2 + lam**2 - 1.0]), np.array([[2.0 * x[0]]]),
            np.array([2.0 * lam]))


SYSTEM = ScaledSystem(circle, np.ones(1), np.ones(1), 1.0)


def _point(segment: Segment, angle: float) -> SegmentPoint:
    y = np.array([math.cos(angle), math.sin(angle)])
    p = segment.endpoint(y)
    assert p is not None
    return p


def test_a_held_parameter_stays_bit_for_bit():
    lam = 0.3 + 1e-13                        # not a round number: round-off would move it
    start = np.array([0.9, lam])
    e_lam = np.array([0.0, 1.0])
    corr = correct(SYSTEM, start, e_lam, lam, CorrectorOptions(tol=1e-14), Stats(),
                   hold_parameter=True)
    assert corr.converged and corr.y[-1] == lam
    assert abs(corr.y[0] - math.sqrt(1.0 - lam**2)) <= 1e-14


def test_estimates_lie_on_the_cubic_and_locate_the_zero_to_its_error():
    """Test function lam - 0.6 on the arc between angles 0.5 and 0.8: the zero is at
    lam = 0.6. An estimate (one evaluation, no Newton) lies O(w^4) off the circle: 6.3e-5
    at the middle of this w = 0.3 bracket. Illinois on estimates over the whole bracket
    finds the cubic's zero, off by that error (3.8e-5); with estimates only once the
    bracket is within 1 % of it, as the event locators do, the error falls by 1e8."""

    def test(y, ev, tan, border):
        return float(y[-1] - 0.6), None

    seg = Segment.between(SYSTEM, CorrectorOptions(tol=1e-13), np.array(
        [math.cos(0.5), math.sin(0.5)]), np.array([math.cos(0.8), math.sin(0.8)]), test)
    lo, hi = _point(seg, 0.5), _point(seg, 0.8)
    mid = seg.estimate(lo, hi, 0.5 * (lo.s + hi.s))
    assert mid is not None and not mid.corrected
    assert 1e-5 < abs(float(np.hypot(*mid.y)) - 1.0) < 1e-4      # 6.3e-5
    errors = []
    for width in (math.inf, 0.01 * (hi.s - lo.s)):
        a, b = illinois(seg, lo, hi, 1e-12, 60, estimate=width)
        best = seg.polished(a if abs(a.value) <= abs(b.value) else b)
        assert best.corrected and abs(float(np.hypot(*best.y)) - 1.0) <= 1e-12
        errors.append(abs(best.y[-1] - 0.6))
    assert 1e-5 < errors[0] < 1e-4                                 # 3.8e-5: the cubic's
    assert errors[1] < 1e-10                                       # round-off of the probes


def test_held_probes_land_at_their_start_parameter_and_folds_are_not_held():
    """A segment whose end tangents cross the parameter's hyperplanes alike (arc 0.5-0.8
    rad: ``t_lam`` 0.88 and 0.70) corrects its probes at the parameter of their Hermite
    start, bit for bit (one condensation per probe on a harmonic-balance residual), and
    locates the zero of ``lam - 0.6`` as the chord's probes do (to the round-off of the
    probes); an arc over the fold of ``lam`` at pi/2 is not held."""

    def test(y, ev, tan, border):
        return float(y[-1] - 0.6), None

    def arc(a, b):
        seg = Segment.between(SYSTEM, CorrectorOptions(tol=1e-13), np.array(
            [math.cos(a), math.sin(a)]), np.array([math.cos(b), math.sin(b)]), test)
        return seg, _point(seg, a), _point(seg, b)

    seg, lo, hi = arc(0.5, 0.8)
    held = seg.held(lo, hi)
    assert held.hold and not seg.hold
    probe = held.probe(lo, hi, 0.5 * (lo.s + hi.s))
    start = _hermite(lo, hi, 0.5 * (lo.s + hi.s))[0]
    assert probe is not None
    assert probe.y[-1] == start[-1]                          # held: the start's parameter
    assert abs(float(np.hypot(*probe.y)) - 1.0) <= 1e-13     # on the circle
    a, b = illinois(held, lo, hi, 1e-12, 60)
    assert abs(min((a, b), key=lambda p: abs(p.value)).y[-1] - 0.6) < 1e-12
    fold, lo, hi = arc(1.4, 1.7)                             # t_lam changes sign
    assert not fold.held(lo, hi).hold
