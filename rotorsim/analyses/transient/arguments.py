"""Checks of the plain arguments of :func:`~.transient.transient`: the model, the time
span and the step count."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from rotorsim.assembly.system import RotorSystem, assemble
from rotorsim.elements.base import NonlinearElement
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor

WHERE = "transient"


def system_of(model: Rotor | RotorSystem, nonlinear: Sequence[NonlinearElement]) -> RotorSystem:
    if isinstance(model, RotorSystem):
        if nonlinear:
            raise ModelError("give the nonlinear elements to assemble(), or a Rotor here",
                             WHERE)
        return model
    if not isinstance(model, Rotor):
        raise ModelError(f"expected a Rotor or RotorSystem, got {type(model).__name__}",
                         WHERE)
    return assemble(model, nonlinear=tuple(nonlinear))


MAX_STEPS = 10**9
"""Largest number of time steps of one run: more is a unit slip (``dt`` in s, not us), not
a run that would end in any reasonable time."""


def check_step_count(dt: float, duration: float) -> None:
    """Refuse a step longer than the run, or so short that the run would never end."""
    if dt > duration:
        raise ModelError(f"dt {dt} s exceeds the duration {duration} s: check the units",
                         f"{WHERE}.dt")
    if duration / dt > MAX_STEPS:
        raise ModelError(f"dt {dt} s gives {duration / dt:.3g} steps over {duration} s, more "
                         f"than {MAX_STEPS:.0e}: check the units", f"{WHERE}.dt")


def time_span(t_span: float | Sequence[float]) -> tuple[float, float]:
    values: list[Any] = [0.0, t_span] if np.ndim(t_span) == 0 else list(t_span)  # type: ignore[arg-type]
    try:
        t0, t_end = (float(x) for x in values)
    except (TypeError, ValueError):
        raise ModelError(f"t_end must be a time or (t0, t_end), got {t_span!r}",
                         WHERE) from None
    if not (np.isfinite(t0) and np.isfinite(t_end) and t_end > t0):
        raise ModelError(f"t_end must be finite and after t0, got {t_span!r}", f"{WHERE}.t_end")
    return t0, t_end
