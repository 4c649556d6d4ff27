"""Figures of rotor transients: time histories, orbits, spectra with 1X and varying-compliance
markers, run-up waterfalls, order tracks and bearing-load histories.

Each function takes a :class:`~rotorsim.results.transient.TransientResult` (the spectrum,
waterfall and order-track figures also take a ready ``Spectrum``, ``Waterfall`` or
``OrderTrack``) and returns the matplotlib Figure; :func:`transient_figure` is the standard
2 x 2 figure drawn by ``rotorsim.plot(result)``.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import LogNorm

from rotorsim.errors import ModelError
from rotorsim.plotting.units import amplitude_scale, figure_axes, speed_factor

_ROTATIONS = ("rx", "ry", "rz")
_VC_COLORS = ("tab:red", "tab:purple", "tab:brown", "tab:olive")


def _is_transient(result: Any) -> bool:
    return type(result).__name__ == "TransientResult"


def _varies(speed: Any) -> bool:
    speed = np.asarray(speed)
    return bool(speed.size and np.ptp(speed) > 1e-6 * max(np.max(np.abs(speed)), 1e-12))


def steady_t_min(result: Any) -> float | None:
    """Start of the second half of the record at constant speed (skips the start-up
    transient); ``None`` (whole record) when the speed varies."""
    if _varies(result.speed):
        return None
    return float(result.t[0] + 0.5 * (result.t[-1] - result.t[0]))


def most_responsive_node(result: Any, t_min: float | None = None) -> int:
    """Kept node with the largest lateral (ux/uy) peak-to-peak motion for ``t >= t_min``."""
    lateral = np.isin(result.dofs % 6, (0, 1))
    if not lateral.any():
        raise ModelError("no lateral DOF (ux, uy) was kept", "most_responsive_node")
    sel = result.window(t_min)
    ptp = np.ptp(result.q[sel][:, lateral], axis=0) if sel.any() else np.zeros(lateral.sum())
    return int(result.dofs[lateral][int(np.argmax(ptp))] // 6)


def _vc_bearings(result: Any) -> list[tuple[str, float]]:
    """``(tags, Z kappa)`` of the rolling bearings, those sharing an order in one entry."""
    groups: dict[float, list[str]] = {}
    orders = np.asarray(result.bearing_elements * result.bearing_kappa, dtype=float)
    for tag, order in zip(result.bearing_tags, orders, strict=True):
        if order > 0:
            key = next((k for k in groups if abs(k - order) <= 1e-9 * order), float(order))
            groups.setdefault(key, []).append(str(tag))
    return [(", ".join(tags), order) for order, tags in groups.items()]


def _top(markers: Sequence[float], nyquist: float, f_max: float | None) -> float:
    """Upper frequency shown [rad/s]: ``f_max``, else 1.3 x the highest marker, at most
    the Nyquist frequency."""
    if f_max is not None:
        return f_max
    return min(nyquist, 1.3 * max(markers)) if len(markers) else nyquist


# ---------------------------------------------------------------------------- time domain
def time_history_figure(result: Any, ax: Any = None, *,
                        dofs: Sequence[tuple[int, str]] | None = None,
                        t_min: float | None = None, t_max: float | None = None,
                        amplitude_units: str = "um", speed_units: str = "rpm",
                        show_speed: bool | None = None) -> Any:
    """Time history of ``dofs`` (``(node, "ux")`` pairs; default ux, uy of the most
    responsive node), rotations in mrad, with the speed on a twin axis when it varies."""
    scale, f = amplitude_scale(amplitude_units), speed_factor(speed_units)
    fig, ax = figure_axes(ax, figsize=(8, 4))
    if dofs is None:
        node = most_responsive_node(result, t_min)
        dofs = [(node, d) for d in ("ux", "uy") if _kept(result, node, d)]
    sel = result.window(t_min, t_max)
    t = result.t[sel]
    for node, dof in dofs:
        rot = dof in _ROTATIONS
        unit = "mrad" if rot else amplitude_units
        ax.plot(t, result.displacement(node, dof)[sel] * (1e3 if rot else scale), lw=0.8,
                label=f"{node}:{dof} [{unit}]")
    rotations = any(d in _ROTATIONS for _, d in dofs)
    ax.set_ylabel(f"displacement [{amplitude_units}]" + (", rotation [mrad]" if rotations
                                                          else ""))
    ax.set_xlabel("time [s]")
    ax.set_title("time history")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    if show_speed if show_speed is not None else _varies(result.speed[sel]):
        twin = ax.twinx()
        twin.plot(t, result.speed[sel] * f, "--", color="0.4", lw=1.0, label="speed")
        twin.set_ylabel(f"speed [{speed_units}]")
        twin.legend(fontsize=8, loc="lower right")
    return fig


def _kept(result: Any, node: int, dof: str) -> bool:
    return bool(np.any(result.dofs == result.dof_map.index(node, dof)))


def orbit_figure(result: Any, ax: Any = None, *, node: int | None = None,
                 t_min: float | None = None, amplitude_units: str = "um") -> Any:
    """Orbit ``(ux, uy)`` of ``node`` (default: the most responsive) for ``t >= t_min``."""
    scale = amplitude_scale(amplitude_units)
    fig, ax = figure_axes(ax, figsize=(5.5, 5.5))
    node = most_responsive_node(result, t_min) if node is None else node
    x, y = result.orbit(node, t_min)
    ax.plot(x * scale, y * scale, lw=0.7, color="tab:blue", label="orbit")
    if x.size:
        ax.plot(x[0] * scale, y[0] * scale, "o", color="tab:green", ms=4, label="start")
        ax.plot(x[-1] * scale, y[-1] * scale, "s", color="tab:red", ms=4, label="end")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"ux [{amplitude_units}]")
    ax.set_ylabel(f"uy [{amplitude_units}]")
    since = "" if t_min is None else f", t >= {t_min:.3g} s"
    ax.set_title(f"orbit of node {node}{since}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def bearing_loads_figure(result: Any, ax: Any = None, *, bearings: Sequence[int] | None = None,
                         t_min: float | None = None, magnitude: bool = True) -> Any:
    """Fx, Fy (solid, dashed) and radial load ``|F| = hypot(Fx, Fy)`` (dotted) that each
    nonlinear bearing's inner ring carries, against time."""
    fig, ax = figure_axes(ax, figsize=(8, 4))
    loads = result.bearing_loads
    if loads.shape[1] == 0:
        ax.text(0.5, 0.5, "no nonlinear bearings", ha="center", va="center",
                transform=ax.transAxes)
        ax.set_title("bearing loads")
        return fig
    sel = result.window(t_min)
    t = result.t[sel]
    for i in range(loads.shape[1]) if bearings is None else bearings:
        color = f"C{i % 10}"
        tag = result.bearing_tags[i]
        fx, fy = loads[sel, i, 0], loads[sel, i, 1]
        ax.plot(t, fx, "-", color=color, lw=0.8, label=f"{tag} Fx")
        ax.plot(t, fy, "--", color=color, lw=0.8, label=f"{tag} Fy")
        if magnitude:
            ax.plot(t, np.hypot(fx, fy), ":", color=color, lw=1.2, label=f"{tag} |F|")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("bearing load [N]")
    ax.set_title("bearing loads on the inner rings")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return fig


# ---------------------------------------------------------------------------- spectra
def spectrum_figure(result: Any, ax: Any = None, *, node: int | None = None, dof: str = "uy",
                    t_min: float | None = None, units: str = "Hz",
                    amplitude_units: str = "um", harmonics: Sequence[float] = (1, 2, 3),
                    vc_harmonics: Sequence[int] = (1, 2), speed: float | None = None,
                    vc_orders: Sequence[tuple[str, float]] = (), f_max: float | None = None,
                    log: bool = True, dynamic_range: float = 1e6, speed_units: str = "rpm"
                    ) -> Any:
    """Amplitude spectrum of one DOF with markers at ``kX`` of the mean speed and at the
    varying-compliance frequency ``Z kappa W`` of each rolling bearing (and its
    ``vc_harmonics``); ``dynamic_range`` decades below the peak are shown on a log scale.

    ``result`` may be a ``Spectrum``; markers then need ``speed`` [rad/s] and ``vc_orders``
    (``(bearing tag, Z kappa)`` pairs). ``t_min`` defaults to the second half of a constant-speed
    record (:func:`steady_t_min`).
    """
    f, sf, scale = speed_factor(units), speed_factor(speed_units), amplitude_scale(amplitude_units)
    fig, ax = figure_axes(ax, figsize=(8, 4.5))
    if _is_transient(result):
        t_min = steady_t_min(result) if t_min is None else t_min
        node = most_responsive_node(result, t_min) if node is None else node
        sel = result.window(t_min)
        speed = float(np.mean(result.speed[sel]))
        vc_orders = _vc_bearings(result)
        title = f"spectrum of {node}:{dof}" + ("" if t_min is None else f", t >= {t_min:.3g} s")
        if _varies(result.speed[sel]):
            title += f"\n(speed varies: markers at the mean, {speed * sf:.4g} {speed_units})"
        result = result.spectrum(node, dof, t_min)
    else:
        title = "amplitude spectrum"
    amp = result.amplitude.reshape(result.amplitude.shape[0], -1)[:, 0] * scale
    freq = result.frequency * f
    (ax.semilogy if log else ax.plot)(freq[1:], amp[1:], lw=0.9, color="tab:blue")
    markers = _markers(speed, harmonics, vc_orders, vc_harmonics)
    for k, (label, w, style) in enumerate(markers):
        ax.axvline(w * f, lw=1.0, label=label, **style)
        ax.annotate(label.split(" ")[0], (w * f, 1.0), xycoords=("data", "axes fraction"),
                    xytext=(2, -10 - 9 * (k % 2)), textcoords="offset points", fontsize=7)
    ax.set_xlim(0.0, _top([w for _, w, _ in markers], result.frequency[-1], f_max) * f)
    if log and amp[1:].max() > 0:
        ax.set_ylim(amp[1:].max() / dynamic_range, amp[1:].max() * 2.0)
    ax.set_xlabel(f"frequency [{units}]")
    ax.set_ylabel(f"amplitude [{amplitude_units}]")
    ax.set_title(title)
    ax.grid(alpha=0.3, which="both")
    if markers:
        ax.legend(fontsize=7)
    return fig


def _markers(speed: float | None, harmonics: Sequence[float],
             vc_orders: Sequence[tuple[str, float]], vc_harmonics: Sequence[int]
             ) -> list[tuple[str, float, dict[str, Any]]]:
    """``(label, frequency [rad/s], line style)`` of the kX and varying-compliance lines."""
    if speed is None or speed <= 0:
        return []
    out = [(f"{k:g}X", k * speed, {"color": "k", "ls": "--"}) for k in harmonics]
    for i, (tag, order) in enumerate(vc_orders):
        color = _VC_COLORS[i % len(_VC_COLORS)]
        out += [(f"{'' if h == 1 else h}VC {tag} ({h * order:.3g}X)", h * order * speed,
                 {"color": color, "ls": "-."}) for h in vc_harmonics]
    return out


def waterfall_figure(result: Any, ax: Any = None, *, node: int | None = None, dof: str = "uy",
                     segment: float | None = None, overlap: float = 0.5, units: str = "Hz",
                     speed_units: str = "rpm", amplitude_units: str = "um",
                     orders: Sequence[float] = (1, 2),
                     vc_orders: Sequence[tuple[str, float]] = (),
                     f_max: float | None = None, dynamic_range: float = 1e3) -> Any:
    """Run-up waterfall: amplitude (log colour, ``dynamic_range`` decades shown) over
    frequency and speed (time when the speed is not monotonic), with the order lines
    ``kX`` and the varying-compliance orders ``Z kappa`` of the rolling bearings.

    ``result`` may be a ``Waterfall`` (pass ``vc_orders`` as ``(bearing tag, Z kappa)``).
    ``segment`` [s] defaults to 1/16 of the record.
    """
    f, sf, scale = speed_factor(units), speed_factor(speed_units), amplitude_scale(amplitude_units)
    fig, ax = figure_axes(ax, figsize=(8, 5.5))
    title = "waterfall"
    if _is_transient(result):
        node = most_responsive_node(result) if node is None else node
        segment = (result.t[-1] - result.t[0]) / 16.0 if segment is None else segment
        vc_orders = _vc_bearings(result)
        title = f"waterfall of {node}:{dof}"
        result = result.waterfall(node, dof, segment=segment, overlap=overlap)
    by_speed = result.speeds.size > 1 and bool(np.all(np.diff(result.speeds) > 0))
    y = result.speeds * sf if by_speed else result.times
    amp = result.amplitude * scale
    peak = float(amp.max()) if amp.size and amp.max() > 0 else 1.0
    mesh = ax.pcolormesh(result.frequency * f, y, np.maximum(amp, peak / dynamic_range),
                         norm=LogNorm(peak / dynamic_range, peak), shading="nearest",
                         cmap="viridis")
    fig.colorbar(mesh, ax=ax, label=f"amplitude [{amplitude_units}]")
    lines = [(f"{k:g}X", float(k), "w--") for k in orders] + \
        [(f"VC {tag} ({o:.3g}X)", o, "r-.") for tag, o in vc_orders]
    for label, order, style in lines:
        ax.plot(order * result.speeds * f, y, style, lw=1.0, label=label)
    top_speed = float(result.speeds.max()) if result.speeds.size else 0.0
    ax.set_xlim(0.0, _top([o * top_speed for _, o, _ in lines], result.frequency[-1],
                          f_max) * f)
    ax.set_xlabel(f"frequency [{units}]")
    ax.set_ylabel(f"speed [{speed_units}]" if by_speed else "time [s]")
    ax.set_title(title)
    if lines:
        ax.legend(fontsize=7, loc="upper right")
    return fig


def order_track_figure(result: Any, ax: Any = None, *, node: int | None = None,
                       dof: str = "uy", orders: Sequence[float] | None = None,
                       revolutions_per_block: int = 8, speed_units: str = "rpm",
                       amplitude_units: str = "um") -> Any:
    """Amplitude of shaft orders against speed: by default 1X, 2X and the varying-compliance
    order ``Z kappa`` of each rolling bearing. ``result`` may be an ``OrderTrack``."""
    sf, scale = speed_factor(speed_units), amplitude_scale(amplitude_units)
    fig, ax = figure_axes(ax, figsize=(8, 4.5))
    names: dict[float, str] = {}
    title = "order track"
    if _is_transient(result):
        node = most_responsive_node(result) if node is None else node
        vc = _vc_bearings(result)
        names = {o: f"VC {tag} ({o:.3g}X)" for tag, o in vc}
        orders = (1.0, 2.0, *names) if orders is None else orders
        title = f"order track of {node}:{dof}"
        result = result.order_track(node, dof, orders,
                                    revolutions_per_block=revolutions_per_block)
    for j, order in enumerate(result.orders):
        ax.plot(result.speed * sf, result.amplitude[:, j] * scale, "-o", ms=2.5, lw=1.0,
                label=names.get(float(order), f"{order:g}X"))
    ax.set_xlabel(f"speed [{speed_units}]")
    ax.set_ylabel(f"amplitude [{amplitude_units}]")
    ax.set_title(f"{title} ({result.revolutions_per_block} revolutions per block)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


# ---------------------------------------------------------------------------- standard
def transient_figure(result: Any, ax: Any = None, *, node: int | None = None,
                     t_min: float | None = None, units: str = "Hz",
                     amplitude_units: str = "um") -> Any:
    """Standard figure of a ``TransientResult`` (``ax`` is ignored: four panels): time
    history of the most responsive node with the speed, its orbit and spectrum (second half
    of a constant-speed record, whole run-up otherwise) and the bearing loads (a waterfall
    when there is no nonlinear bearing but the speed varies)."""
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5))
    t_min = steady_t_min(result) if t_min is None else t_min
    node = most_responsive_node(result, t_min) if node is None else node
    time_history_figure(result, axes[0, 0], dofs=_lateral(result, node),
                        amplitude_units=amplitude_units)
    orbit_figure(result, axes[0, 1], node=node, t_min=t_min, amplitude_units=amplitude_units)
    _guarded(spectrum_figure, result, axes[1, 0], node=node, t_min=t_min, units=units,
             amplitude_units=amplitude_units)
    if result.bearing_loads.shape[1] == 0 and _varies(result.speed):
        _guarded(waterfall_figure, result, axes[1, 1], node=node, units=units,
                 amplitude_units=amplitude_units)
    else:
        bearing_loads_figure(result, axes[1, 1], t_min=None)
    tag = result.summary.get("tag") or "rotor"
    fig.suptitle(f"transient of '{tag}' ({result.method or 'time integration'}, "
                 f"{result.t.size} samples, {result.t[-1] - result.t[0]:.4g} s)")
    fig.tight_layout()
    return fig


def _lateral(result: Any, node: int) -> list[tuple[int, str]]:
    return [(node, d) for d in ("ux", "uy") if _kept(result, node, d)]


def _guarded(draw: Any, result: Any, ax: Any, **options: Any) -> None:
    """Draw a panel that needs uniform samples; show why instead when it cannot."""
    try:
        draw(result, ax, **options)
    except ModelError as exc:
        ax.set_axis_off()
        ax.text(0.5, 0.5, "not drawn:\n" + textwrap.fill(str(exc), 60), ha="center",
                va="center", fontsize=8, transform=ax.transAxes)
