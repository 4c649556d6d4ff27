"""A finer torus grid where a branch of tori stalls.

A rolling contact that opens and closes puts a kink in the bearing force; sampled on the
torus grid of the AFT, the kink makes the harmonic-balance residual non-smooth at the
scale of one grid cell. Where the contact set changes along the branch, the corrector can
then fail at every step size but the tiniest, and the branch creeps: hundreds of points
within a fraction of a rad/s (measured on the textbook rigid rotor past its fold near
637 rad/s with the box (8, 3) on the default (64, 16) grid: 30 points within 0.6 rad/s).
The same branch passes on a (128, 32) grid started before the stall, and with this
module's restarts it refines twice, to (256, 64), and goes on down to 600 rad/s.

:class:`StallWatch` ends a branch segment when its accepted steps stay tiny;
:func:`finer` doubles the grid (up to :data:`MAX_REFINEMENTS` times) and the branch
carries on from the last point before the stall with the finer grid. The tones, and so
the unknowns, are unchanged: only the sampling of the force gets finer.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from rotorsim.harmonic_balance.quasi import TorusAFT
from rotorsim.solvers.continuation_state import ContinuationState

STALL_POINTS = 6
"""Consecutive tiny accepted steps that make a stall."""
STALL_FRACTION = 0.01
"""A step is tiny below this fraction of the largest step."""
MAX_REFINEMENTS = 2
"""Grid doublings at most (each doubles ``N1`` and ``N2``: 16 times the samples)."""


@dataclass
class StallWatch:
    """Continuation monitor (``continue_branch(monitor=)``): True after
    :data:`STALL_POINTS` consecutive accepted steps below :data:`STALL_FRACTION` of
    ``max_step`` (scaled arclength); ``good`` is then the index of the last point before
    them."""

    max_step: float
    tiny: list[int] = field(default_factory=list)
    good: int = -1

    def __call__(self, state: ContinuationState) -> bool:
        if state.point > 0 and state.last_step < STALL_FRACTION * self.max_step:
            self.tiny.append(state.point)
        else:
            self.tiny.clear()
        if len(self.tiny) >= STALL_POINTS:
            self.good = self.tiny[0] - 1
            return True
        return False


def finer(aft: TorusAFT) -> TorusAFT:
    """The same tones on a grid twice as fine in both angles."""
    n1, n2 = aft.grid
    return TorusAFT(aft.harmonics, (2 * n1, 2 * n2))
