"""Jumps of the force tangents along a periodic orbit (contacts that open and close).

A unilateral spring ``f = k max(q - g, 0)`` has a continuous force but a tangent that jumps
between 0 and ``k`` where the contact closes and opens. The Floquet methods that sample the
tangent on a time grid (Hsu, the Newmark integration of the variational equation) then see
the contact duration only to within a grid step, and since a multiplier can be very
sensitive to it (the NLvib unilateral example: ``d mu / d t_c ~ 0.8`` per thousandth of a
period) their results are step-quantised. This module finds those jumps:

1. *candidates*: grid intervals over which the tangent changes by more than
   :data:`CANDIDATE` of its range over the period (max norm over the entries of ``K_t``
   and ``C_t``);
2. *jump test*: each candidate is refined :data:`TEST_LEVELS` times, keeping each time the
   eighth of the interval with the largest change. A jump keeps its full size under
   refinement; a continuous tangent loses it: by ``8^-L`` if smooth, by ``8^(-L p)`` for a
   contact onset ``k ~ delta^p`` (``p = 1/2`` Hertz point contact, ``p = 1/9`` a roller's
   line contact with exponent 10/9). A candidate whose change after ``L = 6`` levels (an
   interval 262144 times shorter; ``p = 1/9`` keeps 25 %) is still at least
   :data:`JUMP_KEEP` of the original is a jump;
3. *location*: the surviving intervals are refined further until shorter than
   :data:`PHASE_TOL` [rad].

Each level is one batched force call on all candidates (STYLE practice 3).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from rotorsim.harmonic_balance.fourier import FloatArray

CANDIDATE = 0.1
"""A grid interval whose tangent change exceeds this fraction of the tangent's range is
tested for a jump."""
JUMP_KEEP = 0.75
"""Least fraction of its change a jump keeps after :data:`TEST_LEVELS` refinements (a true
jump keeps about 100 %; a line-contact onset ``delta^(1/9)`` keeps ``8^(-6/9) = 25 %``)."""
TEST_LEVELS = 6
"""Refinements (by 8) before the jump test."""
PHASE_TOL = 1e-12
"""Width [rad] to which a jump's phase is located."""
SUBDIVISION = 8

TangentSampler = Callable[[FloatArray], FloatArray]
"""``sampler(tau (S,)) -> tangent entries (S, m)`` along the orbit."""


@dataclass(frozen=True, eq=False)
class TangentJumps:
    """Jumps of the tangent over one period.

    Attributes
    ----------
    phases : array (J,)
        Phases of the jumps in ``[0, 2 pi)`` [rad], sorted (located to ``PHASE_TOL``).
    sizes : array (J,)
        Size of each jump relative to the tangent's range over the period.
    candidates : int
        Grid intervals tested.
    evaluations : int
        Tangent samples evaluated by the test and the location.
    """

    phases: FloatArray
    sizes: FloatArray
    candidates: int
    evaluations: int

    @property
    def count(self) -> int:
        """Number of jumps ``J``."""
        return int(self.phases.size)


def find_jumps(sampler: TangentSampler, tau: FloatArray, values: FloatArray | None = None
               ) -> TangentJumps:
    """Jumps of the tangent ``sampler`` along the orbit (module docstring).

    Parameters
    ----------
    sampler : callable
        ``sampler(tau (S,)) -> (S, m)`` tangent entries at phases ``tau`` [rad].
    tau : array (N,)
        Increasing grid in ``[0, 2 pi)``; the interval after the last point wraps to
        ``tau[0] + 2 pi``.
    values : array (N, m), optional
        ``sampler(tau)`` when already evaluated.

    Examples
    --------
    A tangent that is 1 on ``[1, 2)`` rad and 0 elsewhere:

    >>> step = lambda t: ((np.mod(t, 2 * np.pi) >= 1) & (np.mod(t, 2 * np.pi) < 2)
    ...                   ).astype(float)[:, None]
    >>> jumps = find_jumps(step, np.linspace(0, 2 * np.pi, 64, endpoint=False))
    >>> jumps.count, np.round(jumps.phases, 10).tolist()
    (2, [1.0, 2.0])
    >>> find_jumps(lambda t: np.sin(t)[:, None], np.linspace(0, 6.2, 64)).count
    0
    """
    tau = np.asarray(tau, dtype=float)
    g = np.asarray(sampler(tau) if values is None else values, dtype=float)
    g = g.reshape(tau.size, -1)
    scale = float(np.max(g.max(axis=0) - g.min(axis=0), initial=0.0))
    empty = np.zeros(0)
    if scale == 0.0 or not np.isfinite(scale):
        return TangentJumps(empty, empty, 0, 0)
    change = np.max(np.abs(np.roll(g, -1, axis=0) - g), axis=1) / scale
    idx = np.flatnonzero(change > CANDIDATE)
    if idx.size == 0:
        return TangentJumps(empty, empty, 0, 0)
    left = tau[idx]
    right = np.where(idx + 1 < tau.size, tau[(idx + 1) % tau.size], tau[0] + 2.0 * np.pi)
    evaluations, target = 0, JUMP_KEEP * change[idx]
    for _ in range(TEST_LEVELS):      # a jump's interval never changes by less than the jump
        left, right, size, count = _refine(sampler, left, right, scale)
        evaluations += count
        keep = size >= target
        left, right, target = left[keep], right[keep], target[keep]
        if not left.size:
            break
    while left.size and np.max(right - left) > PHASE_TOL:
        left, right, size, count = _refine(sampler, left, right, scale)
        evaluations += count
    phases = np.mod(0.5 * (left + right), 2.0 * np.pi)
    order = np.argsort(phases)
    sizes = size[order] if left.size else empty
    return TangentJumps(phases[order], sizes, int(idx.size), evaluations)


def _refine(sampler: TangentSampler, left: FloatArray, right: FloatArray, scale: float
            ) -> tuple[FloatArray, FloatArray, FloatArray, int]:
    """Split each ``[left, right]`` in eighths and keep the one of largest change."""
    frac = np.linspace(0.0, 1.0, SUBDIVISION + 1)
    t = left[:, None] + (right - left)[:, None] * frac[None, :]      # (c, 9)
    g = np.asarray(sampler(t.reshape(-1)), dtype=float).reshape(t.shape[0], t.shape[1], -1)
    d = np.max(np.abs(np.diff(g, axis=1)), axis=2) / scale            # (c, 8)
    best = np.argmax(d, axis=1)
    rows = np.arange(left.size)
    return t[rows, best], t[rows, best + 1], d[rows, best], int(t.size)
