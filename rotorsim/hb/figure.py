"""Figure of a :class:`~rotorsim.hb.result.FrequencyResponse` (matplotlib, imported lazily
through :func:`rotorsim.plotting.units.figure_axes`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from rotorsim.plotting.units import figure_axes

MARKERS = {"fold": ("o", "tab:red"), "branch_point": ("D", "tab:purple"),
           "period_doubling": ("s", "tab:orange"), "neimark_sacker": ("^", "tab:cyan")}


def response_figure(result: Any, dof: int = 0, measure: str = "fundamental",
                    ax: Any = None) -> Any:
    """Amplitude of ``dof`` against frequency: stable points solid, unstable dashed, the
    bifurcations marked by kind; returns the Figure."""
    fig, ax = figure_axes(ax, figsize=(7, 4.5))
    a = result.amplitude(dof, measure)
    w = result.omega
    if result.stable is None:
        ax.plot(w, a, "-", color="tab:blue", lw=1.2, label="HB")
    else:
        stable = np.asarray(result.stable)
        for flag, style, label in ((True, "-", "stable"), (False, "--", "unstable")):
            on = stable == flag
            on[1:] |= on[:-1].copy()      # each segment reaches the next point: no gaps
            ax.plot(w, np.where(on, a, np.nan), style, color="tab:blue", lw=1.2,
                    label=label)
    seen = set()
    for b in result.bifurcations:
        marker, color = MARKERS.get(b.kind, ("x", "k"))
        ax.plot(b.omega, b.amplitude(dof, measure), marker, color=color, ms=7,
                label=None if b.kind in seen else b.kind.replace("_", " "))
        seen.add(b.kind)
    ax.set_xlabel("frequency Omega [rad/s]")
    ax.set_ylabel(f"{measure.replace('_', ' ')} amplitude of DOF {dof}")
    ax.set_title(f"harmonic balance, H = {result.harmonics}, N = {result.samples}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig
