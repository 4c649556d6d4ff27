"""Varying-compliance orders of rolling bearings, shared by the periodic and quasi-periodic
analyses: a bearing of ``Z`` rolling elements whose cage turns at ``kappa W`` repeats its
stiffness at ``Z kappa W`` (seed 000, the VC frequency)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any


def vc_orders(elements: Sequence[Any]) -> list[float]:
    """Varying-compliance orders ``Z kappa`` of the rolling bearings whose cages turn."""
    out = []
    for el in elements:
        bearing = getattr(el, "bearing", None)
        z, kappa = getattr(bearing, "n_elements", 0), getattr(bearing, "kappa", 0.0)
        # with both rings turning (an inter-shaft bearing) the cage's own speed ratio
        kappa = abs(float(getattr(el, "cage_speed_ratio", kappa)))
        if z and kappa:
            out.append(float(z) * float(kappa))
    return out
