"""Multiplier crossings behind the events of a branch: what makes a sign change resolved.

A branch point is a sign change of the bordered determinant of the harmonic-balance
Jacobian away from a fold. The Jacobian is singular where the truncated Hill problem has
an exponent at 0, which is a Floquet multiplier crossing +1 *only where the truncation
and the sampling resolve it*: a nearly undamped mode whose multiplier pair passes next to
+1 on the unit circle (an internal resonance ``omega_mode = k omega``) can make the
determinant dip through zero in a tongue thinner than the truncation error, and next to a
contact onset the truncated orbit itself may not persist with more harmonics. Neither is
a bifurcation. So a branch point must also be a crossing of the multipliers the branch
computes with its own Floquet model:

* the number of real positive multipliers with ``|mu| > 1 + tol`` (:func:`real_unstable`)
  differs between the two points that bracket it, or between their outer neighbours
  (the same allowance the finer-sampling check of :mod:`.confirm` makes, since the
  determinant and the multipliers need not change at the very same step);
* and it still does on the bracket points corrected with more harmonics and samples
  (:class:`~.refined.SamplingCheck`, :data:`~.confirm.MORE_HARMONICS`).

On ``models/clearance_rotor.toml`` four branch points failed these checks and none of
them was confirmed by time integration; the two that passed, its axial pitchforks, both
were (docs/validation.md case 26, addendum "only resolved events").

A fold is exempt: it is resolved by the branch's own turn (the parameter component of the
tangent, checked on the finer sampling), and Floquet's real multiplier may pass +1 a few
points away from the turn where the model's multipliers carry their own error.

Period doublings and Neimark-Sacker points are counted on the multipliers already
(:mod:`.events`). A multiplier that leaves the unit circle at one edge of an *unstable
window* and returns at the other makes two events; when either edge is an artefact (it does
not survive the finer sampling, or its located zero is a jump or too steep), the window is
not resolved and the other edge is unresolved too (:func:`window_partners`).

References
----------
Y. A. Kuznetsov, Elements of Applied Bifurcation Theory, 3rd ed., Springer 2004, section
9.1 (a branch point of cycles has a multiplier at +1) and section 10.2 (test functions
must have regular zeros); M. Krack, J. Gross, Harmonic Balance for Nonlinear Vibration
Problems, Springer 2019, section 3.5 (Hill's method, its truncation and spurious
exponents).
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import Any, Protocol

import numpy as np

from rotorsim.analyses.periodic.events import IMAG_TOL, unstable_counts

KIND_INDEX = {"period_doubling": 0, "neimark_sacker": 1}
"""Column of :func:`~.events.unstable_counts` for each multiplier-counted kind."""


class Bracketed(Protocol):
    """A candidate event between branch points ``i < j``."""

    @property
    def kind(self) -> str: ...

    @property
    def i(self) -> int: ...

    @property
    def j(self) -> int: ...


def real_unstable(mu: Any, tol: float) -> int:
    """Number of real positive multipliers with ``|mu| > 1 + tol``.

    Examples
    --------
    >>> real_unstable([1.2, 1.0 + 1e-9, -1.3, 1.1 + 0.2j, 1.1 - 0.2j, 0.5], 1e-5)
    1
    """
    m = np.asarray(mu, dtype=complex)
    size = np.abs(m)
    real = np.abs(m.imag) <= IMAG_TOL * np.maximum(size, 1.0)
    return int(np.sum(real & (m.real > 0) & (size > 1.0 + tol)))


def largest_real(mu: Any) -> float:
    """Largest real positive multiplier (0 when there is none)."""
    m = np.asarray(mu, dtype=complex)
    real = np.abs(m.imag) <= IMAG_TOL * np.maximum(np.abs(m), 1.0)
    chosen = m.real[real & (m.real > 0)]
    return float(chosen.max()) if chosen.size else 0.0


def missing_crossing(candidate: Bracketed, multipliers: np.ndarray, tol: float) -> str:
    """"" when the branch point ``candidate`` is a crossing of ``|mu| = 1 + tol`` by a real
    multiplier of the branch (module docstring), else why not.

    Parameters
    ----------
    candidate : Bracketed
        A branch-point candidate between points ``i`` and ``j``.
    multipliers : complex array (P, r)
        The branch's multipliers (NaN rows where Floquet failed).
    tol : float
        Stability tolerance on ``|mu| - 1``.
    """
    last = multipliers.shape[0] - 1
    pairs = ((candidate.i, candidate.j),
             (max(candidate.i - 1, 0), min(candidate.j + 1, last)))
    judged = False
    for a, b in pairs:
        if not (np.all(np.isfinite(multipliers[a])) and np.all(np.isfinite(multipliers[b]))):
            continue
        judged = True
        if real_unstable(multipliers[a], tol) != real_unstable(multipliers[b], tol):
            return ""
    if not judged:
        return "no Floquet multipliers next to the sign change"
    i, j = candidate.i, candidate.j
    return (f"no real Floquet multiplier crosses |mu| = 1 + {tol:g} at this sign change of "
            f"the determinant (largest real multiplier {largest_real(multipliers[i]):.4g} "
            f"at point {i}, {largest_real(multipliers[j]):.4g} at point {j}): not a "
            "resolved crossing of +1")


def window_partners(found: Sequence[Bracketed], reasons: Mapping[Any, str],
                    coarse: np.ndarray, tol: float) -> dict[Any, str]:
    """A multiplier leaving the unit circle and coming back bounds an unstable window:
    when one edge of a window is an artefact (a nonempty reason), the other edge is
    unresolved too. Returns the new reasons of such edges."""
    out: dict[Any, str] = {}
    for kind, c in KIND_INDEX.items():
        edges = [f for f in found if f.kind == kind]
        for a, b in itertools.pairwise(edges):
            up = unstable_counts(coarse[a.j], tol)[c] - unstable_counts(coarse[a.i], tol)[c]
            down = unstable_counts(coarse[b.j], tol)[c] - unstable_counts(coarse[b.i], tol)[c]
            if up * down >= 0 or bool(reasons.get(a)) == bool(reasons.get(b)):
                continue
            lone = b if reasons.get(a) else a
            out[lone] = "the other edge of its unstable window did not survive the check"
    return out
