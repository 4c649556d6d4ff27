"""Figure of a :class:`~rotorsim.results.bearing_life.BearingLifeResult`: contact pressures
of every rolling element and the lives."""

from __future__ import annotations

import math
from typing import Any

import matplotlib.pyplot as plt
import numpy as np


def bearing_life_figure(result: Any, ax: Any = None, *, title: str | None = None) -> Any:
    """Largest Hertz pressure of every element on the inner and outer race [MPa] against
    the element angle (left, with the lives in a text box) and, right, the pressure along
    the most loaded roller (slices, edge slices included) or the contact-ellipse semi-axes
    of every ball. ``ax`` is ignored (two panels)."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    angle = np.degrees(np.mod(result.element_angles, 2.0 * math.pi))
    order = np.argsort(angle)
    p = result.max_pressure / 1e6
    for race, style in ((0, "o-"), (1, "s--")):
        left.plot(angle[order], p[order, race], style, ms=4,
                  label=("inner" if race == 0 else "outer") + " race")
    left.set_xlabel("element angle [deg]")
    left.set_ylabel("max Hertz pressure [MPa]")
    left.grid(alpha=0.3)
    left.legend(fontsize=8)
    lines = [f"L10r = {_fmt(result.L10r)} Mrev", f"P_ref = {_fmt(result.P_ref)} N"]
    if math.isfinite(result.L10):
        lines.append(f"L10 (ISO 281) = {_fmt(result.L10)} Mrev")
    if result.a_iso != 1.0:
        lines.append(f"a_ISO = {result.a_iso:.3g}, Lnmr = {_fmt(result.Lnmr)} Mrev")
    left.text(0.5, 0.97, "\n".join(lines), transform=left.transAxes, va="top", ha="center",
              fontsize=8,
              bbox={"boxstyle": "round", "fc": "white", "alpha": 0.8})
    if result.slice_pressure.size:
        j = int(np.argmax(result.max_pressure[:, 0]))
        for race, style in ((0, "o-"), (1, "s--")):
            right.plot(result.slice_xi, result.slice_pressure[j, :, race] / 1e6, style, ms=3,
                       label=("inner" if race == 0 else "outer") + " race")
        right.set_xlabel("position along the roller [fraction of the length]")
        right.set_ylabel("Hertz line-contact pressure [MPa]")
        right.set_title(f"most loaded roller ({angle[j]:.0f} deg)", fontsize=10)
    else:
        for race, style in ((0, "o-"), (1, "s--")):
            name = "inner" if race == 0 else "outer"
            right.plot(angle[order], result.semi_major[order, race] * 1e3, style, ms=4,
                       label=f"a ({name})")
            right.plot(angle[order], result.semi_minor[order, race] * 1e3, style, ms=4,
                       alpha=0.5, label=f"b ({name})")
        right.set_xlabel("element angle [deg]")
        right.set_ylabel("contact-ellipse semi-axis [mm]")
        if result.truncated:
            right.set_title("ellipse truncated at a shoulder", fontsize=10, color="tab:red")
    right.grid(alpha=0.3)
    right.legend(fontsize=8)
    name = result.summary.get("tag") or result.summary.get("bearing", "bearing")
    fig.suptitle(title or f"contact pressures and life of '{name}' ({result.source})")
    fig.tight_layout()
    return fig


def _fmt(value: float) -> str:
    return f"{value:.4g}" if math.isfinite(value) else "-"
