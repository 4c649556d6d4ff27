"""Figures of periodic-response branches (:class:`~rotorsim.results.periodic.PeriodicResult`).

* :func:`frequency_response_figure`: amplitude against the parameter, stable segments solid,
  unstable dashed, bifurcation markers (fold, branch point, period doubling,
  Neimark-Sacker);
* :func:`multiplier_figure`: largest Floquet multiplier modulus against the parameter
  (stability map, seed 002 Fig. 3.19);
* :func:`harmonics_figure`: amplitude of each harmonic against the parameter (seed 002
  Figs. 3.17-3.18, 3.20-3.26);
* :func:`periodic_orbit_figure` and :func:`harmonic_content_figure`: the orbit and the
  harmonic content at one point;
* :func:`periodic_figure`: the standard 2 x 2 figure of ``rotorsim.plot(result)``.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from rotorsim.plotting.units import amplitude_scale, figure_axes, speed_factor

EVENT_STYLE = {
    "fold": {"marker": "o", "color": "tab:red", "label": "fold"},
    "branch_point": {"marker": "s", "color": "tab:purple", "label": "branch point"},
    "period_doubling": {"marker": "D", "color": "tab:orange", "label": "period doubling"},
    "neimark_sacker": {"marker": "^", "color": "tab:green", "label": "Neimark-Sacker"},
}


def responsive_node(result: Any) -> int:
    """Kept node with the largest lateral (ux/uy) peak-to-peak anywhere on the branch."""
    local = result.dofs % 6
    lateral = local < 2
    if not lateral.any():
        return int(result.dofs[0] // 6)
    best = np.argmax(np.where(lateral, result.peak_to_peak.max(axis=0), -1.0))
    return int(result.dofs[best] // 6)


def _at(result: Any, point: int) -> str:
    """``"1234.5 rad/s"`` (speed, frequency) or ``"<name> = value"`` (model parameter)."""
    value = float(result.parameter[point])
    if result.parameter_name in ("speed", "frequency"):
        return f"{value:.5g} rad/s"
    return f"{result.parameter_name} = {value:.5g}"


def _parameter_factor(result: Any, units: str) -> float:
    """Display factor of the parameter: speed units for speed and frequency branches, 1 for
    a model parameter (shown in its own units)."""
    if result.parameter_name not in ("speed", "frequency"):
        return 1.0
    return float(speed_factor(units))


def _parameter_label(result: Any, units: str) -> str:
    if result.parameter_name not in ("speed", "frequency"):
        return str(result.parameter_name)  # a model parameter (rs.periodic_parameter)
    name = "spin speed" if result.parameter_name == "speed" else "excitation frequency"
    return f"{name} [{units}]"


def _note(ax: Any, result: Any) -> None:
    if result.approximation:
        ax.text(0.01, 0.01, "\n".join(textwrap.wrap(result.approximation, 70)), fontsize=6,
                color="0.35", transform=ax.transAxes, va="bottom")


def frequency_response_figure(result: Any, ax: Any = None, *, node: int | None = None,
                              dof: str = "uy", measure: str = "peak_to_peak",
                              units: str = "rad/s", amplitude_units: str = "um",
                              label: str | None = None, color: str | None = None) -> Any:
    """Amplitude of ``(node, dof)`` against the parameter: stable solid, unstable dashed
    (all solid without a stability analysis), bifurcations marked."""
    f, scale = _parameter_factor(result, units), amplitude_scale(amplitude_units)
    fig, ax = figure_axes(ax, figsize=(8, 5))
    node = responsive_node(result) if node is None else node
    p = result.parameter * f
    a = result.amplitude(node, dof, measure) * scale
    stable = result.stable if result.has_stability else np.ones(p.size, dtype=bool)
    color = color or "tab:blue"
    breaks = np.flatnonzero(stable[1:] != stable[:-1]) + 1
    for seg in np.split(np.arange(p.size), breaks):
        stop = min(seg[-1] + 2, p.size)          # join the segment to the next point
        ax.plot(p[seg[0]:stop], a[seg[0]:stop], "-" if stable[seg[0]] else "--",
                color=color, lw=1.4)
    ax.plot([], [], "-", color=color, label=label or f"{node}:{dof} stable")
    if result.has_stability and not stable.all():
        ax.plot([], [], "--", color=color, label="unstable")
    if measure != "mean":
        _mark_events(ax, result, result.column(node, dof), measure, f, scale)
    ax.set_xlabel(_parameter_label(result, units))
    ax.set_ylabel(f"{measure.replace('_', '-')} of {node}:{dof} [{amplitude_units}]")
    ax.set_title(f"periodic response (H = {result.harmonics})")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _note(ax, result)
    return fig


def _mark_events(ax: Any, result: Any, j: int, measure: str, f: float, scale: float) -> None:
    """One marker per bifurcation at its amplitude (each kind labelled once)."""
    shown: set[str] = set()
    for b in result.bifurcations:
        value = b.max_abs[j] if measure == "max" else b.peak_to_peak[j] * (
            0.5 if measure == "half_peak_to_peak" else 1.0)
        style = dict(EVENT_STYLE.get(b.kind, {"marker": "x", "color": "k", "label": b.kind}))
        if style["label"] in shown:
            style.pop("label")
        else:
            shown.add(str(style["label"]))
        ax.plot(b.parameter * f, value * scale, ls="none", mfc="none", ms=8, mew=1.5, **style)


def multiplier_figure(result: Any, ax: Any = None, *, units: str = "rad/s") -> Any:
    """``max |mu|`` against the parameter with the stability limit ``1 + tol``."""
    f = _parameter_factor(result, units)
    fig, ax = figure_axes(ax, figsize=(8, 4))
    if not result.has_stability:
        ax.text(0.5, 0.5, "no stability analysis", ha="center", va="center",
                transform=ax.transAxes)
        return fig
    p, m = result.parameter * f, result.max_multiplier
    ax.plot(p, m, ".-", lw=0.8, ms=3, color="0.3", label="max |mu|")
    unstable = ~result.stable
    ax.plot(p[unstable], m[unstable], "o", ms=3, color="tab:red", label="unstable")
    ax.axhline(1.0 + result.stability_tol, color="tab:red", lw=0.8, ls=":")
    ax.set_xlabel(_parameter_label(result, units))
    ax.set_ylabel("largest Floquet multiplier |mu|")
    ax.set_title(f"stability ({result.stability_method})")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def harmonics_figure(result: Any, ax: Any = None, *, node: int | None = None,
                     dof: str = "uy", harmonics: Sequence[int] | None = None,
                     units: str = "rad/s", amplitude_units: str = "um",
                     log: bool = True) -> Any:
    """``|X_h|`` of ``(node, dof)`` for each harmonic ``h`` against the parameter (harmonic
    0 is the mean, drawn as ``|mean|``); unstable points dimmed."""
    f, scale = _parameter_factor(result, units), amplitude_scale(amplitude_units)
    fig, ax = figure_axes(ax, figsize=(8, 5))
    node = responsive_node(result) if node is None else node
    hs = range(1, min(result.harmonics, 6) + 1) if harmonics is None else harmonics
    p = result.parameter * f
    stable = result.stable if result.has_stability else np.ones(p.size, dtype=bool)
    for h in hs:
        amp = np.abs(result.harmonic(node, dof, int(h))) * scale
        line, = ax.plot(p, np.where(stable, amp, np.nan), lw=1.2, label=f"h = {h}")
        ax.plot(p, np.where(stable, np.nan, amp), ":", lw=1.0, color=line.get_color())
    if log:
        ax.set_yscale("log")
    ax.set_xlabel(_parameter_label(result, units))
    ax.set_ylabel(f"|X_h| of {node}:{dof} [{amplitude_units}]")
    ax.set_title(f"harmonic content (order {result.order:.4g}), dotted: unstable"
                 if result.order else "harmonic content, dotted: unstable")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, ncol=2)
    return fig


def periodic_orbit_figure(result: Any, ax: Any = None, *, point: int | None = None,
                          node: int | None = None, amplitude_units: str = "um") -> Any:
    """Orbit ``(ux, uy)`` of ``node`` over one period at ``point`` (default: the largest
    response)."""
    scale = amplitude_scale(amplitude_units)
    fig, ax = figure_axes(ax, figsize=(5.5, 5.5))
    node = responsive_node(result) if node is None else node
    point = _largest(result, node) if point is None else point
    x, y = result.orbit(point, node, 512)
    ax.plot(x * scale, y * scale, lw=1.0)
    ax.plot(x[0] * scale, y[0] * scale, "o", ms=4, color="tab:green", label="tau = 0")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"ux [{amplitude_units}]")
    ax.set_ylabel(f"uy [{amplitude_units}]")
    state = "" if not result.has_stability else (
        ", stable" if result.stable[point] else ", unstable")
    ax.set_title(f"orbit of node {node} at {_at(result, point)}{state}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def harmonic_content_figure(result: Any, ax: Any = None, *, point: int | None = None,
                            node: int | None = None, dofs: Sequence[str] = ("ux", "uy"),
                            amplitude_units: str = "um", log: bool = True) -> Any:
    """Bar chart of ``|X_h|``, ``h = 0..H``, of ``dofs`` of ``node`` at ``point``."""
    scale = amplitude_scale(amplitude_units)
    fig, ax = figure_axes(ax, figsize=(7, 4))
    node = responsive_node(result) if node is None else node
    point = _largest(result, node) if point is None else point
    h = np.arange(result.harmonics + 1)
    width = 0.8 / max(len(dofs), 1)
    for k, dof in enumerate(dofs):
        amp = result.harmonic_amplitudes(point, node, dof) * scale
        ax.bar(h + (k - (len(dofs) - 1) / 2) * width, amp, width, label=f"{node}:{dof}")
    if log:
        ax.set_yscale("log")
    ax.set_xticks(h)
    ax.set_xlabel("harmonic h of the fundamental")
    ax.set_ylabel(f"|X_h| [{amplitude_units}]")
    ax.set_title(f"harmonic content at {_at(result, point)} "
                 f"(omega = {result.fundamental[point]:.5g} rad/s)")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8)
    return fig


def _largest(result: Any, node: int) -> int:
    return int(np.argmax(result.amplitude(node, "uy", "peak_to_peak")))


def periodic_figure(result: Any, ax: Any = None, *, node: int | None = None,
                    dof: str = "uy", units: str = "rad/s", amplitude_units: str = "um",
                    point: int | None = None) -> Any:
    """Standard figure: response curve, stability, orbit and harmonic content at ``point``
    (default the largest response); with ``ax`` only the response curve."""
    if ax is not None:
        return frequency_response_figure(result, ax, node=node, dof=dof, units=units,
                                         amplitude_units=amplitude_units)
    fig, axes = plt.subplots(2, 2, figsize=(13, 9))
    node = responsive_node(result) if node is None else node
    point = _largest(result, node) if point is None else point
    frequency_response_figure(result, axes[0, 0], node=node, dof=dof, units=units,
                              amplitude_units=amplitude_units)
    multiplier_figure(result, axes[0, 1], units=units)
    periodic_orbit_figure(result, axes[1, 0], point=point, node=node,
                          amplitude_units=amplitude_units)
    harmonic_content_figure(result, axes[1, 1], point=point, node=node,
                            amplitude_units=amplitude_units)
    fig.tight_layout()
    return fig
