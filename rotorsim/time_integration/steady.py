"""Stop a time integration once its response is steady: the peak-to-peak of chosen values
over each segment (a shaft revolution, given by the caller) stops changing.

:class:`SteadyDetector` is a ``stop_when`` predicate of
:func:`~rotorsim.time_integration.integrate.integrate`. Over each segment ``k`` (the states
with ``floor(segment(state)) == k``) it takes the peak-to-peak ``p_k`` of every chosen
value (over the accepted steps); when a segment closes, it compares ``p_k`` with
``p_{k-1}``:

    ``max_i |p_k,i - p_{k-1},i| <= rtol * max_i p_k,i + atol``

and stops once this holds for ``revolutions`` consecutive segments. The scale is the
largest peak-to-peak of the chosen values, so values that barely move (an axial DOF) do not
hold the run back, and the static offset (gravity sag) does not count.

Why the peak-to-peak per revolution and not the state sampled once per revolution: a
stroboscopic sample settles only when the response is periodic with the shaft period; the
varying compliance of rolling bearings (ball-pass order ``Z kappa``, not an integer) and
sub-synchronous whirl make the steady response quasi-periodic, whose once-per-revolution
samples keep wandering over the orbit, while the peak-to-peak over a revolution, an envelope
of the orbit, settles.

Examples
--------
>>> from rotorsim.time_integration.base import State
>>> stop = SteadyDetector(segment=lambda s: s.t, rtol=1e-3, revolutions=2)
>>> z = np.zeros(1)
>>> reasons = [stop(State(0.25 * k, np.array([np.sin(0.5 * np.pi * k)]), z, z, z))
...            for k in range(20)]
>>> next(k for k, r in enumerate(reasons) if r) * 0.25   # stops at t = 3 (3 full periods)
3.0
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.time_integration.base import FloatArray, IntArray, State


class SteadyDetector:
    """Stop predicate: the per-segment peak-to-peak of chosen values has settled.

    Parameters
    ----------
    segment : callable
        ``segment(state) -> float``, non-decreasing (e.g. shaft revolutions ``phi / 2 pi``).
    dofs : int array, optional
        Unknowns watched (default all; excludes ``transform``).
    transform : array (m, n), optional
        Watch ``transform @ q`` (e.g. physical DOFs of a reduced model).
    rtol : float
        Allowed change between consecutive segments, relative to the largest peak-to-peak.
    atol : float
        Absolute allowance [units of q].
    revolutions : int
        Consecutive settled segments needed.
    after : float
        Ignore states before this time [s].

    Attributes
    ----------
    segment_index : int
        Index of the last closed segment when the run stopped (-1 before).
    change : float
        Relative change of the last comparison (NaN before the first).
    """

    def __init__(self, segment: Callable[[State], float], *, dofs: IntArray | None = None,
                 transform: FloatArray | None = None, rtol: float = 1e-3, atol: float = 0.0,
                 revolutions: int = 3, after: float = -math.inf) -> None:
        if not (rtol >= 0 and atol >= 0 and (rtol > 0 or atol > 0)):
            raise ModelError(f"need rtol >= 0, atol >= 0, not both 0; got {rtol}, {atol}",
                             "SteadyDetector")
        if int(revolutions) != revolutions or revolutions < 1:
            raise ModelError(f"revolutions must be a positive integer, got {revolutions!r}",
                             "SteadyDetector")
        self.segment, self.dofs, self.transform = segment, dofs, transform
        self.rtol, self.atol, self.revolutions, self.after = rtol, atol, int(revolutions), after
        self.segment_index, self.change = -1, math.nan
        self._open: int | None = None
        self._high = self._low = self._last = np.zeros(0)
        self._streak = 0

    def __call__(self, state: State) -> str:
        """The reason to stop (a sentence), or "" to go on."""
        if state.t < self.after:
            return ""
        x = state.q if self.dofs is None else state.q[self.dofs]
        if self.transform is not None:
            x = self.transform @ state.q
        k = math.floor(float(self.segment(state)))
        if self._open is None or k != self._open:
            reason = "" if self._open is None else self._close()
            self._open, self._high, self._low = k, np.array(x), np.array(x)
            return reason
        self._high, self._low = np.fmax(self._high, x), np.fmin(self._low, x)
        return ""

    def _close(self) -> str:
        """Close the open segment; the reason when the run is now steady."""
        p = self._high - self._low
        previous, self._last = self._last, p
        if previous.size != p.size:
            return ""
        scale = float(np.max(p))
        worst = float(np.max(np.abs(p - previous)))
        self.change = worst / scale if scale > 0 else (0.0 if worst == 0 else math.inf)
        settled = worst <= self.rtol * scale + self.atol
        self._streak = self._streak + 1 if settled else 0
        if self._streak < self.revolutions:
            return ""
        self.segment_index = int(self._open or 0)
        return (f"steady: the peak-to-peak of {p.size} values changed by at most "
                f"{self.change:.3g} of the largest ({scale:.4g}) over {self.revolutions} "
                f"consecutive revolutions (up to revolution {self.segment_index})")
