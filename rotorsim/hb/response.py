"""The verbs of :mod:`rotorsim.hb`: :func:`solve` one frequency, :func:`frequency_response`.

``frequency_response`` discretises the :class:`~rotorsim.hb.system.System` by HB-AFT
condensed onto the nonlinear DOFs (:func:`~rotorsim.harmonic_balance.residual.
make_residual`), starts from the linear response at ``start``, which also gives the scales
of the unknowns (:mod:`rotorsim.hb.scaling`), traces the branch to ``stop`` by
pseudo-arclength continuation (:func:`~rotorsim.solvers.continuation.continue_branch`,
frequency scaled by ``|stop - start|``), computes the Floquet multipliers of every point
(Hill's method for small systems, Hsu's otherwise) and locates folds, branch points,
period doublings and Neimark-Sacker points
(:func:`~rotorsim.harmonic_balance.bifurcation.detect_bifurcations`).

References
----------
Seed 002 section 3.5.2 (HB-AFT, arclength continuation, Floquet multipliers). M. Krack,
J. Gross, *Harmonic Balance for Nonlinear Vibration Problems*, Springer 2019, ch. 3-4.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError, Status
from rotorsim.harmonic_balance.bifurcation import BifurcationOptions, detect_bifurcations
from rotorsim.harmonic_balance.floquet import FloquetResult, hill
from rotorsim.harmonic_balance.fourier import FloatArray
from rotorsim.harmonic_balance.monodromy import hsu
from rotorsim.harmonic_balance.residual import (
    HBResidual,
    as_unknowns,
    continuation_function,
    make_residual,
)
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.hb.peaks import refine_peak
from rotorsim.hb.result import Bifurcation, FrequencyResponse, Point
from rotorsim.hb.scaling import linear_guess, unknown_scales
from rotorsim.hb.system import System
from rotorsim.solvers.continuation import Continuation, continue_branch

STABILITY = ("auto", "hill", "hsu")
HSU_STEPS = 128
"""Fewest steps per period of Hsu's method (the HB grid when finer)."""
HILL_LIMIT = 400
"""Largest ``(2H + 1) n`` for which ``stability="auto"`` uses Hill's method (dense
eigenproblem of twice that size at every point); Hsu's method above."""


def discretize(system: System, harmonics: int, samples: int | None = None) -> HBResidual:
    """The HB residual of ``system``: condensed onto the nonlinear DOFs when some DOFs are
    linear (when all are nonlinear the condensation would only add its per-frequency
    overhead).

    Raises
    ------
    ModelError
        For bad ``harmonics`` or ``samples``, or a forcing harmonic above ``harmonics``.
    """
    if not isinstance(system, System):
        raise ModelError(f"expected rotorsim.hb.System, got {type(system).__name__}",
                         "hb")
    top = max([0, *(f.harmonic for f in system.forcing)])
    if isinstance(harmonics, int | np.integer) and not isinstance(harmonics, bool) \
            and top > harmonics:
        raise ModelError(f"forcing at harmonic {top} needs harmonics >= {top}, got "
                         f"{harmonics}", "hb.harmonics")
    pb = system.problem
    return make_residual(pb, harmonics, samples=samples,
                         condense=0 < pb.k < pb.n)


def solve(system: System, omega: float, *, harmonics: int = 7, samples: int | None = None,
          x0: ArrayLike | None = None, tol: float = 1e-10) -> Point:
    """The periodic response at one frequency ``omega`` [rad/s].

    Parameters
    ----------
    system : System
    omega : float
        Response (fundamental) frequency [rad/s].
    harmonics, samples : int
        ``H`` and the AFT samples ``N`` (default ``2^ceil(log2(max(8 H, 16)))``).
    x0 : array, optional
        Start (``Point.x`` of a nearby solution); default the linear response.
    tol : float
        Newton tolerance on the residual scaled by the forcing.

    Raises
    ------
    ConvergenceError
        When Newton does not converge from ``x0``.

    Examples
    --------
    >>> from rotorsim.hb.elements import CubicSpring
    >>> duffing = System(1.0, 1.0, 0.05, elements=[CubicSpring(0, 0.1)], forcing=[0.18])
    >>> round(solve(duffing, 0.5, harmonics=3).amplitude(0), 6)
    0.23851
    """
    _check_frequency(omega, "omega")
    residual = discretize(system, harmonics, samples)
    start = linear_guess(residual, omega) if x0 is None else as_unknowns(x0, residual.size)
    scale = unknown_scales(residual, start)
    sol = solve_point(residual, omega, start, tol=tol, x_scale=scale)
    return Point(float(omega), sol.coefficients, residual.harmonics, residual.samples,
                 sol.residual, sol.x, sol.stats)


def frequency_response(system: System, start: float, stop: float, *, harmonics: int = 7,
                       samples: int | None = None, stability: str | bool | None = "auto",
                       bifurcations: bool = True, step: float | None = None,
                       max_step: float = 0.2, max_points: int = 1000, tol: float = 1e-10,
                       x0: ArrayLike | None = None) -> FrequencyResponse:
    """Continue the periodic response from ``start`` to ``stop`` [rad/s].

    Parameters
    ----------
    system : System
    start, stop : float
        Frequency range [rad/s]; either direction.
    harmonics, samples : int
        ``H`` and the AFT time samples ``N`` (module :mod:`~rotorsim.hb.response`).
    stability : {"auto", "hill", "hsu"}, bool or None
        Floquet method ("auto": Hill up to ``(2H + 1) n = 400``, Hsu above; True is
        "auto"); None or False skips stability (and period doubling / Neimark-Sacker).
    bifurcations : bool
        Locate folds, branch points and (with stability) period doublings and
        Neimark-Sacker points.
    step, max_step : float
        First and largest step in scaled arclength (frequency scaled by the range,
        unknowns by the linear response at ``start``).
    max_points : int
        Most points of the branch.
    tol : float
        Corrector tolerance (scaled residual).
    x0 : array, optional
        Start at ``start`` (``Point.x``); default the linear response.

    Returns
    -------
    FrequencyResponse
        Status OK when the branch reached ``stop`` or ``max_points``, else the reason it
        stopped (the points found are kept).

    Examples
    --------
    >>> from rotorsim.hb.elements import CubicSpring
    >>> duffing = System(1.0, 1.0, 0.05, elements=[CubicSpring(0, 0.1)], forcing=[0.18])
    >>> frf = frequency_response(duffing, 0.5, 1.6, harmonics=1)
    >>> peak = frf.peak(0)                    # single-harmonic closed form 2.84162 at 1.26663
    >>> round(peak.amplitude, 5), round(peak.omega, 5), [b.kind for b in frf.bifurcations]
    (2.84162, 1.26663, ['fold', 'fold'])
    """
    _check_frequency(start, "start")
    _check_frequency(stop, "stop")
    if start == stop:
        raise ModelError(f"start = stop = {start}: give a frequency range", "hb")
    method = _stability_method(stability, system, harmonics)
    clock = time.perf_counter()
    residual = discretize(system, harmonics, samples)
    guess = linear_guess(residual, start) if x0 is None else as_unknowns(x0, residual.size)
    fun = continuation_function(residual, "omega", terms=True)
    opts = _options(guess, residual, start, stop, step, max_step, max_points, tol)
    branch = continue_branch(fun, guess, start, opts)
    stats = dict(branch.stats)
    floquet = _Multipliers(residual, method)
    mult = floquet.at if method is not None else None
    t0 = time.perf_counter()
    stable = multipliers = None
    if method is not None:
        results = [floquet.result(x, w) for x, w in zip(branch.x, branch.lam, strict=True)]
        stable = np.array([r.stable for r in results])
        multipliers = np.array([r.multipliers for r in results])
    stats["stability_time"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    events = detect_bifurcations(fun, branch, multipliers=mult, options=BifurcationOptions(
        tol=1e-10)) if bifurcations and len(branch) > 1 else ()
    stats["bifurcation_time"] = time.perf_counter() - t0
    stats["total_time"] = time.perf_counter() - clock
    coefficients = np.array([residual.expand(x, w) for x, w in zip(branch.x, branch.lam,
                                                                       strict=True)])
    return FrequencyResponse(
        branch.lam.copy(), coefficients, residual.harmonics, residual.samples, stable,
        multipliers, tuple(_event(e, residual) for e in events), Status(branch.status),
        branch.reason, stats, method, branch,
        lambda i, dof, measure: refine_peak(fun, residual, branch, i, dof, measure))


class _Multipliers:
    """Floquet results of the branch points, each computed once (the bifurcation test
    functions ask again for the same points).

    Hill's exponents are picked by their eigenvectors (mean harmonic index), except at
    ``H = 1``, where the truncation at +-1 leaves too few harmonics to tell the copies
    apart and the smallest imaginary parts are taken (on the Duffing middle branch the
    eigenvector rule picks a stable complex pair there, the other rule the saddle's real
    multiplier 1.29 that ``H >= 2`` confirms). Hsu's method takes at least
    ``HSU_STEPS`` steps per period (its error is second order in the step)."""

    def __init__(self, residual: HBResidual, method: str | None) -> None:
        self.residual, self.method = residual, method
        self.cache: dict[tuple[float, bytes], FloquetResult] = {}

    def result(self, x: FloatArray, omega: float) -> FloquetResult:
        key = (float(omega), np.asarray(x).tobytes())
        if key not in self.cache:
            res = self.residual
            if self.method == "hsu":
                self.cache[key] = hsu(res, x, omega, samples=max(res.samples, HSU_STEPS))
            else:
                self.cache[key] = hill(res, x, omega, selection="imaginary"
                                       if res.harmonics == 1 else "eigenvector")
        return self.cache[key]

    def at(self, x: FloatArray, omega: float) -> Any:
        return self.result(x, omega).multipliers


def _options(guess: FloatArray, residual: HBResidual, start: float, stop: float,
             step: float | None, max_step: float, max_points: int,
             tol: float) -> Continuation:
    """Continuation options: unknowns scaled by the linear response at ``start``
    (:mod:`~rotorsim.hb.scaling`), frequency by the range."""
    span = abs(stop - start)
    first = min(step if step is not None else 0.25 * max_step, max_step)
    return Continuation(initial_step=first, max_step=max_step, min_step=min(1e-6, first),
                        max_points=max_points, tol=tol,
                        x_scale=tuple(unknown_scales(residual, guess)), r_scale="auto",
                        lam_scale=span, lam_min=min(start, stop), lam_max=max(start, stop),
                        direction=1 if stop > start else -1)


def _stability_method(stability: str | bool | None, system: System,
                      harmonics: int) -> str | None:
    if stability is None or stability is False:
        return None
    if stability is True:
        stability = "auto"
    if stability not in STABILITY:
        raise TypeError(f"unknown stability {stability!r}; valid: auto, hill, hsu, None")
    if stability == "auto":
        size = (2 * int(harmonics) + 1) * system.n
        return "hill" if size <= HILL_LIMIT else "hsu"
    return str(stability)


def _event(event: Any, residual: HBResidual) -> Bifurcation:
    crit = None
    if event.multipliers is not None and np.size(event.multipliers):
        mu = np.asarray(event.multipliers, dtype=complex)
        target = -1.0 if event.kind == "period_doubling" else None
        i = int(np.argmin(np.abs(mu + 1.0))) if target is not None else int(
            np.argmin(np.abs(np.abs(mu) - 1.0) + 10.0 * (np.abs(mu.imag) < 1e-9)))
        crit = complex(mu[i])
    return Bifurcation(event.kind, float(event.lam), residual.expand(event.x, event.lam),
                       int(event.index), bool(event.located), crit)


def _check_frequency(value: float, name: str) -> None:
    if not (isinstance(value, int | float | np.floating) and math.isfinite(value)
            and value > 0):
        raise ModelError(f"must be a positive finite frequency [rad/s], got {value!r}",
                         f"hb.{name}")
