"""Amplitude peaks of a rotor's periodic branch (``periodic(..., peaks=[(node, dof)])``).

Each request ``(node, dof)`` names one DOF (``max |q(t)|``) or, with ``dof="orbit"``, the
lateral orbit of a node (largest radius of ``(ux, uy)``); its extrema along the branch are
located by :func:`~rotorsim.harmonic_balance.peaks.locate_peaks` (the sign changes of
``da/ds`` refined by the Illinois method with the corrector) and stored as
:class:`~rotorsim.results.periodic.PeriodicPeak` records. Nothing is computed when no peak
is requested.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from rotorsim.analyses.periodic.problem import RotorPeriodicProblem
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOF_NAMES
from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.peaks import locate_peaks
from rotorsim.harmonic_balance.residual import HBResidual
from rotorsim.results.periodic import PeriodicPeak
from rotorsim.solvers.continuation import Branch

MEASURES = (*DOF_NAMES, "orbit")
"""What a peak request may measure: one DOF, or a node's lateral orbit."""


def peak_columns(system: RotorSystem, rp: RotorPeriodicProblem,
                 requests: Sequence[tuple[int, str]], where: str) -> list[Any]:
    """Active-DOF columns of each request (ModelError naming a bad one)."""
    out = []
    for i, request in enumerate(requests):
        try:
            node, dof = request
        except (TypeError, ValueError):
            raise ModelError(f"peaks[{i}] must be (node, dof), got {request!r}",
                             where) from None
        if dof not in MEASURES:
            raise ModelError(f"peaks[{i}]: unknown dof {dof!r}; valid: "
                             f"{', '.join(MEASURES)}", where)
        names = ("ux", "uy") if dof == "orbit" else (dof,)
        free = [system.dof_map.free_index(int(node), name) for name in names]
        cols = np.searchsorted(rp.active, free)
        if np.any(cols >= rp.active.size) or np.any(rp.active[np.minimum(
                cols, rp.active.size - 1)] != free):
            raise ModelError(f"peaks[{i}]: DOF {dof!r} of node {node} is held (a free rigid "
                             "motion)", where)
        out.append(cols)
    return out


def peak_records(residual: HBResidual, branch: Branch, system: RotorSystem,
                 rp: RotorPeriodicProblem, requests: Sequence[tuple[int, str]],
                 to_parameter: Callable[[float], float], where: str
                 ) -> tuple[PeriodicPeak, ...]:
    """The located peaks (maxima) of every request, in request order then along the
    branch."""
    out = []
    for (node, dof), cols in zip(requests, peak_columns(system, rp, requests, where),
                                 strict=True):
        for e in locate_peaks(residual, branch, cols):
            out.append(PeriodicPeak(int(node), str(dof), e.kind, float(to_parameter(e.lam)),
                                    float(e.value), int(e.index), bool(e.located)))
    return tuple(out)
