"""Drive a stepper over a time span: output, checkpoints, resume and progress.

``integrate`` owns everything that is not one step: clipping the last step onto the end of
the span, handing each accepted step to the output recorder, writing checkpoints every N
steps, continuing from a checkpoint or from the final state of an earlier run, stopping
early when a predicate says so (e.g. once the response is steady, :mod:`~.steady`), the
progress bar and the final result with its stats.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.progress import progress_bar
from rotorsim.solvers.threads import one_blas_thread
from rotorsim.time_integration.base import (
    Counters,
    FloatArray,
    IntArray,
    State,
    TimeStepper,
)
from rotorsim.time_integration.checkpoint import load_checkpoint, save_checkpoint
from rotorsim.time_integration.output import OutputRecorder, OutputSpec
from rotorsim.time_integration.problem import SecondOrderProblem

LAST_STEP_SLACK = 1e-7
"""Relative tolerance on the step size within which the last step lands on ``t_end``:
round-off accumulated in ``t`` never leaves a sliver step or costs a factorisation."""

TIME_BAR = "{desc}: {percentage:3.0f}%|{bar}| t = {n:.4g}/{total:.4g} s [{elapsed}<{remaining}]"
"""Layout of the progress bar over simulated time."""


@dataclass(frozen=True, eq=False)
class IntegrationResult:
    """Samples and cost of a time integration.

    Attributes
    ----------
    t : array (k,)
        Sample times [s].
    q : array (k, m)
        Kept unknowns at the sample times.
    v : array (k, len(v_dofs)) or None
        Velocities of the unknowns ``v_dofs`` (None when no velocities are kept).
    dofs : int array (m,)
        Indices of the kept unknowns.
    reduced : dict of str to array
        Reducer values (see :class:`~.output.Reducer`).
    state : State
        Final stepper state (continue from it, or inspect ``q``, ``v`` of all unknowns).
    stats : dict
        ``steps``, ``rejected_steps``, ``newton_failures``, ``factorizations``, ``solves``,
        ``residual_evaluations``, ``iterations``, ``max_iterations``,
        ``iterations_per_step``, ``wall_time`` [s] (of this call only).
    status : Status
        ``OK``, or ``NOT_CONVERGED`` when a step failed under ``on_failure="stop"`` (the
        samples then end at the last accepted step).
    method : str
        Stepper name.
    message : str
        Why the run failed short of ``t_end`` ("" when it did not fail).
    v_dofs : int array or None
        Indices of the unknowns whose velocities ``v`` holds (None when ``v`` is None).
    stopped : str
        Why ``stop_when`` ended the run before ``t_end`` ("" when it did not).
    """

    t: FloatArray
    q: FloatArray
    v: FloatArray | None
    dofs: IntArray
    reduced: dict[str, FloatArray]
    state: State
    stats: dict[str, float]
    status: Status
    method: str
    message: str = ""
    v_dofs: IntArray | None = None
    stopped: str = ""


@one_blas_thread()
def integrate(problem: SecondOrderProblem, stepper: TimeStepper, t_span: Sequence[float],
              q0: ArrayLike | None, v0: ArrayLike | None, *, dt: float,
              output: OutputSpec | None = None,
              a0: ArrayLike | None = None, checkpoint: str | os.PathLike[str] | None = None,
              checkpoint_every: int = 1000, resume: str | os.PathLike[str] | None = None,
              progress: bool = False,
              callback: Callable[[State], None] | None = None,
              on_failure: str = "raise", start: State | None = None,
              stop_when: Callable[[State], str | bool | None] | None = None
              ) -> IntegrationResult:
    """Integrate ``M a + (C + s G) v + K q + r(q, v, t) = f(t)`` over ``t_span``.

    Parameters
    ----------
    problem : SecondOrderProblem
    stepper : TimeStepper
        E.g. ``Newmark.average_acceleration()`` or ``Adaptive(Newmark.hht(-0.1))``.
    t_span : (t0, t_end)
        Time span [s], ``t_end > t0``.
    q0, v0 : array-like (n,) or None
        Initial displacements and velocities (None with ``start``).
    dt : float
        Step size (first trial step for an adaptive stepper) [s].
    output : OutputSpec, optional
        What to keep (default: every step, all unknowns). The run always ends at ``t_end``
        (the last step is shortened when ``dt`` does not divide the span) and, with
        ``every``, the final state is always kept.
    a0 : array-like (n,), optional
        Initial acceleration (default: solved from the equation of motion).
    checkpoint : path, optional
        HDF5 file written at the start and rewritten atomically every
        ``checkpoint_every`` accepted steps and at the end.
    resume : path, optional
        Continue from this checkpoint (same problem, stepper, span, dt, output and initial
        state, else :class:`~rotorsim.errors.CheckpointError`); the samples, reductions and
        final state equal those of an uninterrupted run bit for bit (the cost counters add
        one factorisation: the LU factors are not stored).
    progress : bool
        Show a tqdm progress bar over simulated time.
    callback : callable, optional
        ``callback(state)`` after each accepted step (and its checkpoint); an exception
        it raises stops the run.
    on_failure : {"raise", "stop"}
        When a step fails: raise :class:`~rotorsim.errors.ConvergenceError`, or end the run
        at the last accepted step and return what was computed with status
        ``NOT_CONVERGED`` and the error in ``message`` (the checkpoint then holds the
        last accepted step).
    start : State, optional
        Continue from this state of an earlier run (``state`` of its result) instead of
        calling ``stepper.init``: its arrays, multistep history and factorisation keys are
        taken as they are, so the run goes on as if never interrupted; ``start.t`` must be
        ``t0`` and ``start.dt`` is the next step. Its counters restart at zero, so ``stats``
        count this call only (``steps`` too).
    stop_when : callable, optional
        ``stop_when(state)`` after each accepted step (after ``callback``): a non-empty
        string or True ends the run there, with status ``OK``, the final state kept and the
        reason in ``stopped``.

    Returns
    -------
    IntegrationResult

    Raises
    ------
    ModelError
        For invalid inputs (checked before the first step).
    ConvergenceError
        When a step fails and ``on_failure="raise"`` (time, step, iteration and worst DOF
        in the message); the last checkpoint is left in place.

    Examples
    --------
    >>> from rotorsim.time_integration.newmark import Newmark
    >>> p = SecondOrderProblem(mass=np.eye(1), stiffness=np.eye(1))
    >>> res = integrate(p, Newmark(), (0.0, np.pi), [1.0], [0.0], dt=np.pi / 200)
    >>> float(res.t[-1]) == np.pi, round(float(res.q[-1, 0]), 10)  # cos(pi), phase lag
    (True, -0.9999999979)
    >>> int(res.stats["steps"]), int(res.stats["factorizations"])   # M once, S once
    (200, 2)
    """
    t0, t_end = _span(t_span)
    if not (math.isfinite(dt) and dt > 0):
        raise ModelError(f"dt must be positive and finite, got {dt!r}", "integrate")
    if int(checkpoint_every) != checkpoint_every or checkpoint_every < 1:
        raise ModelError(f"checkpoint_every must be a positive integer, got "
                         f"{checkpoint_every!r}", "integrate")
    if on_failure not in ("raise", "stop"):
        raise ModelError(f"on_failure must be 'raise' or 'stop', got {on_failure!r}",
                         "integrate")
    spec = output if output is not None else OutputSpec()
    spec.check(problem.n, t0, t_end)
    if start is not None:
        start = _checked_start(start, problem.n, t0)
        q0, v0, a0 = start.q, start.v, start.a
    # the run's identity only where a checkpoint stores or checks it (hashing the
    # matrices and the stepper's options costs about 1 ms, a tenth of a short run)
    config = {} if checkpoint is None and resume is None else run_config(
        problem, stepper, (t0, t_end), dt, spec, (q0, v0, a0))
    clock = time.perf_counter()
    first_step = 0 if start is None else start.step
    if resume is not None:
        state, saved, _ = load_checkpoint(resume, config=config)
        recorder = OutputRecorder(spec, problem.n, saved)
    else:
        state = start if start is not None else stepper.init(
            problem, t0, np.asarray(q0, dtype=float), np.asarray(v0, dtype=float), dt=dt,
            a0=None if a0 is None else np.asarray(a0, dtype=float))
        recorder = OutputRecorder(spec, problem.n)
        recorder.start(state)
        if checkpoint is not None:
            save_checkpoint(checkpoint, state, config=config, output=recorder.snapshot())
    bar = progress_bar(progress, total=t_end - t0, initial=state.t - t0, desc=stepper.name,
                       unit="s", bar_format=TIME_BAR)
    status, message, stopped = Status.OK, "", ""
    try:
        while state.t < t_end:
            try:
                old, state = state, _advance(problem, stepper, state, t_end)
            except ConvergenceError as exc:
                if on_failure == "raise":
                    raise
                status, message = Status.NOT_CONVERGED, str(exc)
                break
            recorder.record(stepper, old, state)
            if bar is not None:
                bar.update(state.t - old.t)
            if checkpoint is not None and state.step % checkpoint_every == 0:
                save_checkpoint(checkpoint, state, config=config, output=recorder.snapshot())
            if callback is not None:
                callback(state)
            if stop_when is not None:
                reason = stop_when(state)
                if reason:
                    stopped = reason if isinstance(reason, str) else "stop_when"
                    break
    finally:
        if bar is not None:
            bar.close()
    added = recorder.finish(state)
    if checkpoint is not None and (added or state.step % checkpoint_every != 0):
        save_checkpoint(checkpoint, state, config=config, output=recorder.snapshot())
    t, q, v = recorder.arrays()
    return IntegrationResult(t, q, v, recorder.dofs, recorder.reduced, state,
                             _stats(state, time.perf_counter() - clock, first_step), status,
                             stepper.name, message, recorder.velocity_dofs, stopped)


def run_config(problem: SecondOrderProblem, stepper: TimeStepper, t_span: tuple[float, float],
               dt: float, spec: OutputSpec, initial: tuple[Any, Any, Any]) -> dict[str, Any]:
    """JSON-able identity of a run, stored in checkpoints and compared on resume."""
    options = (dataclasses.asdict(stepper) if dataclasses.is_dataclass(stepper)
               else repr(stepper))
    h = hashlib.blake2b(digest_size=8)
    for x in initial:
        h.update(b"-" if x is None else np.asarray(x, dtype=float).tobytes())
    return json.loads(json.dumps({
        "n": problem.n, "problem": problem.fingerprint, "t_span": list(t_span), "dt": dt,
        "stepper": {"type": type(stepper).__name__, "options": options},
        "output": spec.describe(), "initial": h.hexdigest()}, default=str))


def _advance(problem: SecondOrderProblem, stepper: TimeStepper, state: State,
             t_end: float) -> State:
    """One accepted step; the last one ends exactly at ``t_end``.

    When the remaining interval equals ``state.dt`` up to the round-off accumulated in
    ``t`` (relative ``LAST_STEP_SLACK``), the step keeps ``state.dt`` (and its
    factorisation) and its end time is set to ``t_end``; a shorter remainder is one
    clipped step.
    """
    remaining = t_end - state.t
    if remaining > state.dt * (1.0 + LAST_STEP_SLACK):
        return stepper.step(problem, state)
    if remaining < state.dt * (1.0 - LAST_STEP_SLACK):
        state = dataclasses.replace(state, dt=remaining)
    new = stepper.step(problem, state)
    if abs(new.t - t_end) <= LAST_STEP_SLACK * state.dt:
        new = dataclasses.replace(new, t=t_end)
    return new


def _span(t_span: Sequence[float]) -> tuple[float, float]:
    try:
        t0, t_end = (float(x) for x in t_span)
    except (TypeError, ValueError) as exc:
        raise ModelError(f"t_span must be (t0, t_end), got {t_span!r}", "integrate") from exc
    if not (math.isfinite(t0) and math.isfinite(t_end) and t_end > t0):
        raise ModelError(f"t_span must be finite with t_end > t0, got {t_span!r}", "integrate")
    return t0, t_end


def _checked_start(start: State, n: int, t0: float) -> State:
    """``start`` with its counters reset, after checking its size and time."""
    if not isinstance(start, State):
        raise ModelError(f"start must be a State, got {type(start).__name__}", "integrate")
    if start.q.shape != (n,):
        raise ModelError(f"start has {start.q.size} unknowns, the problem {n}",
                         "integrate.start")
    if start.t != t0:
        raise ModelError(f"start is at t = {start.t!r} s, the span begins at {t0!r} s",
                         "integrate.start")
    return dataclasses.replace(start, counters=Counters(), cache=None)


def _stats(state: State, wall_time: float, first_step: int = 0) -> dict[str, float]:
    steps = state.step - first_step
    out: dict[str, float] = {"steps": steps, **dataclasses.asdict(state.counters)}
    out["iterations_per_step"] = state.counters.iterations / max(steps, 1)
    out["wall_time"] = wall_time
    return out
