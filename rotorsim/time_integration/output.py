"""What a time integration keeps (STYLE practice 5: output is not the stepper's business).

An :class:`OutputSpec` chooses the samples (given times, by the stepper's interpolant, or
every n-th accepted step), the unknowns kept (``dofs``) and running reducers (such as the
largest ``|q|`` after a start-up time) evaluated on every accepted step. Memory grows with
the number of samples times ``len(dofs)``, never with the number of steps times ``n``.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.time_integration.base import FloatArray, IntArray, State, TimeStepper

ReducerKind = Literal["max_abs", "max", "min"]
_UPDATE: dict[str, Callable[[FloatArray, FloatArray], FloatArray]] = {
    "max_abs": lambda acc, x: np.fmax(acc, np.abs(x)), "max": np.fmax, "min": np.fmin}


@dataclass(frozen=True)
class Reducer:
    """A running reduction over all accepted steps (and the initial state).

    Parameters
    ----------
    kind : {"max_abs", "max", "min"}
        Reduction per unknown.
    quantity : {"q", "v", "a"}
        Which state vector.
    dofs : tuple of int, optional
        Unknowns reduced (all if omitted).
    after : float
        Only states with ``t >= after`` count [s] (e.g. skip the start-up transient).
    name : str, optional
        Key in ``IntegrationResult.reduced`` (default ``"<kind>_<quantity>"``).

    Examples
    --------
    >>> Reducer("max_abs", dofs=(0, 2), after=10.0).key
    'max_abs_q'
    """

    kind: ReducerKind = "max_abs"
    quantity: Literal["q", "v", "a"] = "q"
    dofs: tuple[int, ...] | None = None
    after: float = -np.inf
    name: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in _UPDATE:
            raise TypeError(f"unknown reducer kind {self.kind!r}; valid: {', '.join(_UPDATE)}")
        if self.quantity not in ("q", "v", "a"):
            raise TypeError(f"unknown quantity {self.quantity!r}; valid: q, v, a")
        if not self.key or "/" in self.key:
            raise ModelError(f"name must be non-empty without '/', got {self.name!r}",
                             "Reducer")

    @property
    def key(self) -> str:
        """Name of the reduced array in the result."""
        return self.name or f"{self.kind}_{self.quantity}"


@dataclass(frozen=True, eq=False)
class OutputSpec:
    """Samples, unknowns and reducers kept by :func:`~.integrate.integrate`.

    Parameters
    ----------
    times : array-like, optional
        Increasing sample times inside the time span [s], evaluated by the stepper's
        interpolant. Excludes ``every``.
    every : int, optional
        Keep the initial state, every ``every``-th accepted step and the final state
        (default 1 when ``times`` is not given): the samples always end at ``t_end``,
        also when the number of steps is not a multiple of ``every``.
    dofs : sequence of int, optional
        Unknowns kept in the samples (default all).
    velocities : bool
        Keep ``v`` beside ``q``.
    reducers : tuple of Reducer

    Examples
    --------
    >>> spec = OutputSpec(every=10, dofs=[0, 3], reducers=(Reducer("max_abs"),))
    >>> spec.every, spec.dofs.tolist()
    (10, [0, 3])
    """

    times: FloatArray | None = None
    every: int | None = None
    dofs: IntArray | None = None
    velocities: bool = True
    reducers: tuple[Reducer, ...] = field(default=())

    def __post_init__(self) -> None:
        if self.times is not None:
            times = np.array(self.times, dtype=float).reshape(-1)
            if self.every is not None:
                raise ModelError("give 'times' or 'every', not both", "OutputSpec")
            if not (np.all(np.isfinite(times)) and np.all(np.diff(times) > 0)):
                raise ModelError("times must be finite and strictly increasing", "OutputSpec")
            object.__setattr__(self, "times", times)
        elif self.every is None:
            object.__setattr__(self, "every", 1)
        if self.every is not None and (int(self.every) != self.every or self.every < 1):
            raise ModelError(f"every must be a positive integer, got {self.every!r}",
                             "OutputSpec")
        if self.dofs is not None:
            object.__setattr__(self, "dofs", np.array(self.dofs, dtype=np.int64).reshape(-1))
        keys = [r.key for r in self.reducers]
        if len(set(keys)) != len(keys):
            raise ModelError(f"reducer names must be unique, got {keys}", "OutputSpec")

    def check(self, n: int, t0: float, t_end: float) -> None:
        """Validate against a problem of size ``n`` and the span ``[t0, t_end]``."""
        for where, dofs in [("OutputSpec.dofs", self.dofs)] + [
                (f"Reducer '{r.key}'.dofs", r.dofs) for r in self.reducers]:
            if dofs is not None and (len(dofs) == 0 or min(dofs) < 0 or max(dofs) >= n):
                raise ModelError(f"indices must lie in [0, {n}), got {list(dofs)}", where)
        if self.times is not None and len(self.times) and (
                self.times[0] < t0 or self.times[-1] > t_end):
            raise ModelError(f"times must lie in [{t0}, {t_end}]", "OutputSpec.times")

    def describe(self) -> dict[str, object]:
        """JSON-able summary (times by digest) used to match checkpoints."""
        times = None if self.times is None else hashlib.blake2b(
            self.times.tobytes(), digest_size=8).hexdigest()
        return {"times": times, "every": self.every, "velocities": self.velocities,
                "dofs": None if self.dofs is None else self.dofs.tolist(),
                "reducers": [json.loads(json.dumps(r.__dict__, default=str))
                             for r in self.reducers]}


class _Rows:
    """Append-only 2-D float buffer with amortised O(1) growth."""

    def __init__(self, width: int, data: FloatArray | None = None) -> None:
        self._data = np.empty((16, width)) if data is None else np.array(data, dtype=float)
        self._size = 0 if data is None else len(data)

    def extend(self, rows: FloatArray) -> None:
        need = self._size + len(rows)
        if need > len(self._data):
            grown = np.empty((max(need, 2 * len(self._data)), self._data.shape[1]))
            grown[: self._size] = self._data[: self._size]
            self._data = grown
        self._data[self._size: need] = rows
        self._size = need

    @property
    def size(self) -> int:
        return self._size

    def last(self) -> FloatArray:
        return self._data[self._size - 1]

    def array(self) -> FloatArray:
        return self._data[: self._size].copy()


class OutputRecorder:
    """Runtime collector of one run's samples and reductions (checkpointable)."""

    def __init__(self, spec: OutputSpec, n: int, saved: dict[str, FloatArray] | None = None):
        self.spec = spec
        self.dofs: IntArray = np.arange(n) if spec.dofs is None else spec.dofs
        m = len(self.dofs)
        saved = saved or {}
        self._t = _Rows(1, saved.get("t"))
        self._q = _Rows(m, saved.get("q"))
        self._v = _Rows(m, saved.get("v")) if spec.velocities else None
        self._next = int(saved["next_time"][0]) if "next_time" in saved else 0
        self.reduced = {r.key: np.array(saved[f"reduced/{r.key}"]) if f"reduced/{r.key}"
                        in saved else np.full(n if r.dofs is None else len(r.dofs), np.nan)
                        for r in spec.reducers}

    def start(self, state: State) -> None:
        """Record the initial state."""
        if self.spec.times is None or (len(self.spec.times) and self.spec.times[0] == state.t):
            self._append(np.array([state.t]), state.q[self.dofs][None, :],
                         state.v[self.dofs][None, :])
            self._next = 1 if self.spec.times is not None else 0
        self._reduce(state)

    def record(self, stepper: TimeStepper, old: State, new: State) -> None:
        """Record what the accepted step ``old -> new`` contributes."""
        times = self.spec.times
        if times is None:
            if new.step % int(self.spec.every or 1) == 0:
                self._append(np.array([new.t]), new.q[self.dofs][None, :],
                             new.v[self.dofs][None, :])
        else:
            stop = int(np.searchsorted(times, new.t, side="right"))
            if stop > self._next:
                ts = times[self._next: stop]
                q, v = stepper.interpolate(old, new, ts, self.dofs)
                self._append(ts, q, v)
                self._next = stop
        self._reduce(new)

    def finish(self, state: State) -> bool:
        """Keep the final state ``state`` when ``every`` skipped it; True when it was added
        (idempotent, so a run resumed from a finished checkpoint keeps it once)."""
        if self.spec.times is not None or (self._t.size and self._t.last()[0] == state.t):
            return False
        self._append(np.array([state.t]), state.q[self.dofs][None, :],
                     state.v[self.dofs][None, :])
        return True

    def snapshot(self) -> dict[str, FloatArray]:
        """Arrays to store in a checkpoint (restored by the constructor's ``saved``)."""
        out = {"t": self._t.array(), "q": self._q.array(),
               "next_time": np.array([float(self._next)])}
        if self._v is not None:
            out["v"] = self._v.array()
        out.update({f"reduced/{k}": v.copy() for k, v in self.reduced.items()})
        return out

    def arrays(self) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        """Sample times (k,), ``q`` (k, m) and ``v`` (k, m) or None."""
        return (self._t.array()[:, 0], self._q.array(),
                None if self._v is None else self._v.array())

    def _append(self, t: FloatArray, q: FloatArray, v: FloatArray) -> None:
        self._t.extend(t[:, None])
        self._q.extend(q)
        if self._v is not None:
            self._v.extend(v)

    def _reduce(self, state: State) -> None:
        for r in self.spec.reducers:
            if state.t >= r.after:
                x = getattr(state, r.quantity)
                x = x if r.dofs is None else x[list(r.dofs)]
                self.reduced[r.key] = _UPDATE[r.kind](self.reduced[r.key], x)
