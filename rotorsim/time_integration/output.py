"""What a time integration keeps (STYLE practice 5: output is not the stepper's business).

An :class:`OutputSpec` chooses the samples (given times, by the stepper's interpolant, or
every n-th accepted step), the unknowns kept (``dofs``), whose velocities are kept
(``velocities``) and running reducers (:mod:`~.reducers`: largest ``|q|``, RMS, radial
amplitude, peak-to-peak per revolution, ...) evaluated on every accepted step. Memory grows with
the number of samples times ``len(dofs)``, never with the number of steps times ``n``.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError
from rotorsim.time_integration.base import FloatArray, IntArray, State, TimeStepper
from rotorsim.time_integration.reducers import Accumulator, Reducer

__all__ = ["OutputRecorder", "OutputSpec", "Reducer"]

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
    velocities : bool or sequence of int
        Keep ``v`` of all kept unknowns (True), of none (False) or of these unknowns
        (indices into the problem's unknowns, e.g. only those a post-processor needs).
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
    velocities: bool | ArrayLike = True
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
        if not isinstance(self.velocities, bool | np.bool_):
            object.__setattr__(self, "velocities",
                               np.array(self.velocities, dtype=np.int64).reshape(-1))
        keys = [r.key for r in self.reducers]
        if len(set(keys)) != len(keys):
            raise ModelError(f"reducer names must be unique, got {keys}", "OutputSpec")

    def check(self, n: int, t0: float, t_end: float) -> None:
        """Validate against a problem of size ``n`` and the span ``[t0, t_end]``."""
        vdofs = None if isinstance(self.velocities, bool | np.bool_) else np.asarray(
            self.velocities, dtype=np.int64)
        checks: list[tuple[str, IntArray | None]] = [("OutputSpec.dofs", self.dofs),
                                                     ("OutputSpec.velocities", vdofs)]
        for where, dofs in checks:
            if dofs is not None and len(dofs) and (min(dofs) < 0 or max(dofs) >= n):
                raise ModelError(f"indices must lie in [0, {n}), got {list(dofs)}", where)
        if self.dofs is not None and not len(self.dofs):
            raise ModelError("give at least one unknown", "OutputSpec.dofs")
        for r in self.reducers:
            r.check(n)
        if self.times is not None and len(self.times) and (
                self.times[0] < t0 or self.times[-1] > t_end):
            raise ModelError(f"times must lie in [{t0}, {t_end}]", "OutputSpec.times")

    def describe(self) -> dict[str, object]:
        """JSON-able summary (times by digest) used to match checkpoints."""
        times = None if self.times is None else hashlib.blake2b(
            self.times.tobytes(), digest_size=8).hexdigest()
        velocities = self.velocities if isinstance(self.velocities, bool | np.bool_) \
            else self.velocities.tolist()  # type: ignore[union-attr]
        return {"times": times, "every": self.every, "velocities": bool(velocities)
                if isinstance(velocities, np.bool_) else velocities,
                "dofs": None if self.dofs is None else self.dofs.tolist(),
                "reducers": [r.describe() for r in self.reducers]}

    def velocity_dofs(self, n: int) -> IntArray | None:
        """Unknowns whose velocities are kept in a problem of size ``n`` (None: none)."""
        v = self.velocities
        if isinstance(v, bool | np.bool_):
            return (np.arange(n) if self.dofs is None else self.dofs) if v else None
        return np.asarray(v, dtype=np.int64)


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

    def take(self) -> FloatArray:
        """The rows, the buffer shrunk in place (no copy: the peak memory of a long run is
        its buffer, not buffer plus copy); the buffer then belongs to the caller."""
        data, self._data = self._data, np.empty((0, self._data.shape[1]))
        data.resize((self._size, data.shape[1]), refcheck=False)
        return data


class OutputRecorder:
    """Runtime collector of one run's samples and reductions (checkpointable)."""

    def __init__(self, spec: OutputSpec, n: int, saved: dict[str, FloatArray] | None = None):
        self.spec = spec
        self.dofs: IntArray = np.arange(n) if spec.dofs is None else spec.dofs
        self.velocity_dofs = spec.velocity_dofs(n)
        saved = saved or {}
        self._t = _Rows(1, saved.get("t"))
        self._q = _Rows(len(self.dofs), saved.get("q"))
        self._v = None if self.velocity_dofs is None else _Rows(len(self.velocity_dofs),
                                                                saved.get("v"))
        self._next = int(saved["next_time"][0]) if "next_time" in saved else 0
        vd = self.velocity_dofs
        # one interpolation for the kept DOFs and the velocity DOFs (the bearing DOFs'
        # velocities are kept even when no velocities are asked for)
        self._union = self.dofs if vd is None or np.array_equal(vd, self.dofs) else \
            np.union1d(self.dofs, vd)
        self._at = (np.searchsorted(self._union, self.dofs),
                    None if vd is None else np.searchsorted(self._union, vd))
        self._accumulators: list[Accumulator] = [
            r.accumulator(n, _saved_reducer(saved, r.key)) for r in spec.reducers]

    @property
    def reduced(self) -> dict[str, FloatArray]:
        """The reduced arrays so far (see :meth:`~.reducers.Accumulator.values`)."""
        out: dict[str, FloatArray] = {}
        for acc in self._accumulators:
            out.update(acc.values())
        return out

    def start(self, state: State) -> None:
        """Record the initial state."""
        if self.spec.times is None or (len(self.spec.times) and self.spec.times[0] == state.t):
            self._append_state(state)
            self._next = 1 if self.spec.times is not None else 0
        self._reduce(state)

    def record(self, stepper: TimeStepper, old: State, new: State) -> None:
        """Record what the accepted step ``old -> new`` contributes."""
        times = self.spec.times
        if times is None:
            if new.step % int(self.spec.every or 1) == 0:
                self._append_state(new)
        else:
            stop = int(np.searchsorted(times, new.t, side="right"))
            if stop > self._next:
                ts = times[self._next: stop]
                q, v = stepper.interpolate(old, new, ts, self._union)
                if self._union is not self.dofs:
                    q, v = q[:, self._at[0]], v[:, self._at[1]]
                self._append(ts, q, v)
                self._next = stop
        self._reduce(new)

    def finish(self, state: State) -> bool:
        """Keep the final state ``state`` when ``every`` skipped it; True when it was added
        (idempotent, so a run resumed from a finished checkpoint keeps it once)."""
        if self.spec.times is not None or (self._t.size and self._t.last()[0] == state.t):
            return False
        self._append_state(state)
        return True

    def snapshot(self) -> dict[str, FloatArray]:
        """Arrays to store in a checkpoint (restored by the constructor's ``saved``)."""
        out = {"t": self._t.array(), "q": self._q.array(),
               "next_time": np.array([float(self._next)])}
        if self._v is not None:
            out["v"] = self._v.array()
        for acc in self._accumulators:
            key = acc.reducer.key
            for part, value in acc.snapshot().items():
                out[f"reduced/{key}" if part == "value" else
                    f"reducer_state/{key}/{part}"] = value
        return out

    def arrays(self) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        """Sample times (k,), ``q`` (k, m) and ``v`` (k, len(velocity_dofs)) or None; the
        buffers are handed over, so call it once, last."""
        return (self._t.take()[:, 0].copy(), self._q.take(),
                None if self._v is None else self._v.take())

    def _append_state(self, state: State) -> None:
        v = None if self.velocity_dofs is None else state.v[self.velocity_dofs][None, :]
        self._append(np.array([state.t]), state.q[self.dofs][None, :], v)

    def _append(self, t: FloatArray, q: FloatArray, v: FloatArray | None) -> None:
        self._t.extend(t[:, None])
        self._q.extend(q)
        if self._v is not None and v is not None:
            self._v.extend(v)

    def _reduce(self, state: State) -> None:
        for acc in self._accumulators:
            acc.update_state(state)


def _saved_reducer(saved: dict[str, FloatArray], key: str) -> dict[str, FloatArray]:
    """The checkpointed parts of reducer ``key`` (``reduced/<key>`` is its value)."""
    out = {part.rsplit("/", 1)[1]: value for part, value in saved.items()
           if part.startswith(f"reducer_state/{key}/")}
    if f"reduced/{key}" in saved:
        out["value"] = saved[f"reduced/{key}"]
    return out
