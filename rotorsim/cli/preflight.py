"""Checks of a model file's analyses that need no computation, made before any of them runs
(``rotorsim info`` and ``rotorsim run``): a failure then costs nothing, and notes on what
an analysis will assume are printed up front."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np


def transient_notes(model: Any, jobs: Sequence[tuple[str, Any]]) -> list[str]:
    """Check the transient analyses among ``jobs`` (``(name, spec or None)``) against the
    model's speed-dependent linear bearings; notes to print.

    Raises
    ------
    ModelError
        When a run at varying speed meets a bearing whose added mass varies with speed.
    """
    bearings = [b for b in model.rotor.bearing_elements if b.speed_dependent]
    if not bearings:
        return []
    from rotorsim.analyses.transient.variable_bearings import speed_range_notes

    notes = []
    for name, given in jobs:
        spec = given if given is not None else model.analyses.get(name)
        if getattr(spec, "type", None) != "transient":
            continue
        w0 = float(spec.speed)
        w1 = w0 if spec.speed_stop is None else float(spec.speed_stop)
        if getattr(spec, "drive", None) is not None:
            # a torque drive's speeds are known only once its spin equation is solved:
            # check what does not depend on them
            speed_range_notes(bearings, 0.0, np.inf, f"analysis {name!r}")
            continue
        for note in speed_range_notes(bearings, min(w0, w1), max(w0, w1),
                                      f"analysis {name!r}"):
            notes.append(f"{name}: {note}")
    return notes
