"""One BLAS thread inside the hot loops: no waiting on oversubscribed threads.

Time stepping, ARPACK, Campbell speeds, frequency sweeps and harmonic-balance Newton
iterations make thousands of small BLAS calls (matrix-vector products, small dense
solves). A threaded BLAS splits each call over its threads and waits for all of them; on
a machine busy with other work one of them is often descheduled, and every call then
waits a scheduler time slice. Issue 12 reported, on 2 cores next to one busy process, the default
model's run-up went from 3.9 s to 44-53 s and a 50-speed Campbell of 606 DOFs from
0.41 s to 3.75 s (``benchmarks/under_load.py``, ``docs/benchmarks.md``).

The entry of each hot loop therefore runs under :class:`one_blas_thread` (a decorator
or a context), or :func:`blas_threads_for` where the dense work can be large. The limit
is set through threadpoolctl (imported on first use, so ``import rotorsim`` stays light)
once per analysis: nested entries, e.g. ``modal`` inside ``campbell``, only count, and the
original limits come back when the outermost capped section ends. The BLAS thread limit is
process-wide, so sections running in several threads at once (a threaded sweep) share one
cap, held until the last of them ends.

Set the environment variable ``ROTORSIM_BLAS_CAP=off`` to leave the BLAS threads alone
(e.g. to measure the uncapped behaviour, as the benchmark does).
"""

from __future__ import annotations

import functools
import os
import sys
import threading
from collections.abc import Callable
from contextlib import AbstractContextManager, ContextDecorator, nullcontext
from typing import Any, ParamSpec, TypeVar

SMALL_WORK_SIZE = 1000
"""Order of the largest dense matrix at or below which BLAS runs in one thread. A dense LU
of this order takes about 20 ms on one core, a matrix-vector product about 0.3 ms: little
to gain from a second thread alone, and a scheduler time slice (several ms) to lose per
call next to a busy process."""

SWITCH = "ROTORSIM_BLAS_CAP"
"""Environment variable: ``off`` (or ``0``, ``no``, ``false``) disables the caps."""

_P = ParamSpec("_P")
_R = TypeVar("_R")


class _Cap:
    """Process-wide count of the capped sections that are running.

    The first section to start sets the limit and the last to end restores it, whichever
    threads they run in. threadpoolctl lets only one "controlling" thread change a
    process-wide OpenBLAS pool and silently ignores the others; this count already
    serialises the changes, so control is released around each of them.
    """

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.depth = 0
        self.limiter: Any = None
        self.blas: Any = None
        self.modules_seen = -1

    def controller(self) -> Any:
        """threadpoolctl's view of the loaded BLAS libraries, found again (about 1 ms)
        only after new modules were imported, since a new BLAS library arrives with one."""
        if self.blas is None or len(sys.modules) != self.modules_seen:
            from threadpoolctl import ThreadpoolController

            self.blas = ThreadpoolController().select(user_api="blas")
            self.modules_seen = len(sys.modules)
        return self.blas

    def enter(self) -> None:
        with self.lock:
            if self.depth == 0:
                _release_control()
                self.limiter = self.controller().limit(limits=1)
                _release_control()
            self.depth += 1

    def exit(self) -> None:
        with self.lock:
            self.depth -= 1
            if self.depth == 0:
                limiter, self.limiter = self.limiter, None
                _release_control()
                limiter.restore_original_limits()
                _release_control()


def _release_control() -> None:
    """Let any thread change the OpenBLAS limits next (threadpoolctl >= 3.7 remembers one
    controlling thread; older versions have no such rule)."""
    import threadpoolctl

    controller = getattr(threadpoolctl, "OpenBLASController", None)
    release = getattr(controller, "clear_controlling_thread", None)
    if release is not None:
        release(force=True)


_CAP = _Cap()


def caps_enabled() -> bool:
    """False when the environment variable :data:`SWITCH` says ``off``."""
    return os.environ.get(SWITCH, "").strip().lower() not in ("off", "0", "no", "false")


class one_blas_thread(ContextDecorator):  # lower case: used like a function
    """Run a block (``with one_blas_thread():``) or a function (``@one_blas_thread()``)
    with one BLAS thread.

    Examples
    --------
    >>> import numpy as np
    >>> from threadpoolctl import threadpool_info
    >>> with one_blas_thread():
    ...     counts = {lib["num_threads"] for lib in threadpool_info()
    ...               if lib["user_api"] == "blas"}
    >>> counts <= {1}                           # empty only without a threaded BLAS
    True
    """

    def __init__(self) -> None:
        self._entered: list[bool] = []

    def __enter__(self) -> one_blas_thread:
        active = caps_enabled()
        if active:
            _CAP.enter()
        self._entered.append(active)
        return self

    def __exit__(self, *exc: object) -> None:
        if self._entered.pop():
            _CAP.exit()

    def _recreate_cm(self) -> one_blas_thread:
        return one_blas_thread()  # a fresh record per call: decorated functions may recurse


def blas_threads_for(size: int) -> AbstractContextManager[Any]:
    """One BLAS thread when the largest dense matrix of the work has order
    ``size <= SMALL_WORK_SIZE``; otherwise the BLAS threads are left as they are.

    Parameters
    ----------
    size : int
        Order of the largest dense matrix factorised or multiplied in the loop.
    """
    return one_blas_thread() if size <= SMALL_WORK_SIZE else nullcontext()


def capped_by_size(size_of: Callable[..., int]) -> Callable[[Callable[_P, _R]],
                                                            Callable[_P, _R]]:
    """Decorator: run the function under ``blas_threads_for(size_of(*args, **kwargs))``.

    ``size_of`` takes the function's arguments and returns the order of its largest dense
    matrix (see :func:`blas_threads_for`).
    """
    def decorate(func: Callable[_P, _R]) -> Callable[_P, _R]:
        @functools.wraps(func)
        def capped(*args: _P.args, **kwargs: _P.kwargs) -> _R:
            with blas_threads_for(size_of(*args, **kwargs)):
                return func(*args, **kwargs)
        return capped
    return decorate
