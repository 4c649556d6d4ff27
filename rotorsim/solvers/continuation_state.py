"""Continuation state, cost counters and the scales of a run.

A :class:`ContinuationState` holds only numbers and arrays (DESIGN section 6), so
:mod:`~rotorsim.solvers.continuation_checkpoint` writes it to HDF5 and a run resumes bit for
bit. The scales ("auto" or given) are resolved once at the starting point and stored in the
state, so a resumed run measures its arclength exactly as before.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.solvers.continuation_core import FloatArray, ResidualCallback, ScaledSystem
from rotorsim.solvers.stats import Stats

Scale = float | tuple[float, ...] | Literal["auto"]
"""A scale option: a positive number, one per unknown, or "auto"."""


@dataclass(frozen=True)
class ContinuationCounters:
    """Cost counters of a continuation run (STYLE practice 8)."""

    residual_evaluations: int = 0
    factorizations: int = 0
    solves: int = 0
    iterations: int = 0
    rejected_steps: int = 0
    secant_predictions: int = 0
    max_iterations: int = 0
    relaxed_points: int = 0

    def plus(self, stats: Stats, *, rejected: int = 0, secant: int = 0,
             point_iterations: int = 0, relaxed: int = 0) -> ContinuationCounters:
        """Counters after a step that used ``stats`` and the given extra counts."""
        return ContinuationCounters(
            self.residual_evaluations + stats.residual_evaluations,
            self.factorizations + stats.factorizations, self.solves + stats.solves,
            self.iterations + stats.iterations, self.rejected_steps + rejected,
            self.secant_predictions + secant, max(self.max_iterations, point_iterations),
            self.relaxed_points + relaxed)


@dataclass(frozen=True, eq=False)
class ContinuationState:
    """A point of the branch and everything needed to take the next step.

    Attributes
    ----------
    x : array (m,)
        Unknowns at the point.
    lam : float
        Continuation parameter at the point.
    tangent : array (m + 1,)
        Unit tangent in scaled unknowns ``(dx / x_scale, dlam / lam_scale) / ds`` (the
        secant when the tangent solve failed), oriented along the direction of travel.
    predictor : array (m + 1,)
        Unit direction of the next predictor (``tangent``, or the secant after a corner).
    step_size : float
        Scaled arclength ``ds`` of the next step.
    point : int
        Index of this point on the branch (0 for the corrected starting point).
    iterations : int
        Corrector iterations spent on the accepted step to this point.
    last_step : float
        Scaled arclength of the step that reached this point (0 for the first).
    smooth : bool
        False at a corner or where the tangent solve failed.
    det_sign : int
        Sign of ``det [[dR/dy], [t^T]]`` (0 when unknown): changes at a branch point.
    log_det : float
        ``log |det|`` of the same matrix (scaled unknowns).
    residual : float
        ``max |R / r_scale|`` at the point.
    x_scale, r_scale : arrays (m,)
        Scales of the unknowns and residual used by the run (resolved from "auto").
    lam_scale : float
    origin, origin_tangent : arrays (m + 1,)
        Scaled first point and its tangent, to recognise a closed branch.
    counters : ContinuationCounters
    status : int
        A :class:`rotorsim.errors.Status` value.
    finished : bool
        True when the branch ended (bound, closed loop, failure).
    reason : str
        Why the branch ended ("" while running).
    shrinks : int
        Consecutive steps that were cut before they were accepted, each shorter than the
        last (the branch approaches a singular point; see :mod:`.continuation_stepper`).
    """

    x: FloatArray
    lam: float
    tangent: FloatArray
    predictor: FloatArray
    step_size: float
    point: int
    iterations: int
    last_step: float
    smooth: bool
    det_sign: int
    log_det: float
    residual: float
    x_scale: FloatArray
    r_scale: FloatArray
    lam_scale: float
    origin: FloatArray
    origin_tangent: FloatArray
    counters: ContinuationCounters = ContinuationCounters()
    status: int = int(Status.OK)
    finished: bool = False
    reason: str = ""
    shrinks: int = 0

    def system(self, residual: ResidualCallback) -> ScaledSystem:
        """The residual in this run's scaled unknowns."""
        return ScaledSystem(residual, self.x_scale, self.r_scale, self.lam_scale)


def resolve_scales(residual: ResidualCallback, x0: FloatArray, lam0: float, x_scale: Scale,
                   r_scale: Scale, lam_scale: float | str,
                   stats: Stats) -> tuple[FloatArray, FloatArray, float]:
    """Scales of a run, resolving "auto" at the starting point.

    "auto" means ``max |x0|`` for ``x``, ``|lam0|`` (1 if zero) for ``lam`` and, for the
    residual, the row norms ``max_j |dR_i/dx_j| x_scale_j`` at ``(x0, lam0)`` (one extra
    evaluation, counted in ``stats``). At a zero start ``x0 = 0`` the size of the unknowns
    is ``max |dx|`` of the Newton step ``dR/dx dx = -R`` from ``(0, lam0)``
    (:func:`_newton_step_size`; for a harmonic-balance residual that is the response of the
    underlying linear system), 1 only when that step is zero or cannot be computed.
    """
    m = x0.size
    x_auto = float(np.max(np.abs(x0)))
    if isinstance(x_scale, str) and x_auto == 0.0:
        x_auto = _newton_step_size(residual, x0, lam0, stats)
    xs = _as_vector("x_scale", x_scale, m, x_auto)
    ls = (abs(lam0) or 1.0) if lam_scale == "auto" else float(lam_scale)
    if r_scale != "auto":
        return xs, _as_vector("r_scale", r_scale, m, 1.0), ls
    probe = ScaledSystem(residual, xs, np.ones(m), ls)
    jh = probe.evaluate(probe.to_y(x0, lam0), stats).jh
    rows = np.asarray(abs(jh).max(axis=1).toarray()).ravel() if sp.issparse(jh) \
        else np.max(np.abs(jh), axis=1)
    fallback = float(np.max(rows)) or 1.0
    return xs, np.where(rows > 0.0, rows, fallback), ls


def _newton_step_size(residual: ResidualCallback, x0: FloatArray, lam0: float,
                      stats: Stats) -> float:
    """``max |dx|`` of the Newton step ``dR/dx dx = -R`` at ``(x0, lam0)`` (one evaluation
    and one factorisation, counted in ``stats``); 0 when the step is zero, not finite, or
    the Jacobian is singular."""
    m = x0.size
    probe = ScaledSystem(residual, np.ones(m), np.ones(m), 1.0)
    try:
        ev = probe.evaluate(probe.to_y(x0, lam0), stats)
        stats.factorizations += 1
        with warnings.catch_warnings():     # a singular sparse matrix warns, returns NaN
            warnings.simplefilter("ignore", spla.MatrixRankWarning)
            step = (spla.spsolve(sp.csc_matrix(ev.jh), -ev.rh) if sp.issparse(ev.jh)
                    else np.linalg.solve(ev.jh, -ev.rh))
    except (ConvergenceError, np.linalg.LinAlgError, ValueError, RuntimeError):
        return 0.0
    size = float(np.max(np.abs(step), initial=0.0))
    return size if np.isfinite(size) else 0.0


def checked_scale(name: str, value: object) -> float | tuple[float, ...] | str:
    """A scale option as stored: "auto", a positive float, or a tuple of them.

    Raises
    ------
    ModelError
        For anything else (the message names the option).
    """
    if isinstance(value, str):
        if value != "auto":
            raise ModelError(f"{name} must be 'auto' or positive numbers, got {value!r}",
                             "Continuation")
        return value
    arr = np.asarray(value, dtype=float)
    if arr.ndim > 1 or arr.size == 0 or not (np.all(np.isfinite(arr)) and np.all(arr > 0)):
        raise ModelError(f"{name} must be positive and finite, got {value!r}", "Continuation")
    if name == "lam_scale" and arr.ndim:
        raise ModelError("lam_scale must be a number or 'auto'", "Continuation")
    return float(arr) if arr.ndim == 0 else tuple(float(v) for v in arr)


def _as_vector(name: str, value: float | Sequence[float] | str, m: int,
               auto: float) -> FloatArray:
    if isinstance(value, str):
        return np.full(m, auto if auto > 0.0 else 1.0)
    arr = np.asarray(value, dtype=float)
    if arr.ndim and arr.size != m:
        raise ModelError(f"{name} has {arr.size} entries for {m} unknowns", "Continuation")
    return np.broadcast_to(arr, (m,)).astype(float)
