"""What a run keeps and shows: :class:`Output`."""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, ClassVar

from rotorsim.options.group import OptionGroup, about, check_count

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


REDUCERS = ("max_abs", "peak_to_peak", "max_amplitude", "rms")
"""Reducers of a transient's kept DOFs (``Output.reducers``)."""


@dataclass(frozen=True)
class Output(OptionGroup):
    """Recorded DOFs, samples and progress of :func:`~rotorsim.transient`,
    :func:`~rotorsim.periodic` and :func:`~rotorsim.periodic_parameter`
    (``output=rs.Output(...)``).

    Parameters
    ----------
    nodes : sequence of int, optional
        Nodes whose DOFs are kept (default all; the nonlinear elements' DOFs are always
        kept). The verbs also take them as their ``nodes=`` keyword (not both).
    every : int, optional
        Keep every ``every``-th time step (default 1; ignored with ``times``). Transients
        only.
    times : sequence of float, optional
        Sample times [s], strictly increasing (dense output by the stepper's interpolant).
        Transients only.
    rolling_elements : bool
        Also keep the load and contact angle of every rolling element of each bearing at
        every sample (``result.element_loads``, ``result.contact_angles``). Transients only.
    progress : bool
        Show a progress bar (on a terminal).
    velocities : bool
        Also keep the velocities of the kept DOFs (``result.v``; default False: memory
        goes to the displacements). Transients only.
    reducers : sequence of str
        Reductions of the kept DOFs over every accepted time step with ``t >= after``, in
        ``result.reduced`` (:data:`REDUCERS`): ``"max_abs"`` (largest ``|q|``),
        ``"peak_to_peak"`` (per shaft revolution), ``"max_amplitude"`` (largest radial
        amplitude ``sqrt(ux^2 + uy^2)`` of each node) and ``"rms"`` (time-weighted root
        mean square). With a large ``every`` they summarise a long run in little memory.
        Transients only.
    after : float, optional
        Start of the reductions [s] (default: the start of the run). Transients only.

    Examples
    --------
    >>> Output(nodes=[2, 5], every=10).nodes
    (2, 5)
    >>> Output(reducers=["rms", "peak_to_peak"]).reducers
    ('rms', 'peak_to_peak')
    >>> Output(every=0)
    Traceback (most recent call last):
    ...
    rotorsim.options.group.OptionError: Output.every: must be a positive integer, got 0
    """

    FROM_VERB: ClassVar[tuple[str, ...]] = ("every",)
    nodes: Sequence[int] | None = field(
        default=None, metadata=about("nodes whose DOFs are kept (default all)"))
    every: int | None = field(
        default=None, metadata=about("keep every n-th time step (default 1)", file=int,
                                     ge=1))
    times: ArrayLike | None = field(
        default=None, metadata=about("sample times (default every time step)", "s"))
    rolling_elements: bool = field(
        default=False, metadata=about("keep the load of every rolling element",
                                      file=bool))
    progress: bool = field(default=False, metadata=about("show a progress bar"))
    velocities: bool = field(
        default=False, metadata=about("keep the velocities of the kept DOFs", file=bool))
    reducers: Sequence[str] = field(
        default=(), metadata=about("reductions over the run: max_abs, peak_to_peak (per "
                                   "revolution), max_amplitude (radial), rms", file=list,
                                   choices=REDUCERS))
    after: float | None = field(
        default=None, metadata=about("start of the reductions (default: the start)", "s",
                                     file=float))

    def __post_init__(self) -> None:
        if self.nodes is not None:
            nodes = tuple(self.nodes) if _sequence(self.nodes) else None
            if nodes is None or not all(isinstance(n, numbers.Integral)
                                        and not isinstance(n, bool) for n in nodes):
                raise self._fail("nodes", f"expected node numbers, got {self.nodes!r}")
            object.__setattr__(self, "nodes", nodes)
        if self.every is not None and not check_count(self.every, 1):
            raise self._fail("every", f"must be a positive integer, got {self.every!r}")
        if self.times is not None:
            times = tuple(self.times) if _sequence(self.times) else None  # type: ignore[arg-type]
            if times is None or not all(isinstance(t, numbers.Real) and math.isfinite(t)
                                        for t in times):
                raise self._fail("times", f"expected finite sample times [s], got "
                                          f"{self.times!r}")
            object.__setattr__(self, "times", times)
        self._check_reducers()
        for name in ("rolling_elements", "progress", "velocities"):
            if not isinstance(getattr(self, name), bool):
                raise self._fail(name, f"must be True or False, got {getattr(self, name)!r}")


    def _check_reducers(self) -> None:
        if not _sequence(self.reducers) or not all(isinstance(r, str) for r in self.reducers):
            raise self._fail("reducers", f"expected names of reducers, got {self.reducers!r}")
        reducers = tuple(self.reducers)
        unknown = [r for r in reducers if r not in REDUCERS]
        if unknown or len(set(reducers)) != len(reducers):
            raise self._fail("reducers", f"expected distinct names among "
                                         f"{', '.join(REDUCERS)}; got {list(reducers)}")
        object.__setattr__(self, "reducers", reducers)
        if self.after is not None and not (isinstance(self.after, numbers.Real)
                                           and math.isfinite(self.after)):
            raise self._fail("after", f"expected a finite time [s], got {self.after!r}")



def _sequence(value: object) -> bool:
    return not isinstance(value, str | bytes) and hasattr(value, "__len__") \
        and hasattr(value, "__iter__")
