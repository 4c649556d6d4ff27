"""Trace a solution branch of ``R(x, lam) = 0`` by pseudo-arclength continuation.

:func:`continue_branch` drives the :class:`~.continuation_stepper.Continuation` stepper
from a starting point to a bound, a closed loop, ``max_points`` or a failure, keeps every
point in a frozen :class:`Branch`, writes HDF5 checkpoints every N points and resumes from
them bit for bit. Bifurcation detection on the result lives in
:mod:`rotorsim.harmonic_balance.bifurcation`.

The problem is only a callback, so the same code continues a static equilibrium in a load
factor, a harmonic-balance residual in the excitation frequency, or a fold in a second
parameter.

References
----------
Seed 002 section 3.5.2.2, eqs 3.39-3.42 (arc-length continuation).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError, Status
from rotorsim.progress import progress_bar
from rotorsim.solvers.allocator import keep_freed_memory
from rotorsim.solvers.continuation_checkpoint import (
    load_continuation_checkpoint,
    save_continuation_checkpoint,
)
from rotorsim.solvers.continuation_core import FloatArray, ResidualCallback
from rotorsim.solvers.continuation_state import ContinuationCounters, ContinuationState
from rotorsim.solvers.continuation_stepper import Continuation
from rotorsim.solvers.threads import capped_by_size

__all__ = ["Branch", "Continuation", "ContinuationCounters", "ContinuationState",
           "continue_branch", "run_config"]

Monitor = Callable[[ContinuationState], "bool | None"]
"""``monitor(state)`` after each point; returning True ends the branch, raising aborts."""

_FIELDS = ("lam", "x", "tangents", "step_sizes", "iterations", "det_sign", "log_det",
           "smooth", "residuals")


@dataclass(frozen=True, eq=False)
class Branch:
    """A traced solution branch.

    Attributes
    ----------
    lam : array (P,)
        Parameter at each point.
    x : array (P, m)
        Unknowns at each point.
    tangents : array (P, m + 1)
        Unit tangents in scaled unknowns (see :class:`ContinuationState`).
    step_sizes : array (P,)
        Scaled arclength of the step that reached each point (0 for the first).
    iterations : int array (P,)
        Corrector iterations of the accepted step to each point.
    det_sign : int array (P,)
        Sign of the determinant of the bordered Jacobian (0 where unknown).
    log_det : array (P,)
        ``log |det|`` of the bordered Jacobian in scaled unknowns.
    smooth : bool array (P,)
        False at corners and where the tangent solve failed (secant predictor next).
    residuals : array (P,)
        ``max |R / r_scale|`` at each point.
    x_scale, r_scale : arrays (m,)
    lam_scale : float
    status : Status
        OK when the branch ended on a bound, closed, or used up ``max_points``.
    reason : str
        Why the branch ended.
    stats : dict
        ``points``, ``residual_evaluations``, ``factorizations``, ``solves``,
        ``iterations``, ``rejected_steps``, ``secant_predictions``, ``max_iterations``,
        ``iterations_per_point``, ``wall_time`` [s] (this call only).
    options : Continuation
    state : ContinuationState
        Last state (continue from it with ``options.step``).
    events : tuple
        Bifurcation events (filled by ``Branch.with_events``).
    """

    lam: FloatArray
    x: FloatArray
    tangents: FloatArray
    step_sizes: FloatArray
    iterations: NDArray[np.int64]
    det_sign: NDArray[np.int64]
    log_det: FloatArray
    smooth: NDArray[np.bool_]
    residuals: FloatArray
    x_scale: FloatArray
    r_scale: FloatArray
    lam_scale: float
    status: Status
    reason: str
    stats: dict[str, float]
    options: Continuation
    state: ContinuationState
    events: tuple[Any, ...] = ()

    def __len__(self) -> int:
        return int(self.lam.size)

    def scaled(self) -> FloatArray:
        """Points in scaled unknowns ``(x / x_scale, lam / lam_scale)`` (P, m + 1)."""
        return np.column_stack([self.x / self.x_scale, self.lam / self.lam_scale])

    def arclength(self) -> FloatArray:
        """Cumulative chord length of the branch in scaled unknowns (P,)."""
        chords = np.linalg.norm(np.diff(self.scaled(), axis=0), axis=1)
        return np.concatenate([[0.0], np.cumsum(chords)])

    def with_events(self, events: tuple[Any, ...]) -> Branch:
        """Copy of the branch carrying ``events`` (e.g. from ``detect_bifurcations``)."""
        return dataclasses.replace(self, events=tuple(events))


@capped_by_size(lambda residual, x0, *_, **__: np.size(x0))
def continue_branch(residual: ResidualCallback, x0: ArrayLike, lam0: float,
                    options: Continuation | None = None, *,
                    checkpoint: str | os.PathLike[str] | None = None,
                    checkpoint_every: int = 25,
                    resume: str | os.PathLike[str] | None = None, progress: bool = False,
                    monitor: Monitor | None = None,
                    orientation: ArrayLike | None = None) -> Branch:
    """Trace the branch of ``residual(x, lam) = 0`` through ``(x0, lam0)``.

    Parameters
    ----------
    residual : callable
        ``residual(x, lam) -> (R (m,), dR/dx (m, m) dense or sparse, dR/dlam (m,))``.
        An exception it raises (ValueError, ArithmeticError, LinAlgError, RotorsimError)
        or a non-finite value counts as a failed evaluation and cuts the step.
    x0 : array-like (m,)
        Starting guess, corrected at fixed ``lam0``.
    lam0 : float
        Starting parameter.
    options : Continuation, optional
    checkpoint : path, optional
        HDF5 file rewritten atomically every ``checkpoint_every`` points and at the end
        (its folder is created; a folder or an uncreatable path is a ModelError).
    resume : path, optional
        Continue from this checkpoint (same options and start, else
        :class:`~rotorsim.errors.CheckpointError`); the branch equals
        that of an uninterrupted run bit for bit.
    progress : bool
        Show a tqdm bar over points.
    monitor : callable, optional
        ``monitor(state)`` after each point (after its checkpoint); True ends the branch,
        an exception aborts the run (the last checkpoint stays).
    orientation : array-like (m + 1,), optional
        Leave the start along ``(dx, dlam)`` instead of ``options.direction`` in ``lam``
        (:meth:`Continuation.init`; e.g. off a bifurcation point, see
        :mod:`~rotorsim.solvers.continuation_switch`).

    Returns
    -------
    Branch
        Every point found, with status OK (bound, closed loop, ``max_points``, monitor)
        or a failure status when the step fell below ``min_step``.

    Raises
    ------
    ModelError
        For invalid inputs.
    ConvergenceError
        If the starting point does not converge.

    Examples
    --------
    >>> def fold(x, lam):  # x^3 - x + lam = 0, an S-curve
    ...     return x**3 - x + lam, np.diag(3 * x**2 - 1), np.ones(1)
    >>> opts = Continuation(initial_step=0.05, max_step=0.1, direction=-1, lam_min=-1.0,
    ...                     lam_max=1.0)
    >>> b = continue_branch(fold, [-1.3], 1.0, opts)
    >>> b.status.name, b.reason, float(b.lam[-1])
    ('OK', 'lam_min = -1 reached', -1.0)
    >>> int(np.sum(np.diff(np.sign(b.tangents[:, -1])) != 0))  # two folds passed
    2
    """
    opts = options if options is not None else Continuation()
    keep_freed_memory()      # the corrector's work arrays: no page faults per iteration
    if int(checkpoint_every) != checkpoint_every or checkpoint_every < 1:
        raise ModelError(f"checkpoint_every must be a positive integer, got "
                         f"{checkpoint_every!r}", "continue_branch")
    if checkpoint is not None:
        _prepare_target(Path(checkpoint))
    x_start = np.array(x0, dtype=float).reshape(-1)
    config = run_config(opts, x_start, float(lam0))
    clock = time.perf_counter()
    if resume is not None:
        state, saved, _ = load_continuation_checkpoint(resume, config=config)
        history = {name: list(saved[name]) for name in _FIELDS}
    else:
        state = opts.init(residual, x_start, float(lam0), orientation=orientation)
        history = {name: [] for name in _FIELDS}
        _record(history, state)
    bar = progress_bar(progress, total=opts.max_points, initial=len(history["lam"]),
                       desc="continuation", unit="pt")
    try:
        while not state.finished:
            if len(history["lam"]) >= opts.max_points:
                state = dataclasses.replace(state, finished=True, reason="max_points reached")
                break
            previous = state.point
            state = opts.step(residual, state)
            if state.point > previous:
                _record(history, state)
                if bar is not None:
                    bar.update(1)
                    bar.set_postfix(lam=f"{state.lam:.6g}")
            if checkpoint is not None and (state.point % checkpoint_every == 0):
                save_continuation_checkpoint(checkpoint, state, branch=_arrays(history),
                                             config=config)
            if monitor is not None and state.point > previous and monitor(state):
                state = dataclasses.replace(state, finished=True, reason="stopped by monitor")
    finally:
        if bar is not None:
            bar.close()
    if checkpoint is not None:
        save_continuation_checkpoint(checkpoint, state, branch=_arrays(history), config=config)
    arrays = _arrays(history)
    return Branch(**arrays, x_scale=state.x_scale, r_scale=state.r_scale,
                  lam_scale=state.lam_scale, status=Status(state.status), reason=state.reason,
                  stats=_stats(state.counters, len(history["lam"]),
                               time.perf_counter() - clock),
                  options=opts, state=state)


def _prepare_target(path: Path) -> None:
    """Create the checkpoint's folder (as the CLI does for its results folder) before any
    work, or refuse a path that cannot hold a file."""
    where = "continue_branch.checkpoint"
    if path.is_dir():
        raise ModelError(f"{str(path)!r} is a folder; give a file name", where)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ModelError(f"cannot create the folder of {str(path)!r} "
                         f"({type(exc).__name__}: {exc.strerror or exc})", where) from exc


def _record(history: dict[str, list[Any]], state: ContinuationState) -> None:
    row = (state.lam, state.x, state.tangent, state.last_step, state.iterations,
           state.det_sign, state.log_det, state.smooth, state.residual)
    for name, value in zip(_FIELDS, row, strict=True):
        history[name].append(value)


def _arrays(history: dict[str, list[Any]]) -> dict[str, Any]:
    kinds: dict[str, Any] = {"iterations": np.int64, "det_sign": np.int64, "smooth": bool}
    out = {name: np.array(values, dtype=kinds.get(name, float))
           for name, values in history.items()}
    return out


def run_config(options: Continuation, x0: FloatArray, lam0: float) -> dict[str, Any]:
    """JSON-able identity of a run, stored in checkpoints and compared on resume."""
    h = hashlib.blake2b(digest_size=8)
    h.update(x0.tobytes())
    h.update(np.float64(lam0).tobytes())
    return json.loads(json.dumps({"m": int(x0.size), "start": h.hexdigest(),
                                  "options": dataclasses.asdict(options)}))


def _stats(counters: ContinuationCounters, points: int, wall_time: float) -> dict[str, float]:
    out: dict[str, float] = {"points": points, **dataclasses.asdict(counters)}
    out["iterations_per_point"] = counters.iterations / max(points - 1, 1)
    out["wall_time"] = wall_time
    return out
