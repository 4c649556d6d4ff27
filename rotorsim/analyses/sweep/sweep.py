"""Parameter sweeps: evaluate a model over a grid or a random sample of its parameters.

A sweep is a base rotor, a parameter space (:class:`Grid` or :class:`Sample`), an
``apply(rotor, params) -> Rotor`` function that builds the model of one point and an
``evaluate(rotor, params) -> dict`` function that analyses it. Points run serially, in
local processes or on a dask.distributed cluster; the process that called :func:`sweep`
stores each point as it arrives (workers never touch the store), so an interrupted
sweep keeps every finished point and resumes from there.
"""

from __future__ import annotations

import concurrent.futures as cf
import functools
import multiprocessing
import os
import pickle
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.io.sweep_store import StoreHeader, content_hash, describe_callable, open_store
from rotorsim.model.rotor import Rotor
from rotorsim.progress import progress_bar
from rotorsim.results.sweep import Grid, Normal, PointRecord, Sample, SweepResult, Uniform
from rotorsim.solvers.threads import one_blas_thread

__all__ = [
    "Grid", "Normal", "Sample", "SweepResult", "Uniform", "chain", "critical_speeds_eval",
    "min_log_dec", "scale_bearing_stiffness", "scale_disk_mass", "set_bearing_stiffness",
    "sweep",
]
# the ready-made model and evaluate functions live in sweep_functions; re-exported here
from rotorsim.analyses.sweep.functions import (
    chain,
    critical_speeds_eval,
    min_log_dec,
    scale_bearing_stiffness,
    scale_disk_mass,
    set_bearing_stiffness,
)

Params = Mapping[str, float]
Apply = Callable[[Rotor, Params], Rotor]
Evaluate = Callable[[Rotor, Params], Mapping[str, Any]]
EXECUTORS = ("serial", "process")
ON_FAILURE = ("record", "raise")


@dataclass(frozen=True, eq=False)
class SweepDefinition:
    """Everything a worker needs to evaluate a point (sent once to each worker)."""

    rotor: Rotor
    apply: Apply | None
    evaluate: Evaluate
    on_failure: str


@one_blas_thread()  # each sweep worker runs its points with one BLAS thread
def evaluate_point(definition: SweepDefinition, index: int, params: Params) -> PointRecord:
    """Build and evaluate the model of one point; record model and convergence failures."""
    t0 = time.perf_counter()
    try:
        rotor = definition.rotor
        if definition.apply is not None:
            rotor = definition.apply(rotor, params)
            if not isinstance(rotor, Rotor):
                raise TypeError(f"apply must return a Rotor, got {type(rotor).__name__}")
        outputs = definition.evaluate(rotor, params)
    except (ConvergenceError, ModelError) as exc:
        if definition.on_failure == "raise":
            raise
        status = Status.NOT_CONVERGED if isinstance(exc, ConvergenceError) else Status.FAILED
        return PointRecord(index, None, status, f"{type(exc).__name__}: {exc}",
                           time.perf_counter() - t0)
    if not isinstance(outputs, Mapping):
        raise TypeError(f"evaluate must return a dict name -> value, got {outputs!r}")
    arrays = {str(k): np.asarray(v) for k, v in outputs.items()}
    return PointRecord(index, arrays, Status.OK, "", time.perf_counter() - t0)


@one_blas_thread()  # serial and threaded workers: the cap is set once per sweep
def sweep(
    rotor: Rotor,
    space: Grid | Sample,
    apply: Apply | None,
    evaluate: Evaluate,
    *,
    store: str | os.PathLike[str] | None = None,
    executor: Any = "serial",
    max_workers: int | None = None,
    resume: bool = True,
    progress: bool = False,
    on_failure: str = "record",
) -> SweepResult:
    """Evaluate a model at every point of a parameter space.

    Point ``i`` has parameters ``space.point(i)``; its model is ``apply(rotor, params)``
    (``rotor`` itself when ``apply`` is None) and its outputs ``evaluate(model, params)``,
    a dict of numbers or arrays with the same names and shapes at every point.

    Parameters
    ----------
    rotor : Rotor
        Base model.
    space : Grid or Sample
        The points.
    apply : callable or None
        ``apply(rotor, params) -> Rotor``, e.g. :func:`set_bearing_stiffness`.
    evaluate : callable
        ``evaluate(rotor, params) -> dict``, e.g. :func:`min_log_dec`.
    store : path, optional
        HDF5 file written point by point (layout in :mod:`rotorsim.io.sweep_store`).
    executor : "serial", "process", dask.distributed.Client or executor
        Where points run: here, in ``max_workers`` local processes (spawned: ``apply`` and
        ``evaluate`` must be picklable, i.e. module-level functions or
        :func:`functools.partial` of them), on a dask cluster, or on any
        :class:`concurrent.futures.Executor` (or object with ``map``) you pass.
    max_workers : int, optional
        Number of local processes (default: CPU count); for other executors, the number
        of points kept in flight is twice this (default: twice the cluster's threads).
    resume : bool
        With an existing ``store`` of the same sweep, evaluate only the points not yet
        stored; a store of a different sweep raises :class:`ModelError`. ``False``
        overwrites the store.
    progress : bool
        Show a progress bar (tqdm).
    on_failure : {"record", "raise"}
        A :class:`ModelError` or :class:`ConvergenceError` inside ``apply``/``evaluate``
        is recorded (status, message, NaN outputs) or raised. Other exceptions always
        propagate; points stored before them are kept.

    Returns
    -------
    SweepResult

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    >>> rotor = rs.Rotor(shaft, [], [rs.BearingElement(n=0, kxx=1e6, cxx=500.0),
    ...                              rs.BearingElement(n=4, kxx=1e6, cxx=500.0)])
    >>> res = sweep(rotor, Grid({"bearing_k": [1e6, 1e7], "speed": [0.0, 100.0]}),
    ...             set_bearing_stiffness([0, 1]), min_log_dec(num_modes=2))
    >>> res.reshape("log_dec_min").shape, bool(np.all(res.outputs["log_dec_min"] > 0))
    ((2, 2), True)
    """
    _check_inputs(rotor, space, apply, evaluate, max_workers, on_failure)
    t0 = time.perf_counter()
    definition = SweepDefinition(rotor, apply, evaluate, on_failure)
    _check_executor(executor, definition)
    header = StoreHeader(space, {
        "rotor": content_hash(rotor), "rotor_summary": rotor.summary(),
        "apply": describe_callable(apply), "evaluate": describe_callable(evaluate)})
    target = open_store(store, header, resume)
    bar = None
    try:
        resumed, pending = int(target.done.sum()), np.flatnonzero(~target.done)
        tasks = ((int(i), space.point(int(i))) for i in pending)
        bar = progress_bar(progress, total=space.n_points, initial=resumed, desc="sweep",
                           unit="pt")
        evaluated = failed = 0
        records = _records(executor, definition, tasks, max_workers) if pending.size else ()
        for record in records:
            target.write(record)
            evaluated += 1
            failed += record.status != Status.OK
            if bar is not None:
                bar.update(1)
        options = {"executor": executor if isinstance(executor, str)
                   else type(executor).__qualname__, "max_workers": max_workers,
                   "on_failure": on_failure, "resume": resume,
                   "store": None if store is None else os.fspath(store),
                   "apply": header.definition["apply"],
                   "evaluate": header.definition["evaluate"]}
        stats = {"points": float(space.n_points), "evaluated": float(evaluated),
                 "resumed": float(resumed), "failed": float(failed),
                 "wall_time": time.perf_counter() - t0}
        return target.finish(options, stats)
    finally:
        target.close()
        if bar is not None:
            bar.close()


def _check_inputs(rotor: Any, space: Any, apply: Any, evaluate: Any, max_workers: Any,
                  on_failure: str) -> None:
    if not isinstance(rotor, Rotor):
        raise ModelError(f"needs a Rotor, got {type(rotor).__name__}", "sweep")
    if not isinstance(space, Grid | Sample):
        raise ModelError(f"space must be a Grid or a Sample, got {type(space).__name__}",
                         "sweep")
    if apply is not None and not callable(apply):
        raise TypeError(f"apply must be callable or None, got {apply!r}")
    if not callable(evaluate):
        raise TypeError(f"evaluate must be callable, got {evaluate!r}")
    if max_workers is not None and (isinstance(max_workers, bool)
                                    or not isinstance(max_workers, int) or max_workers < 1):
        raise TypeError(f"max_workers must be None or an integer >= 1, got {max_workers!r}")
    if on_failure not in ON_FAILURE:
        raise TypeError(f"on_failure must be one of {ON_FAILURE}, got {on_failure!r}")


def _check_executor(executor: Any, definition: SweepDefinition) -> None:
    if isinstance(executor, str):
        if executor not in EXECUTORS:
            raise TypeError(f"executor must be one of {EXECUTORS}, a dask.distributed.Client"
                            f" or an executor object, got {executor!r}")
        if executor == "process":
            try:
                pickle.dumps(definition)
            except (pickle.PicklingError, AttributeError, TypeError) as exc:
                raise TypeError(
                    "executor='process' sends rotor, apply and evaluate to other processes:"
                    " they must be picklable (module-level functions or functools.partial"
                    f" of them, not lambdas or local functions): {exc}") from exc
    elif not (_is_dask_client(executor) or hasattr(executor, "submit")
              or hasattr(executor, "map")):
        raise TypeError(f"executor must be one of {EXECUTORS}, a dask.distributed.Client or"
                        f" an object with submit or map, got {type(executor).__name__}")


# ---------------------------------------------------------------------------- executors
Task = tuple[int, dict[str, float]]


def _records(executor: Any, definition: SweepDefinition, tasks: Iterator[Task],
             max_workers: int | None) -> Iterator[PointRecord]:
    """Evaluate ``tasks`` on ``executor``; yield records as they finish, in any order."""
    if executor == "serial":
        return (evaluate_point(definition, i, p) for i, p in tasks)
    if executor == "process":
        return _process_pool(definition, tasks, max_workers)
    if _is_dask_client(executor):
        return _dask(executor, definition, tasks, max_workers)
    window = 2 * (max_workers or os.cpu_count() or 1)
    if hasattr(executor, "submit"):
        return _stream(lambda i, p: executor.submit(evaluate_point, definition, i, p),
                       tasks, window, cf.wait)
    return iter(executor.map(functools.partial(_evaluate_task, definition), tasks))


def _evaluate_task(definition: SweepDefinition, task: Task) -> PointRecord:
    return evaluate_point(definition, *task)


def _stream(submit: Callable[[int, dict[str, float]], Any], tasks: Iterator[Task],
            window: int, wait: Callable[..., Any]) -> Iterator[PointRecord]:
    """Keep ``window`` futures in flight; yield results as they complete. Failed futures
    are raised after the results that finished with them have been yielded."""
    in_flight: set[Any] = set()
    try:
        for task in tasks:
            in_flight.add(submit(*task))
            if len(in_flight) >= window:
                yield from _drain(wait, in_flight)
        while in_flight:
            yield from _drain(wait, in_flight)
    finally:
        for future in in_flight:
            future.cancel()


def _drain(wait: Callable[..., Any], in_flight: set[Any]) -> Iterator[PointRecord]:
    done, _ = wait(list(in_flight), return_when="FIRST_COMPLETED")
    in_flight.difference_update(done)
    errors = [f for f in done if f.exception() is not None]
    for future in done:
        if future not in errors:
            yield future.result()
    if errors:
        raise errors[0].exception()


_INSTALLED: list[SweepDefinition] = []


def _install(definition: SweepDefinition) -> None:
    """Pool initializer: keep the definition in the worker process."""
    _INSTALLED[:] = [definition]


def _evaluate_installed(index: int, params: dict[str, float]) -> PointRecord:
    return evaluate_point(_INSTALLED[0], index, params)


def _process_pool(definition: SweepDefinition, tasks: Iterator[Task],
                  max_workers: int | None) -> Iterator[PointRecord]:
    workers = max_workers or os.cpu_count() or 1
    pool = cf.ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context(
        "spawn"), initializer=_install, initargs=(definition,))
    try:
        yield from _stream(lambda i, p: pool.submit(_evaluate_installed, i, p), tasks,
                           2 * workers, cf.wait)
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _is_dask_client(executor: Any) -> bool:
    return type(executor).__module__.split(".")[0] == "distributed" \
        and hasattr(executor, "scatter")


def _dask(client: Any, definition: SweepDefinition, tasks: Iterator[Task],
          max_workers: int | None) -> Iterator[PointRecord]:
    from distributed import wait

    shared = client.scatter(definition, broadcast=True, hash=False)
    width = max_workers or max(1, sum(client.nthreads().values()))
    yield from _stream(lambda i, p: client.submit(evaluate_point, shared, i, p, pure=False),
                       tasks, 2 * width, wait)
