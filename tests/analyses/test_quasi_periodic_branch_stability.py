"""``branch_stability``: the stability box of a branch's tori grown where it matters
(``rotorsim/analyses/quasiperiodic/branch_stability.py``).

Every rule is tested on stand-in tori whose first-box and full-check results are set by
hand, so that each rule can be seen to send exactly its tori to the full check (and a
broken rule fails its test). The real branches of ``test_quasi_periodic_rotor.py`` and
``test_quasi_periodic_beyond.py`` run through it as well: their stability changes are
found on checked tori. The default model's 190 tori against a full check at every torus
are in docs/benchmarks.md (``benchmarks/bench_quasi_branch.py --compare``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pytest

from rotorsim.analyses.quasiperiodic.branch_stability import (
    CHECK_EVERY,
    FIRST_BOX,
    MARGIN,
    branch_stability,
)
from rotorsim.analyses.quasiperiodic.stability import TorusStability
from rotorsim.harmonic_balance.quasi.hill import TorusExponents

TOL = 1e-6


def _result(largest: float, boxes: tuple[tuple[int, int], ...], values: tuple[float, ...],
            converged: bool = True) -> TorusStability:
    ex = TorusExponents(np.array([largest + 10j, largest - 1.0]), boxes[-1],
                        np.array([0.01, 0.02]))
    return TorusStability(ex, converged, np.array(values), boxes, 4, TOL)


@dataclass
class StandIn:
    """A torus whose first box gives ``first`` and whose full check gives ``full`` after
    ``boxes`` boxes; it records which it was asked for."""

    first: float
    full: float | None = None
    boxes: int = 2
    calls: list[str] = field(default_factory=list)

    def exponents(self, box: tuple[int, int] | None = None,
                  first: TorusStability | None = None) -> TorusStability:
        if box is not None:
            assert box == FIRST_BOX and first is None
            self.calls.append("first")
            return _result(self.first, (FIRST_BOX,), (self.first,))
        assert first is not None and first.boxes == (FIRST_BOX,)
        self.calls.append("full")
        full = self.first if self.full is None else self.full
        tried = ((1, 1), (1, 2), (2, 2))[:self.boxes]
        values = (self.first,) + (full,) * (self.boxes - 1)
        return _result(full, tried, values)


def _checked(points: list[StandIn]) -> list[int]:
    return [i for i, p in enumerate(points) if "full" in p.calls]


def test_smooth_stable_tori_are_checked_on_the_schedule_only() -> None:
    points = [StandIn(-0.12 - 1e-5 * i, -0.12 - 1e-5 * i - 1e-6) for i in range(20)]
    out = branch_stability(points)
    assert _checked(points) == [0, 8, 16, 19] and CHECK_EVERY == 8
    assert all(p.calls.count("first") == 1 for p in points)   # the first box once per torus
    for i, (p, s) in enumerate(zip(points, out, strict=True)):
        assert s.checked == (i in (0, 8, 16, 19))
        assert s.exponents.largest == pytest.approx(p.full if s.checked else p.first)
        assert s.converged and s.stable


def test_a_stretch_that_needs_a_third_box_is_checked_throughout_and_bounded() -> None:
    points = [StandIn(-0.12) for _ in range(30)]
    for i in (8, 9, 10, 11):               # the box (1, 1) is not enough here
        points[i].boxes = 3
    out = branch_stability(points)
    assert _checked(points) == [0, 7, 8, 9, 10, 11, 12, 16, 24, 29]
    assert [s.checked for s in out[6:14]] == [False] + [True] * 6 + [False]


def test_a_change_of_stability_is_found_on_checked_tori() -> None:
    points = [StandIn(-0.55 + 0.1 * i) for i in range(12)]    # crosses zero after i = 5
    out = branch_stability(points)
    assert out[5].stable and not out[6].stable
    assert {5, 6} <= set(_checked(points))


def test_a_torus_within_the_margin_of_zero_is_checked() -> None:
    """The neighbours' boxes differ by 1e-4, so a first-box exponent within ten times that
    of zero could change sign with the box."""
    points = [StandIn(-0.2, -0.2 + 1e-4) for _ in range(9)]
    points[3] = StandIn(-0.9 * MARGIN * 1e-4)
    points[5] = StandIn(-1.1 * MARGIN * 1e-4)
    branch_stability(points)
    # 3 (inside the margin) and its neighbours (a jump of the exponent) are checked;
    # 5, just outside the margin, only for its own jump from 4 and 6
    assert 3 in _checked(points)
    points_far = [StandIn(-0.2, -0.2 + 1e-4) for _ in range(9)]
    points_far[3] = StandIn(-0.2 - 0.5 * 0.1 * 0.2)             # half the jump rule
    branch_stability(points_far)
    assert _checked(points_far) == [0, 8]


def test_every_one_checks_every_torus() -> None:
    points = [StandIn(-0.12) for _ in range(5)]
    out = branch_stability(points, every=1)
    assert _checked(points) == list(range(5)) and all(s.checked for s in out)
    assert branch_stability([]) == ()
