"""Figure functions, one per result type (registered in :data:`DRAWERS`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from rotorsim.plotting.api_figures import api_unbalance_figure, level1_figure
from rotorsim.plotting.bearing_figures import (
    load_distribution_figure,
    stiffness_variation_figure,
)
from rotorsim.plotting.layout import rotor_layout_figure
from rotorsim.plotting.life_figures import bearing_life_figure
from rotorsim.plotting.periodic_figures import periodic_figure
from rotorsim.plotting.quasi_periodic_figures import quasi_periodic_figure
from rotorsim.plotting.transient_figures import (
    order_track_figure,
    spectrum_figure,
    transient_figure,
    waterfall_figure,
)
from rotorsim.plotting.units import speed_factor

WHIRL_STYLE = {
    "forward": {"marker": "^", "color": "tab:red", "label": "forward"},
    "backward": {"marker": "v", "color": "tab:blue", "label": "backward"},
    "mixed": {"marker": "o", "color": "tab:gray", "label": "mixed"},
    "none": {"marker": "s", "color": "tab:green", "label": "axial/torsional"},
}


def _axes(ax: Any, nrows: int = 1, ncols: int = 1, **kw: Any) -> tuple[Any, Any]:
    if ax is not None:
        return ax.figure, ax
    fig, axes = plt.subplots(nrows, ncols, **kw)
    return fig, axes


def campbell_figure(result: Any, ax: Any = None, *, units: str = "rpm",
                    harmonics: tuple[float, ...] = (1,), color_by: str | None = None,
                    annotate: bool = True) -> Any:
    """Campbell diagram: damped frequencies vs speed, whirl marked, kX lines, criticals.

    ``color_by="log_dec"`` colours points by logarithmic decrement instead of whirl.
    """
    f = speed_factor(units)
    fig, ax = _axes(ax, figsize=(8, 5.5))
    speeds = result.speeds * f
    wd = result.wd * f
    for j in range(wd.shape[1]):
        ax.plot(speeds, wd[:, j], color="0.75", lw=0.8, zorder=1)
    if color_by == "log_dec":
        grid = np.broadcast_to(speeds[:, None], wd.shape)
        sc = ax.scatter(grid, wd, c=np.clip(result.log_dec, -1, 3), cmap="RdYlGn", s=12,
                        zorder=2)
        fig.colorbar(sc, ax=ax, label="log dec")
    else:
        whirl = np.asarray(result.whirl)
        for name, style in WHIRL_STYLE.items():
            mask = whirl == name
            if mask.any():
                grid = np.broadcast_to(speeds[:, None], wd.shape)
                ax.scatter(grid[mask], wd[mask], s=14, zorder=2, **style)
    top = np.nanmax(wd) * 1.05
    ratios = result.summary.get("line_speed_ratios") or {None: 1.0}
    spools = [(name, r) for name, r in ratios.items() if r != 0]
    dashes = ("--", "-.", ":", (0, (5, 1, 1, 1)))
    for k, (j, (spool, r)) in ((k, sp) for k in harmonics for sp in enumerate(spools)):
        dash = dashes[j % len(dashes)]  # one dash pattern per spool
        label = f"{k:g}X" if spool is None else f"{k:g}X {spool}"
        ax.plot(speeds, k * abs(r) * speeds, color="k", ls=dash, lw=1, label=label)
        if annotate:
            crit = result.critical_speeds(harmonic=k, spool=spool)
            span = float(speeds.max() - speeds.min()) or 1.0
            groups: list[list[float]] = []  # crossings closer than 3 % of the axis share a label
            for s in np.sort(crit.speed * f):
                if groups and s - groups[-1][-1] < 0.03 * span:
                    groups[-1].append(s)
                else:
                    groups.append([s])
            ax.plot(crit.speed * f, crit.frequency * f, "o", mfc="none", mec="k", ms=9)
            for g in groups:
                ax.annotate("/".join(f"{s:.0f}" for s in g), (g[0], k * abs(r) * g[0]),
                            textcoords="offset points", xytext=(4, -12), fontsize=8)
    ax.set_ylim(0, top)
    ax.set_xlim(speeds.min(), speeds.max())
    ax.set_xlabel(f"rotor speed [{units}]")
    ax.set_ylabel(f"damped natural frequency [{units}]")
    ax.set_title("Campbell diagram")
    handles, labels = ax.get_legend_handles_labels()
    unique = dict(zip(labels, handles, strict=True))
    ax.legend(unique.values(), unique.keys(), loc="upper left", fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def mode_shape_figure(result: Any, ax: Any = None, *, mode: int = 0, view: str = "2d",
                      units: str = "Hz") -> Any:
    """Mode shape: real parts in the x-z and y-z planes (2d) or node orbits along z (3d)."""
    f = speed_factor(units)
    ux, uy = result.lateral_shape(mode)
    z = result.nodes_pos
    order = np.argsort(z)
    title = (f"mode {mode}: {result.wd[mode] * f:.2f} {units}, {result.whirl[mode]}, "
             f"log dec {result.log_dec[mode]:.3f}")
    if view == "3d":
        fig = plt.figure(figsize=(8, 5)) if ax is None else ax.figure
        ax3 = fig.add_subplot(projection="3d") if ax is None else ax
        t = np.linspace(0, 2 * np.pi, 60)
        ring = np.exp(1j * t)
        for zi, x, y in zip(z, ux, uy, strict=True):
            ax3.plot(np.full(t.size, zi), (x * ring).real, (y * ring).real, lw=0.8)
        ax3.plot(z[order], ux.real[order], uy.real[order], "k-o", ms=3)
        ax3.set_xlabel("z [m]")
        ax3.set_ylabel("x")
        ax3.set_zlabel("y")
        ax3.set_title(title)
        return fig
    fig, ax = _axes(ax, figsize=(8, 4))
    ax.plot(z[order], ux.real[order], "-o", ms=3, label="x (Re ux)")
    ax.plot(z[order], uy.real[order], "-s", ms=3, label="y (Re uy)")
    ax.plot(z[order], np.abs(ux[order] + 0j), ":", color="0.5", label="|ux|")
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("z [m]")
    ax.set_ylabel("normalised displacement")
    ax.set_title(title)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def bode_figure(result: Any, ax: Any = None, *, node: int | None = None,
                dofs: tuple[str, ...] = ("ux", "uy"), input: int = 0, units: str = "rpm",
                polar: bool = False, amplitude_units: str = "um") -> Any:
    """Bode plot (amplitude and phase vs frequency) or polar plot of one node's response.

    ``node`` defaults to the node with the largest response.
    """
    f = speed_factor(units)
    scale = {"m": 1.0, "mm": 1e3, "um": 1e6}[amplitude_units]
    if node is None:
        amp = np.nan_to_num(np.abs(result.response[:, :, input]))
        node = int(np.argmax(amp.max(axis=0).reshape(-1, 6)[:, :2].max(axis=1)))
    x = result.frequencies * f
    if polar:
        fig, ax = _axes(ax, figsize=(6, 6))
        for dof in dofs:
            z = result.complex(node, dof, input) * scale
            ax.plot(z.real, z.imag, "-", label=dof)
            ax.plot(z.real[0], z.imag[0], "ko", ms=3)
        ax.set_aspect("equal")
        ax.axhline(0, color="k", lw=0.5)
        ax.axvline(0, color="k", lw=0.5)
        ax.set_xlabel(f"Re [{amplitude_units}]")
        ax.set_ylabel(f"Im [{amplitude_units}]")
        ax.set_title(f"polar plot, node {node}")
        ax.legend(fontsize=8)
        return fig
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    for dof in dofs:
        top.semilogy(x, result.amplitude(node, dof, input) * scale, label=dof)
        bottom.plot(x, np.degrees(np.unwrap(result.phase(node, dof, input))), label=dof)
    top.set_ylabel(f"amplitude [{amplitude_units}]")
    bottom.set_ylabel("phase [deg]")
    bottom.set_xlabel(f"{'speed' if result.kind == 'unbalance' else 'frequency'} [{units}]")
    top.set_title(f"{result.kind} response, node {node}")
    for a in (top, bottom):
        a.grid(alpha=0.3, which="both")
        a.legend(fontsize=8)
    return fig


def static_figure(result: Any, ax: Any = None) -> Any:
    """Static deflection, shear force and bending moment along the shaft."""
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8, 8))
    n_shaft = result.summary.get("shaft_elements", len(result.nodes_pos) - 1) + 1
    z = result.nodes_pos[:n_shaft]
    for dof in ("ux", "uy"):
        axes[0].plot(z, result.deflection(dof)[:n_shaft] * 1e6, "-o", ms=3, label=dof)
    axes[0].set_ylabel("deflection [um]")
    if result.shear_force is not None:
        ez = result.element_z.ravel()
        for i, name in enumerate(("x", "y")):
            axes[1].plot(ez, result.shear_force[..., i].ravel(), label=f"V{name}")
            axes[2].plot(ez, result.bending_moment[..., i].ravel(), label=f"M{name}")
    axes[1].set_ylabel("shear force [N]")
    axes[2].set_ylabel("bending moment [N m]")
    axes[2].set_xlabel("z [m]")
    axes[0].set_title("static deflection and section forces")
    for a in axes:
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    return fig


def critical_speed_map_figure(result: Any, ax: Any = None, *, units: str = "rpm") -> Any:
    """Critical speeds vs support stiffness (log-log), bearing curves and intersections."""
    f = speed_factor(units)
    fig, ax = _axes(ax, figsize=(7, 5.5))
    for j in range(result.critical_speeds.shape[1]):
        ax.loglog(result.stiffness, result.critical_speeds[:, j] * f, "-", lw=1.5,
                  label=f"mode {j + 1}")
    for i, b in enumerate(result.curve_bearings):
        for name, values, style in (("kxx", result.bearing_kxx, "--"),
                                    ("kyy", result.bearing_kyy, ":")):
            ax.loglog(values[i], result.speeds * f, style, color="k", lw=1,
                      label=f"bearing {b} {name}")
    crossings = result.intersections
    if len(crossings.speed):
        ax.loglog(crossings.stiffness, crossings.speed * f, "o", mfc="none", mec="tab:red",
                  ms=8, label="intersections")
    ax.set_xlabel("support stiffness [N/m]")
    ax.set_ylabel(f"critical speed [{units}]")
    ax.set_title("undamped critical speed map")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    return fig


DRAWERS: dict[str, Callable[..., Any]] = {
    "Rotor": rotor_layout_figure,
    "CriticalSpeedMapResult": critical_speed_map_figure,
    "FrequencyResponseResult": bode_figure,
    "StaticResult": static_figure,
    "CampbellResult": campbell_figure,
    "ModalResult": mode_shape_figure,
    "BearingEquilibriumResult": load_distribution_figure,
    "StiffnessVariation": stiffness_variation_figure,
    "BearingLifeResult": bearing_life_figure,
    "TransientResult": transient_figure,
    "Spectrum": spectrum_figure,
    "Waterfall": waterfall_figure,
    "OrderTrack": order_track_figure,
    "PeriodicResult": periodic_figure,
    "QuasiPeriodicResult": quasi_periodic_figure,
    "ApiLevel1Result": level1_figure,
    "ApiUnbalanceResult": api_unbalance_figure,
}
