"""The option arguments of the periodic verbs as resolved option groups.

:func:`periodic_options` turns the keywords of :func:`~rotorsim.analyses.periodic.periodic.
periodic` and :func:`~rotorsim.analyses.periodic.parameter.periodic_parameter` (a plain
value or a group of :mod:`rotorsim.options`, and the shortcut keywords ``unbalance=`` and
``nodes=``) into :class:`PeriodicOptions`: every group complete, its fields left at None
filled with the verb's defaults, and fields the verb does not use refused by name.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from rotorsim.analyses.periodic.branch import Stepping
from rotorsim.analyses.periodic.excitation import HarmonicBase
from rotorsim.errors import ModelError
from rotorsim.options import (
    Checkpointing,
    ContinuationOptions,
    Excitation,
    Harmonics,
    Output,
    StabilityOptions,
)
from rotorsim.solvers.continuation import Continuation


@dataclass(frozen=True)
class PeriodicDefaults:
    """The defaults of one periodic verb, for the group fields left at None."""

    continuation: ContinuationOptions
    stability: StabilityOptions
    checkpoint: Checkpointing
    unused: dict[str, tuple[str, ...]]
    """Group fields the verb does not use: ``{keyword: (field, ...)}``."""


@dataclass(frozen=True)
class PeriodicOptions:
    """The resolved groups of one call (every field set)."""

    harmonics: Harmonics
    excitation: Excitation
    continuation: ContinuationOptions
    stability: StabilityOptions
    output: Output
    checkpoint: Checkpointing

    @property
    def base(self) -> HarmonicBase | None:
        """The housing motion (checked to be a HarmonicBase)."""
        return self.excitation.base  # type: ignore[return-value]

    @property
    def checkpoint_every(self) -> int:
        """Points between checkpoints (the verb's default filled in)."""
        assert self.checkpoint.every is not None
        return int(self.checkpoint.every)

    def stepping(self) -> Stepping:
        """The continuation settings of the branch (the verb's defaults filled in)."""
        c = self.continuation
        return Stepping(c.step, c.max_step, c.max_points, c.tol, c.solver)


def periodic_options(verb: str, defaults: PeriodicDefaults, *, harmonics: int | Harmonics,
                     unbalance: Sequence[tuple[int, float, float]],
                     excitation: Excitation | None,
                     continuation: ContinuationOptions | None,
                     stability: str | StabilityOptions | None,
                     nodes: Sequence[int] | None, output: Output | None,
                     checkpoint: str | os.PathLike[str] | Checkpointing | None
                     ) -> PeriodicOptions:
    """Resolve the option keywords of ``verb`` (errors name ``<verb>.<keyword>``)."""
    groups: dict[str, Any] = {
        "harmonics": Harmonics.coerce(harmonics, f"{verb}.harmonics"),
        "excitation": Excitation.coerce(excitation, f"{verb}.excitation").merged(
            verb, unbalance=unbalance),
        "continuation": ContinuationOptions.coerce(continuation, f"{verb}.continuation"),
        "stability": StabilityOptions.coerce(stability, f"{verb}.stability"),
        "output": Output.coerce(output, f"{verb}.output").merged(verb, nodes=nodes),
        "checkpoint": Checkpointing.coerce(checkpoint, f"{verb}.checkpoint"),
    }
    for keyword, names in defaults.unused.items():
        groups[keyword].refuse(names, f"{verb}.{keyword}", verb)
    for keyword in ("continuation", "stability", "checkpoint"):
        groups[keyword] = groups[keyword].resolved(getattr(defaults, keyword))
    base = groups["excitation"].base
    if base is not None and not isinstance(base, HarmonicBase):
        raise ModelError(f"expected rs.HarmonicBase, got {type(base).__name__}",
                         f"{verb}.excitation.base")
    solver = groups["continuation"].solver
    if solver is not None and not isinstance(solver, Continuation):
        raise ModelError(f"expected rotorsim.solvers.continuation.Continuation, got "
                         f"{type(solver).__name__}", f"{verb}.continuation.solver")
    return PeriodicOptions(**groups)


PARAMETERS = ("speed", "frequency")
"""Continuation parameters of ``rs.periodic``."""


def check_parameter(where: str, parameter: str, start: float, stop: float,
                    speed: float | None) -> bool:
    """True for frequency continuation (``parameter="frequency"``), False for the speed;
    ModelError for bad values, TypeError for an unknown parameter."""
    if parameter not in PARAMETERS:
        raise TypeError(f"unknown parameter {parameter!r}; valid: {', '.join(PARAMETERS)}")
    for name, value in (("start", start), ("stop", stop)):
        if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
            raise ModelError(f"must be a positive number [rad/s], got {value!r}",
                             f"{where}.{name}")
    if start == stop:
        raise ModelError(f"start and stop are equal ({start})", where)
    frequency = parameter == "frequency"
    if frequency and not (isinstance(speed, int | float) and math.isfinite(speed)):
        raise ModelError("parameter='frequency' needs a fixed speed [rad/s]",
                         f"{where}.speed")
    if not frequency and speed is not None:
        raise ModelError("speed is the continuation parameter; give start and stop",
                         f"{where}.speed")
    return frequency
