"""Running reductions of a time integration, evaluated on every accepted step.

A :class:`Reducer` says what to reduce (``q``, ``v`` or ``a`` of chosen unknowns, or of
linear combinations of them given by a ``transform`` matrix, e.g. the physical DOFs of a
reduced model) and how: the largest ``|x|``, the maximum, the minimum, the time-weighted
RMS, the largest radial amplitude ``sqrt(x^2 + y^2)`` of ``(x, y)`` pairs, or the
peak-to-peak per segment of a monotone counter (e.g. per shaft revolution: the analysis
layer passes ``segment = lambda state: phi(state.t) / (2 pi)``; this module knows nothing
of rotors). Each reducer keeps an accumulator of fixed size; a per-segment reducer adds one
row per segment. Memory never grows with the number of steps times the problem size.

Examples
--------
>>> acc = Reducer("rms").accumulator(1)
>>> for t, x in [(0.0, 1.0), (1.0, -1.0), (2.0, 1.0)]:
...     acc.update(t, np.array([x]))
>>> acc.values()["rms_q"].tolist()
[1.0]
"""

from __future__ import annotations

import functools
import hashlib
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.time_integration.base import FloatArray, IntArray, State

ReducerKind = Literal["max_abs", "max", "min", "rms", "max_amplitude", "peak_to_peak"]
REDUCER_KINDS: tuple[str, ...] = ("max_abs", "max", "min", "rms", "max_amplitude",
                                  "peak_to_peak")
_RUNNING: dict[str, Callable[[FloatArray, FloatArray], FloatArray]] = {
    "max_abs": lambda acc, x: np.fmax(acc, np.abs(x)), "max": np.fmax, "min": np.fmin,
    "max_amplitude": lambda acc, x: np.fmax(acc, np.hypot(x[0::2], x[1::2]))}


@dataclass(frozen=True, eq=False)
class Reducer:
    """A running reduction over all accepted steps (and the initial state).

    Parameters
    ----------
    kind : {"max_abs", "max", "min", "rms", "max_amplitude", "peak_to_peak"}
        Per reduced value: largest ``|x|``, maximum, minimum; ``rms``: the root mean
        square over time (trapezoidal rule over the accepted steps, so a variable step is
        weighted by its length); ``max_amplitude``: the largest ``sqrt(x^2 + y^2)`` of
        consecutive pairs ``(x, y)`` (the values must come in pairs); ``peak_to_peak``:
        ``max - min`` over each segment (one row per segment, see ``segment``), or over the
        whole run without ``segment``; a last segment holding one state only (the run
        ended on its first step) gives no row. Extremes are taken over the accepted steps, so a
        peak between two steps is resolved to the step size.
    quantity : {"q", "v", "a"}
        Which state vector.
    dofs : tuple of int, optional
        Unknowns reduced (all if omitted; excludes ``transform``).
    after : float
        Only states with ``t >= after`` count [s] (e.g. skip the start-up transient).
    name : str, optional
        Key in ``IntegrationResult.reduced`` (default ``"<kind>_<quantity>"``).
    transform : array (m, n), optional
        Reduce ``transform @ x`` instead of chosen unknowns (e.g. the rows of a reduction
        basis for the physical DOFs of interest).
    segment : callable, optional
        ``segment(state) -> float``, non-decreasing along the run; ``peak_to_peak`` starts a
        new row whenever ``floor(segment)`` changes (e.g. the shaft revolution count
        ``phi / 2 pi``). The segment index of each row is in ``<name>_<segment_label>``.
        The first and last rows may cover part of a segment only.
    segment_label : str
        Suffix of the key of the segment indices.

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
    transform: FloatArray | None = None
    segment: Callable[[State], float] | None = None
    segment_label: str = "segment"

    def __post_init__(self) -> None:
        if self.kind not in REDUCER_KINDS:
            raise TypeError(f"unknown reducer kind {self.kind!r}; valid: "
                            f"{', '.join(REDUCER_KINDS)}")
        if self.quantity not in ("q", "v", "a"):
            raise TypeError(f"unknown quantity {self.quantity!r}; valid: q, v, a")
        if not self.key or "/" in self.key:
            raise ModelError(f"name must be non-empty without '/', got {self.name!r}",
                             "Reducer")
        if self.transform is not None:
            if self.dofs is not None:
                raise ModelError("give 'dofs' or 'transform', not both", f"Reducer "
                                 f"'{self.key}'")
            object.__setattr__(self, "transform", np.atleast_2d(np.asarray(
                self.transform, dtype=float)))
        if self.segment is not None and self.kind != "peak_to_peak":
            raise ModelError("segment is an option of 'peak_to_peak' only",
                             f"Reducer '{self.key}'")

    @property
    def key(self) -> str:
        """Name of the reduced array in the result."""
        return self.name or f"{self.kind}_{self.quantity}"

    def width(self, n: int) -> int:
        """Number of values reduced per state in a problem of size ``n``."""
        if self.transform is not None:
            return int(self.transform.shape[0])
        return n if self.dofs is None else len(self.dofs)

    def check(self, n: int) -> None:
        """Validate against a problem of size ``n``."""
        where = f"Reducer '{self.key}'"
        if self.dofs is not None and (len(self.dofs) == 0 or min(self.dofs) < 0
                                      or max(self.dofs) >= n):
            raise ModelError(f"indices must lie in [0, {n}), got {list(self.dofs)}",
                             f"{where}.dofs")
        if self.transform is not None and self.transform.shape[1] != n:
            raise ModelError(f"transform must have {n} columns, got "
                             f"{self.transform.shape}", f"{where}.transform")
        if self.kind == "max_amplitude" and self.width(n) % 2:
            raise ModelError(f"max_amplitude reduces (x, y) pairs: an even number of values "
                             f"is needed, got {self.width(n)}", where)

    def describe(self) -> dict[str, Any]:
        """JSON-able identity (the transform by digest) used to match checkpoints."""
        out: dict[str, Any] = {"kind": self.kind, "quantity": self.quantity,
                               "dofs": None if self.dofs is None else list(self.dofs),
                               "after": self.after, "name": self.name}
        if self.transform is not None:
            out["transform"] = hashlib.blake2b(self.transform.tobytes(),
                                               digest_size=8).hexdigest()
        if self.segment is not None:
            out["segment"] = self.segment_label
        return out

    def values_of(self, state: State) -> FloatArray:
        """The reduced values of ``state`` (before the reduction)."""
        x = getattr(state, self.quantity)
        if self.transform is not None:
            return np.asarray(self.transform @ x)
        return x if self.dofs is None else x[self._index]

    @functools.cached_property
    def _index(self) -> IntArray:
        return np.asarray(self.dofs, dtype=np.int64)

    def accumulator(self, n: int, saved: dict[str, FloatArray] | None = None) -> Accumulator:
        """A fresh accumulator (or one restored from :meth:`Accumulator.snapshot`)."""
        return Accumulator(self, self.width(n), saved or {})


class Accumulator:
    """Runtime state of one :class:`Reducer` (checkpointable by :meth:`snapshot`)."""

    def __init__(self, reducer: Reducer, m: int, saved: dict[str, FloatArray]) -> None:
        self.reducer = reducer
        kind = reducer.kind
        width = m // 2 if kind == "max_amplitude" else m
        fresh = np.zeros(m) if kind == "rms" else np.full(width, np.nan)
        self._acc = np.array(saved["value"]) if "value" in saved else fresh
        # rms: the integral of x^2 (in _acc), the last x^2 and [t_first, t_last];
        # peak_to_peak: running max (_acc) and min of the open segment, finished rows and
        # the segment indices
        self._last = np.array(saved.get("last", np.full(m, np.nan)))
        self._times = np.array(saved.get("times", [np.nan, np.nan]))
        self._low = np.array(saved.get("low", np.full(m, np.nan)))
        self._rows = [np.array(r) for r in saved.get("rows", np.zeros((0, m)))]
        self._segments = [float(s) for s in saved.get("segments", np.zeros(0))]
        self._count = int(saved.get("count", np.zeros(1))[0])  # states in the open segment

    def update_state(self, state: State) -> None:
        """Add the accepted state ``state`` (when ``t >= after``)."""
        r = self.reducer
        if state.t < r.after:
            return
        segment = None if r.segment is None else math.floor(float(r.segment(state)))
        self.update(state.t, r.values_of(state), segment)

    def update(self, t: float, x: FloatArray, segment: int | None = None) -> None:
        """Add the values ``x`` at time ``t`` [s] (in segment ``segment``)."""
        kind = self.reducer.kind
        if kind in _RUNNING:
            self._acc = _RUNNING[kind](self._acc, x)
        elif kind == "rms":
            x2 = x * x
            if np.isfinite(self._times[1]):
                self._acc = self._acc + 0.5 * (t - self._times[1]) * (self._last + x2)
            else:
                self._times[0] = t
            self._times[1], self._last = t, x2
        else:
            self._peak_to_peak(x, 0 if segment is None else segment)

    def _peak_to_peak(self, x: FloatArray, segment: int) -> None:
        if self._segments and segment == self._segments[-1]:
            self._acc, self._low = np.fmax(self._acc, x), np.fmin(self._low, x)
            self._count += 1
            return
        if self._segments:
            self._rows.append(self._acc - self._low)
        self._segments.append(float(segment))
        self._acc, self._low = np.array(x, dtype=float), np.array(x, dtype=float)
        self._count = 1

    def values(self) -> dict[str, FloatArray]:
        """The reduced arrays: ``{key: values}`` (and ``{key}_{segment_label}`` for a
        per-segment peak-to-peak)."""
        r, key = self.reducer, self.reducer.key
        if r.kind == "rms":
            span = self._times[1] - self._times[0]
            if not np.isfinite(span):
                return {key: np.full(self._acc.size, np.nan)}
            mean = self._acc / span if span > 0 else self._last
            return {key: np.sqrt(mean)}
        if r.kind != "peak_to_peak":
            return {key: self._acc.copy()}
        if r.segment is None:
            return {key: self._acc - self._low}
        # an open segment of one state (the run ended on its first step) says nothing
        keep = len(self._segments) - (self._count == 1 and len(self._segments) > 1)
        rows = [*self._rows, self._acc - self._low][:keep]
        return {key: np.array(rows).reshape(len(rows), self._acc.size),
                f"{key}_{r.segment_label}": np.array(self._segments[:keep])}

    def snapshot(self) -> dict[str, FloatArray]:
        """Arrays that restore this accumulator (``saved`` of :meth:`Reducer.accumulator`):
        ``value`` and, for ``rms`` and ``peak_to_peak``, their running parts."""
        m = self._last.size
        out = {"value": self._acc.copy()}
        if self.reducer.kind == "rms":
            out.update({"last": self._last.copy(), "times": self._times.copy()})
        if self.reducer.kind == "peak_to_peak":
            out.update({"low": self._low.copy(),
                        "rows": np.array(self._rows).reshape(len(self._rows), m),
                        "segments": np.array(self._segments),
                        "count": np.array([float(self._count)])})
        return out
