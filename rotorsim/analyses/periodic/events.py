"""Period-doubling and Neimark-Sacker points of a rotor branch, robust to neutral modes.

The generic test functions of :mod:`rotorsim.harmonic_balance.bifurcation` change sign
whenever *any* multiplier touches ``-1`` or a product ``mu_i mu_j`` crosses 1. A rotor has
undamped or nearly undamped modes (shaft modes far from the bearings, the free rotor of seed
002) whose multipliers sit on the unit circle up to round-off, so those tests fire at
random there. Here the multipliers are *counted* instead: at each point,

* ``n_pd``: real multipliers (``|Im mu| <= 1e-6 max(|mu|, 1)``) with ``Re mu < 0`` and
  ``|mu| > 1 + tol``;
* ``n_ns``: complex multipliers with ``|mu| > 1 + tol``;

and a change of ``n_pd`` (``n_ns``) between consecutive points brackets a period doubling
(Neimark-Sacker point). It is located by the Illinois method along the branch
(:mod:`rotorsim.solvers.continuation_locate`) on ``g = |mu|_(k) - (1 + tol)``, the
``k``-th largest modulus of that kind, ``k`` the larger count of the bracket; the located
point is where the crossing multiplier passes ``|mu| = 1 + tol``.
Folds and branch points come from the branch itself
(:func:`~rotorsim.harmonic_balance.bifurcation.detect_bifurcations`).

References
----------
Seed 002 section 3.5.2.2 (Floquet multipliers); Y. A. Kuznetsov, Elements of Applied
Bifurcation Theory, 3rd ed., Springer 2004, section 9.1 (multipliers at the bifurcations
of cycles).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Collection
from typing import Any, Protocol

import numpy as np

from rotorsim.elements.base import FloatArray
from rotorsim.harmonic_balance.bifurcation import PROBE_MAX_ITER, BifurcationEvent
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.continuation_core import CorrectorOptions, ScaledSystem
from rotorsim.solvers.continuation_locate import (
    ESTIMATE_WIDTH,
    Segment,
    illinois,
    steepness,
)

IMAG_TOL = 1e-6
"""``|Im mu| <= IMAG_TOL max(|mu|, 1)`` counts as real."""
KINDS = ("period_doubling", "neimark_sacker")


class FloquetModel(Protocol):
    """Multipliers at a point ``(x, lam)`` of a branch (``lam`` its continuation
    parameter) and the stability tolerance on ``|mu| - 1``: a
    :class:`~rotorsim.analyses.periodic.stability.StabilityModel` or the stability of a
    parameter branch."""

    @property
    def tol(self) -> float: ...

    def floquet(self, x: FloatArray, lam: float) -> Any: ...


def unstable_counts(mu: Any, tol: float) -> tuple[int, int]:
    """``(n_pd, n_ns)`` of a set of multipliers (module docstring).

    Examples
    --------
    >>> unstable_counts([-1.2, 0.5, 1.1 + 0.3j, 1.1 - 0.3j, 1.0 + 1e-9], 1e-5)
    (1, 2)
    """
    m = np.asarray(mu, dtype=complex)
    size = np.abs(m)
    outside = size > 1.0 + tol
    real = np.abs(m.imag) <= IMAG_TOL * np.maximum(size, 1.0)
    return int(np.sum(outside & real & (m.real < 0))), int(np.sum(outside & ~real))


def kth_modulus(mu: Any, kind: str, k: int) -> float:
    """``k``-th largest ``|mu|`` among the real negative (period doubling) or the complex
    (Neimark-Sacker) multipliers; 0 when there are fewer."""
    m = np.asarray(mu, dtype=complex)
    size = np.abs(m)
    real = np.abs(m.imag) <= IMAG_TOL * np.maximum(size, 1.0)
    chosen = size[real & (m.real < 0)] if kind == "period_doubling" else size[~real]
    chosen = np.sort(chosen)[::-1]
    return float(chosen[k - 1]) if chosen.size >= k else 0.0


def floquet_events(residual: Callable[..., Any], branch: Branch, model: FloquetModel,
                   multipliers: np.ndarray, *, tol: float = 1e-8,
                   max_iter: int = 40, relative_tol: float = 0.0,
                   pairs: Collection[tuple[str, int, int]] | None = None,
                   ) -> list[BifurcationEvent]:
    """Located period doublings and Neimark-Sacker points between the points of ``branch``.

    Parameters
    ----------
    residual : callable
        The continuation callback that produced ``branch``.
    branch : Branch
    model : FloquetModel
        Computes the multipliers at intermediate points.
    multipliers : complex array (P, r)
        Multipliers at the branch points (NaN rows are skipped).
    tol, max_iter
        Location tolerance on the scaled chord abscissa and Illinois iterations.
    relative_tol : float
        Location tolerance as a fraction of the bracket's chord (the larger applies).
    pairs : collection of (kind, i, j), optional
        Locate only these count changes (e.g. the confirmed ones); default all.
    """
    valid = np.flatnonzero(np.all(np.isfinite(multipliers), axis=1))
    counts = [unstable_counts(multipliers[i], model.tol) for i in valid]
    system = ScaledSystem(residual, branch.x_scale, branch.r_scale, branch.lam_scale)
    corrector = CorrectorOptions(branch.options.tol, min(PROBE_MAX_ITER, branch.options.max_iter),
                                 branch.options.max_backtracks, step_tol=tol,
                                 stall_tol=branch.options.stall_tol)
    points = branch.scaled()
    events = []
    for a in range(valid.size - 1):
        i, j = int(valid[a]), int(valid[a + 1])
        for c, kind in enumerate(KINDS):
            if counts[a][c] == counts[a + 1][c] or (pairs is not None
                                                     and (kind, i, j) not in pairs):
                continue
            k = max(counts[a][c], counts[a + 1][c])
            chord = float(np.linalg.norm(points[j] - points[i]))
            event = _locate(system, corrector, points, model, kind, k, i, j,
                            max(tol, relative_tol * chord), max_iter)
            if event is not None:
                events.append(event)
    return events


def _locate(system: ScaledSystem, corrector: CorrectorOptions, points: FloatArray,
            model: FloquetModel, kind: str, k: int, i: int, j: int, tol: float,
            max_iter: int) -> BifurcationEvent | None:
    def test(y: FloatArray, ev: Any, tan: Any, border: Any) -> tuple[float, Any]:
        x, lam = system.from_y(y)
        mu = model.floquet(x, lam).multipliers
        return kth_modulus(mu, kind, k) - (1.0 + model.tol), mu

    segment = Segment.between(system, corrector, points[i], points[j], test)
    lo, hi = segment.endpoint(points[i]), segment.endpoint(points[j])
    if lo is None or hi is None or lo.value * hi.value > 0.0:
        return None
    ends, length = (lo.value, hi.value), hi.s - lo.s
    # no early jump screen: the count-based test switches between multiplier sets (a
    # complex pair becoming real), so its bracket values may differ by O(1) although the
    # crossing multiplier moves smoothly; the steepness at the located zero is judged
    lo, hi = illinois(segment, lo, hi, tol, max_iter, ESTIMATE_WIDTH * length)
    regular = True
    best = lo if abs(lo.value) <= abs(hi.value) else hi
    point = segment.polished(best)      # on the branch; the value is the bracket's
    x, lam = system.from_y(point.y)
    return BifurcationEvent(kind, lam, x, i, j, ends, regular and hi.s - lo.s <= tol,
                            "test_function", None, point.data, best.value,
                            steepness(lo, hi, ends, length) if regular else math.inf)
