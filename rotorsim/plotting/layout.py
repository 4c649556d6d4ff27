"""Rotor layout drawing: shaft sections, disks, bearings and housings to scale."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Polygon, Rectangle


def disk_outline(m: float, Id: float, Ip: float) -> tuple[float, float]:
    """Equivalent solid-disk outer diameter and width [m] from ``m, Id, Ip``.

    ``Ip = m D^2 / 8`` and ``Id = Ip / 2 + m w^2 / 12`` for a solid disk; a disk whose
    ``Id <= Ip / 2`` gets a nominal width of 5 % of ``D``.

    Examples
    --------
    >>> D, w = disk_outline(m=10.0, Id=0.05 / 2 + 10.0 * 0.02**2 / 12, Ip=0.05)
    >>> round(D, 4), round(w, 4)
    (0.2, 0.02)
    """
    D = float(np.sqrt(8.0 * Ip / m)) if Ip > 0 else 0.05
    excess = Id - Ip / 2.0
    w = float(np.sqrt(12.0 * excess / m)) if excess > 0 else 0.05 * D
    return D, w


def rotor_layout_figure(rotor: Any, ax: Any = None, *, node_labels: bool = True) -> Any:
    """Side view of ``rotor`` to scale (mm): shaft sections, disks, bearings, housings."""
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(10, 4))
    z = rotor.nodes_pos * 1e3
    radius = 0.0
    for el in rotor.shaft_elements:
        z0, z1 = z[el.n], z[el.n + 1]
        ro0, ro1, ri0, ri1 = (v * 500.0 for v in (el.odl, el.odr, el.idl, el.idr))
        radius = max(radius, ro0, ro1)
        for sign in (1.0, -1.0):
            ax.add_patch(Polygon([(z0, sign * ri0), (z1, sign * ri1), (z1, sign * ro1),
                                  (z0, sign * ro0)], closed=True, fc="0.75", ec="0.3", lw=0.6))
    for d in rotor.disk_elements:
        D, w = (v * 1e3 for v in disk_outline(d.m, d.Id, d.Ip))
        radius = max(radius, D / 2)
        ax.add_patch(Rectangle((z[d.n] - w / 2, -D / 2), w, D, fc="tab:blue", ec="navy",
                               alpha=0.7, lw=0.8))
    size = max(radius * 0.25, 5.0)
    local = _node_radius(rotor) * 1e3
    for b in rotor.bearing_elements:
        zb = z[b.n]
        base = -local[b.n] if b.n < rotor.n_shaft_nodes else -radius * 1.6
        tri = [(zb, base), (zb - size / 2, base - size), (zb + size / 2, base - size)]
        ax.add_patch(Polygon(tri, closed=True, fc="tab:orange", ec="k", lw=0.8))
        ax.add_patch(Polygon([(x, -y) for x, y in tri], closed=True, fc="tab:orange",
                             ec="k", lw=0.8))
        label = b.tag or f"B(n={b.n})"
        ax.annotate(label, (zb, base - size), textcoords="offset points", xytext=(0, -10),
                    ha="center", fontsize=7)
    for pm in rotor.point_mass_elements:
        ax.plot(z[pm.n], -radius * 1.6 - size * 1.5, "ks", ms=6)
    multi = bool(getattr(rotor, "multi_line", False))
    if node_labels and not multi:
        for n in range(rotor.n_shaft_nodes):
            ax.annotate(str(n), (z[n], radius * 1.1 + size * 1.2), ha="center", fontsize=6,
                        color="0.3")
    if multi:  # name each line at its left end, beside its outer radius
        local_r = _node_radius(rotor) * 1e3
        for line, first in zip(rotor.layout.lines, rotor.layout.first_node, strict=True):
            ax.annotate(f"{line.name} ({line.speed_ratio:g}X)", (z[first], local_r[first]),
                        textcoords="offset points", xytext=(2, 2), fontsize=7,
                        color="darkred")
    ax.axhline(0.0, color="k", lw=0.5, ls="-.")
    span = z[: rotor.n_shaft_nodes]
    extent = radius * 1.6 + size * 2.5
    margin = 0.05 * (span.max() - span.min()) or extent  # a rigid rotor: a square view
    ax.set_xlim(span.min() - margin, span.max() + margin)
    ax.set_ylim(-extent, extent)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("z [mm]")
    ax.set_ylabel("radius [mm]")
    lines = f"{len(rotor.layout.lines)} lines, " if multi else ""
    ax.set_title(f"rotor '{rotor.tag}': {lines}{len(rotor.shaft_elements)} elements, "
                 f"{len(rotor.disk_elements)} disks, {len(rotor.bearing_elements)} bearings")
    return fig


def _node_radius(rotor: Any) -> np.ndarray:
    """Largest outer radius [m] of the shaft elements meeting at each shaft node."""
    r = np.zeros(rotor.n_shaft_nodes)
    for el in rotor.shaft_elements:
        r[el.n] = max(r[el.n], el.odl / 2)
        r[el.n + 1] = max(r[el.n + 1], el.odr / 2)
    return r
