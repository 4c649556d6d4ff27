"""Figures of bearing statics: load distribution of one equilibrium, stiffness over one
element pass (registered in :data:`rotorsim.plotting.figures.DRAWERS`)."""

from __future__ import annotations

import math
from typing import Any

import matplotlib.pyplot as plt
import numpy as np

STIFFNESS_LABELS = ("x", "y", "z", "rx", "ry")
"""Relative DOFs indexing the stiffness coefficients (``"xy"`` is ``K[0, 1]``)."""
_UNITS = {(0, 0): "N/m", (0, 1): "N/rad", (1, 0): "N", (1, 1): "N m/rad"}


def load_zone_sector(angles: Any, loaded: Any) -> tuple[float, float]:
    """Start angle and extent [rad] of the load zone, each loaded element counting one pitch.

    The zone runs counter-clockwise from half a pitch before the first loaded element after
    the largest gap between loaded elements.

    Examples
    --------
    >>> psi = np.radians([0.0, 90.0, 180.0, 270.0])
    >>> [round(math.degrees(v), 6) for v in load_zone_sector(psi, [True, True, False, False])]
    [-45.0, 180.0]
    """
    psi = np.sort(np.mod(np.asarray(angles, dtype=float)[np.asarray(loaded, dtype=bool)],
                         2.0 * math.pi))
    n = np.asarray(angles).size
    pitch = 2.0 * math.pi / n
    if psi.size == 0:
        return 0.0, 0.0
    if psi.size == n:
        return 0.0, 2.0 * math.pi
    gaps = np.diff(np.concatenate([psi, psi[:1] + 2.0 * math.pi]))
    k = int(np.argmax(gaps))
    start = psi[(k + 1) % psi.size] - 0.5 * pitch
    return float(start), float(min(2.0 * math.pi, 2.0 * math.pi - gaps[k] + pitch))


def load_distribution_figure(result: Any, ax: Any = None, *, title: str | None = None) -> Any:
    """Load distribution of a ``BearingEquilibriumResult``.

    Left: polar bars of the element loads [N] at the element angles (measured from +x towards
    +y), loaded elements in colour, the load zone shaded and the direction of the radial load
    on the inner ring as an arrow. Right: the loaded contact angles [deg] against the element
    angle, with the displacement, the load zone and the largest load in a text box. ``ax`` is
    ignored (two panels).
    """
    fig = plt.figure(figsize=(11, 4.8))
    polar = fig.add_subplot(1, 2, 1, projection="polar")
    right = fig.add_subplot(1, 2, 2)
    psi = np.mod(result.element_angles, 2.0 * math.pi)
    load, loaded = result.element_load, result.loaded
    pitch = 2.0 * math.pi / result.n_elements
    top = max(result.max_element_load, 1e-12) * 1.15
    polar.bar(psi, load, width=0.7 * pitch, color=np.where(loaded, "tab:red", "0.75"),
              edgecolor="k", linewidth=0.5, zorder=3)
    start, extent = load_zone_sector(psi, loaded)
    if extent > 0:
        span = np.linspace(start, start + extent, 200)
        polar.fill_between(span, 0.0, top, color="tab:orange", alpha=0.15, zorder=1,
                           label=f"load zone {math.degrees(extent):.0f} deg")
    fx, fy = float(result.load[0]), float(result.load[1])
    if math.hypot(fx, fy) > 0:
        polar.annotate("", xy=(math.atan2(fy, fx), 0.9 * top), xytext=(0.0, 0.0),
                       arrowprops={"arrowstyle": "->", "color": "tab:blue", "lw": 2})
        polar.plot([], [], color="tab:blue", lw=2, label="radial load direction")
    polar.set_ylim(0.0, top)
    polar.set_title("element loads [N]", fontsize=10)
    polar.legend(loc="lower left", bbox_to_anchor=(-0.15, -0.15), fontsize=8)
    _contact_angle_panel(right, result, psi)
    name = result.summary.get("tag") or result.summary.get("bearing", "bearing")
    fig.suptitle(title or f"load distribution of '{name}'")
    fig.tight_layout()
    return fig


def _contact_angle_panel(ax: Any, result: Any, psi: Any) -> None:
    degrees = np.degrees(psi)
    alpha = np.degrees(result.contact_angle)
    loaded = result.loaded
    order = np.argsort(degrees)
    ax.plot(degrees[order], alpha[order], color="0.6", lw=0.8, zorder=1)
    ax.plot(degrees[loaded], alpha[loaded], "o", color="tab:red", label="loaded", zorder=2)
    ax.plot(degrees[~loaded], alpha[~loaded], "o", mfc="none", mec="0.5", label="unloaded",
            zorder=2)
    ax.set_xlim(0.0, 360.0)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.set_xlabel("element angle [deg]")
    ax.set_ylabel("contact angle [deg]")
    ax.set_title("loaded contact angles", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    d = result.displacement
    text = "\n".join([
        f"x, y, z = {d[0] * 1e6:.3g}, {d[1] * 1e6:.3g}, {d[2] * 1e6:.3g} um",
        f"rx, ry = {d[3] * 1e3:.3g}, {d[4] * 1e3:.3g} mrad",
        f"loaded {result.load_zone.size}/{result.n_elements}, "
        f"zone {math.degrees(result.load_zone_extent):.0f} deg",
        f"Qmax = {result.max_element_load:.4g} N",
    ])
    ax.text(0.02, 0.03, text, transform=ax.transAxes, fontsize=8, va="bottom",
            bbox={"boxstyle": "round", "fc": "white", "alpha": 0.8})


def stiffness_variation_figure(result: Any, ax: Any = None, *,
                               coefficients: tuple[str, ...] = ("xx", "yy", "zz", "xy")) -> Any:
    """Stiffness coefficients of a ``StiffnessVariation`` over one element pass (top) and
    the largest element load (bottom), against the normalised orbital position.

    ``coefficients`` name entries of the 5x5 matrix by their two DOFs (``"xx"``,
    ``"xy"``, ``"zry"`` = ``K[2, 4]``...); coefficients that are zero over the pass are
    left out. ``ax`` is ignored (two panels).
    """
    fig, (upper, lower) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    x = np.concatenate([result.position, [1.0]])  # close the period
    for name in coefficients:
        i, j = _indices(name)
        values = result.stiffness[:, i, j]
        if not np.any(values):
            continue
        unit = _UNITS[(int(i >= 3), int(j >= 3))]
        upper.plot(x, np.concatenate([values, values[:1]]), "-o", ms=3,
                   label=f"K{name} [{unit}]")
    upper.set_ylabel("stiffness")
    upper.set_title(f"stiffness over one element pass ({result.position.size} positions)")
    upper.grid(alpha=0.3)
    upper.legend(fontsize=8)
    q = result.max_element_load
    lower.plot(x, np.concatenate([q, q[:1]]), "-o", ms=3, color="tab:red")
    lower.set_ylabel("largest element load [N]")
    lower.set_xlabel("orbital position (fraction of the element pitch)")
    lower.grid(alpha=0.3)
    return fig


def _indices(name: str) -> tuple[int, int]:
    """``"xy"`` -> (0, 1), ``"rxry"`` -> (3, 4), ``"zry"`` -> (2, 4)."""
    for first in sorted(STIFFNESS_LABELS, key=len, reverse=True):
        rest = name[len(first):]
        if name.startswith(first) and rest in STIFFNESS_LABELS:
            return STIFFNESS_LABELS.index(first), STIFFNESS_LABELS.index(rest)
    raise TypeError(f"unknown stiffness coefficient {name!r}; use two of {STIFFNESS_LABELS}, "
                    "e.g. 'xx' or 'zry'")
