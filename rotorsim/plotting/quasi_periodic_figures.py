"""Figures of a quasi-periodic branch (:class:`~rotorsim.results.quasi_periodic.
QuasiPeriodicResult`): the amplitude envelope and the base tones over speed with the
unstable tori marked, the largest exponent, the spectrum of combination tones and the
Poincare section at one speed."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from rotorsim.plotting.periodic_figures import responsive_node
from rotorsim.plotting.units import amplitude_scale, figure_axes, speed_factor

TONES_SHOWN = 12
"""Largest tones drawn in the spectrum."""


def envelope_figure(result: Any, ax: Any = None, *, node: int | None = None,
                    dof: str = "uy", units: str = "rpm", amplitude_units: str = "um") -> Any:
    """Peak-to-peak envelope and the amplitudes of the 1X and VC tones over speed; the
    points whose torus is unstable (not the response) in red."""
    fig, ax = figure_axes(ax)
    node = responsive_node(result) if node is None else node
    f, scale = speed_factor(units), amplitude_scale(amplitude_units)
    s = result.speed * f
    ptp = result.amplitude(node, dof, "peak_to_peak") * scale
    ax.plot(s, ptp, "k-", label="peak to peak")
    ax.plot(s, np.abs(result.tone(node, dof, 1, 0)) * scale, "-", label="1X (k1, k2) = (1, 0)")
    ax.plot(s, np.abs(result.tone(node, dof, 0, 1)) * scale, "-", label="VC (0, 1)")
    bad = result.has_stability and ~result.stable
    if np.any(bad):
        ax.plot(s[bad], ptp[bad], "rx", label="unstable torus")
    for e in result.events:
        ax.axvline(e.parameter * f, color="tab:red", ls=":", lw=1)
    ax.set_xlabel(f"speed [{units}]")
    ax.set_ylabel(f"node {node} {dof} [{amplitude_units}]")
    ax.set_title("quasi-periodic response (shaft and VC tones)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def exponent_figure(result: Any, ax: Any = None, *, units: str = "rpm") -> Any:
    """Largest real part of the torus's exponents over speed (negative: stable)."""
    fig, ax = figure_axes(ax)
    s = result.speed * speed_factor(units)
    ax.plot(s, result.exponents, "k.-")
    if not result.exponents_converged.all():
        off = ~result.exponents_converged
        ax.plot(s[off], result.exponents[off], "o", mfc="none", color="tab:orange",
                label="boxes disagree")
        ax.legend(fontsize=8)
    ax.axhline(0.0, color="tab:red", lw=1)
    ax.set_xlabel(f"speed [{units}]")
    ax.set_ylabel("largest Re(lambda) [1/s]")
    ax.set_title(f"stability of the torus ({result.stability_method})")
    ax.grid(alpha=0.3)
    return fig


def tone_spectrum_figure(result: Any, ax: Any = None, *, point: int, node: int,
                         dof: str = "uy", amplitude_units: str = "um") -> Any:
    """The largest tones ``k1 W + k2 w2`` of one DOF at one point."""
    fig, ax = figure_axes(ax)
    freq, amp, k = result.spectrum(point, node, dof)
    n = min(TONES_SHOWN, freq.size)
    scale = amplitude_scale(amplitude_units)
    ax.stem(freq[:n] / (2 * np.pi), amp[:n] * scale, bottom=amp[n - 1] * scale / 10)
    ax.set_yscale("log")       # combination tones are decades below the 1X
    for x, y, (k1, k2) in zip(freq[:n] / (2 * np.pi), amp[:n] * scale, k[:n], strict=True):
        ax.annotate(f"({k1},{k2})", (x, y), fontsize=7, textcoords="offset points",
                    xytext=(0, 3), ha="center")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel(f"|X| [{amplitude_units}]")
    ax.set_title(f"tones (k1, k2) at {result.speed[point]:.5g} rad/s, node {node} {dof}")
    ax.grid(alpha=0.3, axis="y")
    return fig


def poincare_figure(result: Any, ax: Any = None, *, point: int, node: int,
                    amplitude_units: str = "um") -> Any:
    """Orbit over 30 revolutions and its Poincare section once per revolution (a closed
    curve for a torus)."""
    fig, ax = figure_axes(ax)
    scale = amplitude_scale(amplitude_units)
    t = np.linspace(0.0, 30 * 2 * np.pi / result.speed[point], 6000)
    x, y = result.orbit(point, node, t)
    px, py = result.poincare(point, node)
    ax.plot(x * scale, y * scale, "-", color="0.7", lw=0.5, label="orbit")
    ax.plot(px * scale, py * scale, ".", ms=2, color="tab:blue", label="once per rev")
    ax.set_xlabel(f"ux [{amplitude_units}]")
    ax.set_ylabel(f"uy [{amplitude_units}]")
    ax.set_title(f"node {node} at {result.speed[point]:.5g} rad/s")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize=8)
    return fig


def quasi_periodic_figure(result: Any, ax: Any = None, *, node: int | None = None,
                          dof: str = "uy", units: str = "rpm", amplitude_units: str = "um",
                          point: int | None = None) -> Any:
    """Standard figure: envelope, exponents, tone spectrum and Poincare section at ``point``
    (default the largest response); with ``ax`` only the envelope."""
    if ax is not None:
        return envelope_figure(result, ax, node=node, dof=dof, units=units,
                               amplitude_units=amplitude_units)
    fig, axes = plt.subplots(2, 2, figsize=(13, 9))
    node = responsive_node(result) if node is None else node
    if point is None:
        point = int(np.argmax(result.amplitude(node, dof, "peak_to_peak")))
    envelope_figure(result, axes[0, 0], node=node, dof=dof, units=units,
                    amplitude_units=amplitude_units)
    if result.has_stability:
        exponent_figure(result, axes[0, 1], units=units)
    else:
        axes[0, 1].set_axis_off()
    tone_spectrum_figure(result, axes[1, 0], point=point, node=node, dof=dof,
                         amplitude_units=amplitude_units)
    poincare_figure(result, axes[1, 1], point=point, node=node,
                    amplitude_units=amplitude_units)
    fig.tight_layout()
    return fig
