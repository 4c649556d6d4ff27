"""Figures of the API 617 checks: the Level I sweep (log decrement against applied
cross-coupling, and the CSR screening chart) and the unbalance responses with their
half-power bands, operating range and separation margins."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np

from rotorsim.plotting.units import amplitude_scale, speed_factor


def level1_figure(result: Any, ax: Any = None, *, units: str = "rpm") -> Any:
    """Log decrement of the first forward mode against applied cross-coupling (Q_A and
    Q0 marked) beside the CSR / average gas density screening chart (API 617 Level I)."""
    from rotorsim.analyses.standards.api_formulas import CSR_BOUNDARY

    if ax is None:
        fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    else:
        fig, left, right = ax.figure, ax, None
    left.plot(result.applied / 1e3, result.log_dec, "o-", ms=3, label="first forward mode")
    left.axhline(0.0, color="k", lw=0.8)
    left.axhline(0.1, color="tab:red", ls=":", lw=1, label="log dec 0.1")
    left.plot([result.q_a / 1e3], [result.log_dec_a], "s", color="tab:orange",
              label=f"QA = {result.q_a / 1e3:.4g} N/mm")
    if np.isfinite(result.q0):
        left.plot([result.q0 / 1e3], [0.0], "D", color="tab:red",
                  label=f"Q0 = {result.q0 / 1e3:.4g} N/mm")
    left.set_xlabel("applied cross-coupled stiffness Q [N/mm]")
    left.set_ylabel("log decrement")
    left.set_title(f"Level I at MCS {result.mcs * speed_factor(units):.0f} {units}")
    left.grid(alpha=0.3)
    left.legend(fontsize=8)
    if right is not None:
        rho, csr = np.array(CSR_BOUNDARY).T
        top = max(100.0, 1.3 * np.nan_to_num(result.density))
        right.plot([*rho, rho[-1], rho[-1]], [*csr, 0.0, 0.0], "k-")
        right.fill_between([*rho, rho[-1], top], [*csr, 0.0, 0.0], 4.0, color="tab:red",
                           alpha=0.1, label="Region B")
        if np.isfinite(result.density):
            right.plot([result.density], [result.csr], "o", color="tab:blue",
                       label=f"machine: CSR {result.csr:.3g}")
        right.set_xlim(0, top)
        right.set_ylim(0, 4.0)
        right.set_xlabel("average gas density [kg/m^3]")
        right.set_ylabel("CSR = MCS / first critical speed (rigid supports)")
        right.set_title("Level I screening chart")
        right.grid(alpha=0.3)
        right.legend(fontsize=8)
    fig.tight_layout()
    return fig


def api_unbalance_figure(result: Any, ax: Any = None, *, units: str = "rpm",
                         amplitude_units: str = "um") -> Any:
    """Peak-to-peak major axis at each mode's response node against speed, with the
    operating range, the half-power bands and the mechanical-test limit Av1."""
    f, scale = speed_factor(units), amplitude_scale(amplitude_units)
    if ax is None:
        fig, ax = plt.subplots(figsize=(9, 4.5))
    else:
        fig = ax.figure
    x = result.speeds * f
    for m in range(result.num_modes):
        node = int(result.response_node[m])
        af = f"AF {result.af[m]:.3g}" if np.isfinite(result.af[m]) else "no peak"
        line, = ax.semilogy(x, result.major_pp[m, :, node] * scale,
                            label=f"mode {m}: node {node}, {af}")
        if np.isfinite(result.af[m]):
            ax.axvspan(result.half_power_low[m] * f, result.half_power_high[m] * f,
                       color=line.get_color(), alpha=0.15)
    ax.axvspan(result.min_speed * f, result.mcs * f, color="0.5", alpha=0.15, hatch="//",
               label="operating range")
    ax.axhline(result.vibration_limit * scale, color="k", ls=":", lw=1, label="Av1")
    ax.set_xlabel(f"speed [{units}]")
    ax.set_ylabel(f"major axis, peak to peak [{amplitude_units}]")
    ax.set_title("API unbalance responses (U = 6350 W/N at the anti-nodes)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig
