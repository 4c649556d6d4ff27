"""Bifurcations along a continued branch: detection by test functions, then location.

Generic (no rotor, no harmonic-balance specifics): a branch of ``R(x, lam) = 0`` from
:func:`~rotorsim.solvers.continuation.continue_branch`, the same residual callback, and,
for the stability of periodic solutions, a callback ``multipliers(x, lam) -> complex
array`` (Floquet multipliers).

Test functions at every point, each changing sign at its bifurcation:

* fold (limit point): the ``lam`` component of the unit tangent;
* branch point: the sign of ``det [[dR/dx, dR/dlam], [t^T]]`` (from the LU factors, as a
  sum of ``log |u_ii|`` and a product of signs, so it never overflows);
* period doubling: ``prod (1 + mu_i)`` over the multipliers (a real multiplier crosses -1;
  complex pairs contribute ``|1 + mu|^2 > 0``);
* Neimark-Sacker: ``prod_{i<j} (mu_i mu_j - 1)`` (a complex pair crosses the unit circle,
  ``mu mu* = 1``); a sign change caused by two real multipliers with product 1 (a neutral
  saddle) is discarded after location.

Products are reduced to ``sign * exp(mean log |factor|)``: continuous, with the sign of the
product, and free of overflow. Each sign change between two points is located by the
Illinois (modified regula falsi) method on the test function along the branch: an
intermediate point at chord abscissa ``s`` is re-corrected on the hyperplane through
``y_i + s u`` orthogonal to the chord ``u``. Folds are then polished by Newton on the
extended system of seed 002 (:func:`~rotorsim.harmonic_balance.fold_tracking.locate_fold`).

References
----------
Seed 002 section 3.5.2.2 (Floquet multipliers, extended system ``dF/dP phi = 0``).
Y. A. Kuznetsov, Elements of Applied Bifurcation Theory, 3rd ed., Springer 2004, sections
10.2 (test functions) and 10.3; R. Seydel, Practical Bifurcation and Stability Analysis,
Springer 2010, chapter 5.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Collection
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.fold_tracking import locate_fold
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    FloatArray,
    ResidualCallback,
    ScaledSystem,
    Tangent,
)
from rotorsim.solvers.continuation_locate import (
    ESTIMATE_WIDTH,
    Segment,
    SegmentPoint,
    illinois,
    screened,
    steepness,
)

MultiplierCallback = Callable[[FloatArray, float], ArrayLike]
"""``multipliers(x, lam) -> complex array``: Floquet multipliers of the periodic solution."""

KINDS = ("fold", "branch_point", "period_doubling", "neimark_sacker")


@dataclass(frozen=True)
class BifurcationOptions:
    """Options of :func:`detect_bifurcations`.

    Parameters
    ----------
    kinds : tuple of str
        Subset of ``KINDS`` to look for (multiplier kinds need ``multipliers``).
    tol : float
        Location tolerance on the chord abscissa (scaled arclength).
    max_iter : int
        Illinois iterations per event.
    fold_tol, fold_max_iter : float, int
        Newton tolerance (scaled residual) and iterations of the extended fold system.
    fd_step : float
        Difference step of the extended system's second derivatives.
    relative_tol : float
        Location tolerance as a fraction of the bracket's chord (the larger of the two
        applies): 1e-6 places an event to a millionth of the step between its points.
    screen_jumps : bool
        Stop locating a branch point or a multiplier event whose test function jumps
        across zero instead of passing through it
        (:func:`~rotorsim.solvers.continuation_locate.screened`); it is returned
        unlocated with ``steepness = inf``. Folds are always located (a corner of a
        non-smooth branch is a fold too).
    """

    kinds: tuple[str, ...] = KINDS
    tol: float = 1e-10
    max_iter: int = 60
    fold_tol: float = 1e-12
    fold_max_iter: int = 20
    fd_step: float = 1e-5
    relative_tol: float = 0.0
    screen_jumps: bool = False

    def __post_init__(self) -> None:
        unknown = sorted(set(self.kinds) - set(KINDS))
        if unknown:
            raise TypeError(f"unknown bifurcation kinds {unknown}; valid: {', '.join(KINDS)}")
        if not (self.tol > 0 and self.fold_tol > 0 and self.max_iter >= 1):
            raise ModelError("need tol > 0, fold_tol > 0 and max_iter >= 1",
                             "BifurcationOptions")


@dataclass(frozen=True, eq=False)
class BifurcationEvent:
    """A bifurcation located on a branch.

    Attributes
    ----------
    kind : str
        One of ``KINDS``.
    lam : float
        Parameter at the bifurcation.
    x : array (m,)
        Unknowns at the bifurcation.
    index : int
        The event lies between branch points ``index`` and ``next_index``.
    next_index : int
    test_values : (float, float)
        Test function at the two bracketing points (opposite signs).
    located : bool
        True when the extended system converged (folds) or the bracket shrank below the
        tolerance; False leaves the best estimate (e.g. a failed re-correction).
    method : str
        "extended_system" or "test_function".
    null_vector : array (m,) or None
        Folds: null vector of ``dR/dx`` in scaled unknowns.
    multipliers : complex array or None
        Period doubling and Neimark-Sacker: the multipliers at the located point.
    value : float
        Test function at the located point (NaN for folds polished by the extended
        system): a regular zero is small against ``test_values``, a jump is not.
    steepness : float
        Slope of the test function at the located point over its mean slope between
        the bracket points (:func:`~rotorsim.solvers.continuation_locate.steepness`): about
        1 at a regular zero, large at a thin non-smooth transition.
    """

    kind: str
    lam: float
    x: FloatArray
    index: int
    next_index: int
    test_values: tuple[float, float]
    located: bool
    method: str
    null_vector: FloatArray | None = None
    multipliers: NDArray[np.complex128] | None = None
    value: float = math.nan
    steepness: float = math.nan


def branch_test_functions(branch: Branch, multipliers: MultiplierCallback | None = None,
                   ) -> dict[str, FloatArray]:
    """Test function of each bifurcation kind at every branch point (P,).

    "fold" and "branch_point" come from the branch itself; "period_doubling" and
    "neimark_sacker" call ``multipliers`` once per point. NaN or 0 marks "unknown".

    Examples
    --------
    >>> mu = np.array([-1.2, 0.5, 0.3 + 0.9j, 0.3 - 0.9j])
    >>> round(period_doubling_value(mu), 6) < 0, neimark_sacker_value(mu) > 0
    (True, True)
    """
    out = {"fold": branch.tangents[:, -1].copy(), "branch_point": branch.det_sign.astype(float)}
    if multipliers is not None:
        values = [np.asarray(multipliers(x, lam), dtype=complex)
                  for x, lam in zip(branch.x, branch.lam, strict=True)]
        out["period_doubling"] = np.array([period_doubling_value(v) for v in values])
        out["neimark_sacker"] = np.array([neimark_sacker_value(v) for v in values])
    return out


def period_doubling_value(mu: ArrayLike) -> float:
    """``prod (1 + mu_i)`` as ``sign * exp(mean log |1 + mu_i|)``."""
    return _signed_mean(np.asarray(mu, dtype=np.complex128) + (1.0 + 0.0j))


def neimark_sacker_value(mu: ArrayLike) -> float:
    """``prod_{i<j} (mu_i mu_j - 1)`` as ``sign * exp(mean log |.|)``."""
    m = np.asarray(mu, dtype=complex).ravel()
    i, j = np.triu_indices(m.size, k=1)
    return _signed_mean(m[i] * m[j] - 1.0)


def detect_bifurcations(residual: ResidualCallback, branch: Branch, *,
                        multipliers: MultiplierCallback | None = None,
                        options: BifurcationOptions | None = None,
                        pairs: Collection[tuple[str, int, int]] | None = None,
                        ) -> tuple[BifurcationEvent, ...]:
    """Find and locate the bifurcations between the points of ``branch``.

    Parameters
    ----------
    residual : callable
        The callback that produced ``branch``.
    branch : Branch
    multipliers : callable, optional
        ``multipliers(x, lam) -> complex array``; needed for period doubling and
        Neimark-Sacker points.
    options : BifurcationOptions, optional
    pairs : collection of (kind, i, j), optional
        Locate only these sign changes (e.g. the confirmed ones); default all.

    Returns
    -------
    tuple of BifurcationEvent
        Sorted along the branch. Attach them with ``branch.with_events(events)``.

    Examples
    --------
    >>> from rotorsim.solvers.continuation import Continuation, continue_branch
    >>> def s_curve(x, lam):
    ...     return x**3 - x + lam, np.diag(3 * x**2 - 1), np.ones(1)
    >>> b = continue_branch(s_curve, [-1.3], 1.0, Continuation(direction=-1, lam_min=-1.0))
    >>> events = detect_bifurcations(s_curve, b)
    >>> [(e.kind, round(e.lam, 12)) for e in events]
    [('fold', -0.38490017946), ('fold', 0.38490017946)]
    """
    opts = options if options is not None else BifurcationOptions()
    values = branch_test_functions(branch, multipliers)
    locator = _Locator(residual, branch, multipliers, opts)
    events = []
    for kind in opts.kinds:
        if kind not in values:
            continue
        for i, j in _sign_changes(values[kind]):
            if pairs is not None and (kind, i, j) not in pairs:
                continue
            event = locator.locate(kind, i, j, (float(values[kind][i]), float(values[kind][j])))
            if event is not None:
                events.append(event)
    return tuple(sorted(events, key=lambda e: (e.index, e.kind)))


def _sign_changes(values: FloatArray) -> list[tuple[int, int]]:
    """Pairs of consecutive valid points (finite, nonzero) with opposite signs."""
    valid = np.flatnonzero(np.isfinite(values) & (values != 0.0))
    signs = np.sign(values[valid])
    change = np.flatnonzero(signs[1:] != signs[:-1])
    return [(int(valid[k]), int(valid[k + 1])) for k in change]


def _signed_mean(factors: NDArray[np.complex128]) -> float:
    """Sign of the (real) product of ``factors`` times the geometric mean of ``|f|``."""
    if factors.size == 0:
        return 1.0
    size = np.abs(factors)
    if np.any(size == 0.0):
        return 0.0
    sign = 1.0 if math.cos(float(np.sum(np.angle(factors)))) >= 0.0 else -1.0
    return sign * math.exp(float(np.mean(np.log(size))))


CORNER_STEEPNESS = 100.0
"""A fold whose test function (the tangent's parameter component) crosses zero more than
this many times as steeply as across its first bracket turns at a corner of the branch (a
contact onset met by a sample): the extended system, which needs a smooth fold, is not
tried there (on the clearance rotor it failed at both folds, 0.9 s each), and the fold is
located on its test function."""

PROBE_MAX_ITER = 6
"""Newton iterations of a probe's corrector: it starts from the cubic Hermite interpolant
of its bracket, O(h^4) from the branch, and converges in 2-3 where the residual is smooth;
where a contact-onset sample makes it stall (accepted within ``stall_tol``), more
iterations only cost evaluations."""


class _Locator:
    """Locates each kind of sign change with :mod:`~rotorsim.solvers.continuation_locate`."""

    def __init__(self, residual: ResidualCallback, branch: Branch,
                 multipliers: MultiplierCallback | None, options: BifurcationOptions) -> None:
        self.system = ScaledSystem(residual, branch.x_scale, branch.r_scale, branch.lam_scale)
        self.residual = residual
        self.branch = branch
        self.points = branch.scaled()
        self.multipliers = multipliers
        self.options = options
        self.corrector = CorrectorOptions(branch.options.tol,
                                          min(PROBE_MAX_ITER, branch.options.max_iter),
                                          branch.options.max_backtracks,
                                          step_tol=options.tol,
                                          stall_tol=branch.options.stall_tol)

    def locate(self, kind: str, i: int, j: int,
               ends: tuple[float, float]) -> BifurcationEvent | None:
        reference = [math.nan]
        segment = Segment.between(self.system, self.corrector, self.points[i], self.points[j],
                                  lambda y, ev, tan, border: self._test(kind, y, tan, border,
                                                                        reference),
                                  guard="drift" if kind == "branch_point" else "cone")
        lo = segment.endpoint(self.points[i])
        hi = segment.endpoint(self.points[j])
        if lo is None or hi is None or lo.value * hi.value >= 0.0:
            return None
        if kind == "branch_point":  # one condensation per probe where no fold is near
            segment = segment.held(lo, hi)
        h = hi.s - lo.s
        if kind == "branch_point":  # the branch stores det signs; the slope needs values
            ends = (lo.value, hi.value)
        tol = max(self.options.tol, self.options.relative_tol * h)
        coarse = max(tol, 1e-6 * h) if kind == "fold" else tol
        # folds sit at corners of a contact branch, where a Hermite estimate across the
        # corner is only O(w) close (and the parameter has kinks at every contact onset
        # an AFT sample crosses): their probes are always corrected
        near = ESTIMATE_WIDTH * h if kind != "fold" else 0.0
        if self.options.screen_jumps and kind != "fold":
            lo, hi, regular = screened(segment, lo, hi, coarse, self.options.max_iter, near)
        else:
            lo, hi, regular = *illinois(segment, lo, hi, coarse, self.options.max_iter,
                                        near), True
        if not regular:  # a jump of the test function: returned unlocated
            best = lo if abs(lo.value) <= abs(hi.value) else hi
            x, lam = self.system.from_y(segment.polished(best).y)
            return BifurcationEvent(kind, lam, x, i, j, ends, False, "test_function",
                                    None, best.data, best.value, math.inf)
        if kind == "fold":
            best = lo if abs(lo.value) <= abs(hi.value) else hi
            smooth = steepness(lo, hi, ends, h) <= CORNER_STEEPNESS
            fold = self._fold(best, h) if smooth else None
            if fold is not None:
                x, lam, phi = fold
                return BifurcationEvent("fold", lam, x, i, j, ends, True, "extended_system",
                                        phi)
            lo, hi = illinois(segment, lo, hi, tol, self.options.max_iter, near)
        best = lo if abs(lo.value) <= abs(hi.value) else hi
        # the event's point on the branch; its test value is that of the bracket, where
        # the estimates are free of the corrector's noise at a nearly singular Jacobian
        point = segment.polished(best)
        if kind == "neimark_sacker" and not _is_complex_crossing(point.data):
            return None
        x, lam = self.system.from_y(point.y)
        return BifurcationEvent(kind, lam, x, i, j, ends, hi.s - lo.s <= tol, "test_function",
                                point.t[:-1] if kind == "fold" else None, point.data,
                                best.value, steepness(lo, hi, ends, h))

    def _test(self, kind: str, y: FloatArray, tan: Tangent, border: FloatArray,
              reference: list[float]) -> tuple[float, NDArray[np.complex128] | None]:
        """Test value at a corrected point (and the multipliers for the Floquet kinds)."""
        if kind == "fold":
            return float(tan.t[-1]), None
        if kind == "branch_point":
            # |det| = |c| (border . t) for the cofactor vector c; compare |c| to the first
            log_c = tan.log_det - math.log(float(border @ tan.t))
            if math.isnan(reference[0]):
                reference[0] = log_c
            return tan.det_sign * math.exp(max(-700.0, min(700.0, log_c - reference[0]))), None
        assert self.multipliers is not None
        x, lam = self.system.from_y(y)
        mu = np.asarray(self.multipliers(x, lam), dtype=complex)
        value = period_doubling_value(mu) if kind == "period_doubling" \
            else neimark_sacker_value(mu)
        return value, mu

    def _fold(self, best: SegmentPoint, h: float) -> tuple[FloatArray, float, FloatArray] | None:
        """Polish a fold with the extended system; None if it fails or lands elsewhere."""
        x, lam = self.system.from_y(best.y)
        try:
            fold = locate_fold(self.residual, x, lam, best.t[:-1],
                               x_scale=self.branch.x_scale, r_scale=self.branch.r_scale,
                               lam_scale=self.branch.lam_scale, tol=self.options.fold_tol,
                               max_iter=self.options.fold_max_iter,
                               fd_step=self.options.fd_step)
        except ConvergenceError:
            return None
        if np.linalg.norm(self.system.to_y(fold.x, fold.lam) - best.y) > h:
            return None
        return fold.x, fold.lam, fold.phi


def _is_complex_crossing(mu: NDArray[np.complex128] | None) -> bool:
    """Is the multiplier pair with product closest to 1 a complex-conjugate pair?"""
    if mu is None or mu.size < 2:
        return False
    i, j = np.triu_indices(mu.size, k=1)
    k = int(np.argmin(np.abs(mu[i] * mu[j] - 1.0)))
    return bool(abs(mu[i[k]].imag) > 1e-8 * max(1.0, abs(mu[i[k]])))
