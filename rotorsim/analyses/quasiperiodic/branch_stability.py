"""Stability of every torus of a branch, with the stability box checked where it matters.

:func:`~rotorsim.analyses.quasiperiodic.stability.torus_stability` grows the stability box
of each torus, (1, 1) then (1, b) ..., until two boxes agree. On the default model the
second box's Hill matrix (630 rows against 378) costs four fifths of the exponents' time,
and at 189 of its 190 tori it only confirms the first box to 1e-3. Along a branch the box
a torus needs changes with the modulation of the torus, smoothly between points, so
:func:`branch_stability` solves the first box at every torus and grows the boxes (the full
check) only

- at every :data:`CHECK_EVERY`-th torus and the last one;
- next to every checked torus that the first box did not converge (the two boxes
  disagreed beyond :data:`~.stability.AGREE_RTOL`, or a third box was needed), and so on
  outwards until a checked torus on each side was converged by its first box: a stretch
  of the branch that needs larger boxes is checked throughout, and bounded by checks;
- at every torus whose first-box verdict differs from a neighbour's (a change of
  stability: the event's two tori are always checked);
- at every torus whose largest real part lies within :data:`MARGIN` times the larger box
  difference of its checked neighbours (or the stability tolerance) of zero, where the
  box could flip the verdict;
- at every torus whose first-box critical exponent moved from a neighbour's by more than
  :data:`JUMP` of its magnitude (a change of the critical mode's character between the
  checked tori).

Each new check can make its intervals fail the rule, so the rules are applied again until
no torus needs one. A torus that was not checked keeps its first-box exponents, marked
``checked=False``, with ``converged`` True only when its first box also kept its selected
exponents inside the box (its edge share). Measured on the default model's branch of 190
tori: the same stability of every torus and the same largest exponents to
:data:`~.stability.AGREE_RTOL` as the full check at every torus
(``tests/analyses/test_quasi_periodic_branch_stability.py``; ``docs/benchmarks.md``).
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Sequence
from typing import Any

import numpy as np

from rotorsim.analyses.quasiperiodic.stability import TorusStability

FIRST_BOX = (1, 1)
"""The box solved at every torus."""
CHECK_EVERY = 8
"""Tori between scheduled full checks."""
MARGIN = 10.0
"""A first-box exponent within this many box differences of zero gets the full check."""
JUMP = 0.1
"""Relative change of the first-box largest real part between neighbours that gets the
full check."""


def branch_stability(points: Sequence[Any], every: int = CHECK_EVERY
                     ) -> tuple[TorusStability, ...]:
    """The stability of each of ``points`` (:class:`~.point.QuasiPeriodicPoint` in branch
    order) by the rules of the module docstring.

    Parameters
    ----------
    points : sequence of QuasiPeriodicPoint
    every : int
        Tori between scheduled full checks (1: every torus is checked).
    """
    n = len(points)
    if n == 0:
        return ()
    small = [p.exponents(box=FIRST_BOX) for p in points]
    full: dict[int, TorusStability] = {}

    def check(i: int) -> bool:
        if i in full:
            return False
        full[i] = points[i].exponents(first=small[i])
        return True

    for i in sorted({*range(0, n, max(int(every), 1)), n - 1}):
        check(i)
    while any([check(i) for i in _needing_check(small, full)]):
        pass
    return tuple(full[i] if i in full else dataclasses.replace(small[i], checked=False)
                 for i in range(n))


def _needing_check(small: Sequence[TorusStability], full: dict[int, TorusStability]
                   ) -> list[int]:
    """Unchecked tori that the rules (module docstring) send to the full check, given the
    checks so far."""
    largest = np.array([s.exponents.largest for s in small])
    stable = np.array([s.stable for s in small])
    checked = sorted(full)
    out: list[int] = []
    for j0, j1 in itertools.pairwise(checked):
        if j1 - j0 < 2:
            continue
        ends = (full[j0], full[j1])
        inside = range(j0 + 1, j1)
        if not all(_first_box_suffices(c) for c in ends):
            # walk out from the torus that needed more: its neighbour next
            out.extend(i for i, c in ((j0 + 1, ends[0]), (j1 - 1, ends[1]))
                       if not _first_box_suffices(c))
            continue
        margin = MARGIN * max(max(_box_difference(c) for c in ends), ends[0].tolerance)
        for i in inside:
            near = (i - 1, i + 1)
            if (abs(largest[i]) <= margin
                    or any(stable[k] != stable[i] for k in near)
                    or any(abs(largest[k] - largest[i]) > JUMP * abs(largest[i])
                           for k in near)):
                out.append(i)
    return out


def _first_box_suffices(check: TorusStability) -> bool:
    """The full check converged with the second box agreeing with the first."""
    return check.converged and len(check.boxes) == 2


def _box_difference(check: TorusStability) -> float:
    """|largest real part of the last box - that of the first| [1/s]."""
    return float(abs(check.largest[-1] - check.largest[0]))
