"""Seed 001 (Leontiev, Ivannikov, Degtyarev 2017): radial roller bearing with flexible rings.

Reproduces section 3.1 and 3.3 of the seed with
:class:`~rotorsim.elements.rolling.flexible_ring.bearing.FlexibleRingRollerBearing`:

* Fig. 5: the inner-contact roller loads ``Q_i`` of the bearing with rigid and with
  flexible rings, for the diametral clearances ``g = -40 um`` (preload) and ``g = +10 um``,
  under ``F_x = 5000 N`` with the inner ring at 12000 rpm; the seed states that with
  ``g = -40 um`` rigid rings give contact forces about 2.5 times higher;
* Fig. 8: misalignment, ``M_y = 13.7 N m`` added, 10 slices: the contact forces along the
  most loaded roller, and the (unchanged) distribution of the radial forces.

When :mod:`rotorsim.verification.ring_fe` is importable, the roller loads of its 2D
plane-stress finite-element model of the two rings (the counterpart of the seed's NX
Nastran model) are added to Fig. 5, with the same contact constant.

Data as interpreted here (SI inside): 24 rollers, ``R_p = 75 mm``, ``R_b = 6.5 mm``,
``L = 16 mm``, ``R_s = 54 mm`` (inner ring bore, hollow shaft), ``R_h = 97 mm``, ring width
``b = 30 mm``, ``E = 2e11 Pa`` (the seed's "2e11 MPa" is a typo), ``nu = 0.3``,
``rho = 7850 kg/m^3``; rectangular ring sections ``R_s .. R_p - R_b`` and
``R_p + R_b .. R_h``; contact constant of seed eq 16; roller mass ``rho pi R_b^2 L``
(16.7 g; not given in the seed) at the kinematic cage speed
``(1 - R_b/R_p)/2 x 12000 rpm``; rollers held at ``psi_j = pi + (j - 1) 2 pi / 24``, so that
roller 13 (the seed's most loaded roller) lies in the load direction +x.

Run: ``python examples/seed001_flexible_rings.py [--fast] [--out DIR]``.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium  # noqa: E402
from rotorsim.elements.rolling.flexible_ring.bearing import FlexibleRingRollerBearing  # noqa: E402

FIGURES = ROOT / "docs" / "figures" / "seed001"
SEED = dict(n_rollers=24, pitch_radius=75e-3, roller_radius=6.5e-3, effective_length=16e-3,
            shaft_radius=54e-3, housing_radius=97e-3, ring_width=30e-3, E=2.0e11, nu=0.3,
            rho=7850.0, psi0=math.pi, cage="fixed", n_slices=10)
"""Seed 001 section 3.1 bearing (10 slices, as in section 3.3)."""
SPEED = 12000.0 * math.pi / 30.0
"""Inner-ring speed [rad/s] (12000 rpm)."""
LOAD = (5000.0, 0.0, 0.0, 0.0, 0.0)
"""``[Fx, Fy, Fz, Mx, My]`` on the inner ring [N, N m] (section 3.1)."""
MOMENT = 13.7
"""``M_y`` [N m] of the misalignment case (section 3.3)."""
CLEARANCES = {"preload": -40e-6, "clearance": 10e-6}
"""Diametral clearances ``g`` [m] of Fig. 5a and 5b."""
MOST_LOADED = 13
"""The seed's most loaded roller (1-based number), on the +x axis here."""


def seed_bearing(clearance: float, rigid: bool = False, speed: float = SPEED
                 ) -> FlexibleRingRollerBearing:
    """The seed 001 bearing with diametral clearance ``clearance`` [m] at ``speed``."""
    return FlexibleRingRollerBearing(**SEED, diametral_clearance=clearance, rigid_rings=rigid,
                                     speed=speed, tag="seed001")


def solve(bearing: FlexibleRingRollerBearing, load: Any = LOAD) -> dict[str, Any]:
    """Static equilibrium under ``load``: displacement, roller loads and slice loads."""
    t0 = time.perf_counter()
    res = bearing_equilibrium(bearing, load)
    wall = time.perf_counter() - t0
    st = bearing.state(res.displacement[None, :], bearing.element_angles())
    assert st.slice_load is not None and st.outer_slice_load is not None
    return {"displacement": res.displacement, "inner_load": st.element_load[0],
            "outer_load": st.outer_load[0], "slice_load": st.slice_load[0],
            "outer_slice_load": st.outer_slice_load[0], "ring": st.ring_deflection[0],
            "stiffness": res.stiffness, "iterations": res.iterations,
            "inner_iterations": st.iterations, "wall_time": wall}


def fe_loads(clearance: float, speed: float, fast: bool) -> dict[str, Any] | None:
    """Roller loads of the 2D ring finite-element model, or ``None`` when it is absent."""
    try:
        from rotorsim.verification.ring_fe import (
            SEED001_CASE,
            MeshOptions,
            ring_fe_roller_loads,
        )
    except ImportError:
        return None
    case = {**SEED001_CASE, "speed": speed, "F_x": LOAD[0]}
    mesh = MeshOptions(mesh_size=2e-3, max_size=5e-3) if fast else None
    kn = seed_bearing(clearance).Kn  # the contact law of seed eq 16, whole roller
    t0 = time.perf_counter()
    res = ring_fe_roller_loads(**case, clearance=clearance, Kn=kn, psi0=SEED["psi0"], mesh=mesh)
    return {"inner_load": res.roller_loads, "outer_load": res.outer_loads,
            "wall_time": time.perf_counter() - t0, "n_dofs": res.summary["n_dofs"]}


def load_distributions(fast: bool) -> dict[str, dict[str, Any]]:
    """Fig. 5: rigid, flexible (and FE) roller loads for both clearances at 12000 rpm, and
    rigid and flexible at rest."""
    out: dict[str, dict[str, Any]] = {}
    for name, g in CLEARANCES.items():
        out[name] = {"rigid": solve(seed_bearing(g, rigid=True)),
                     "flexible": solve(seed_bearing(g)),
                     "rigid_at_rest": solve(seed_bearing(g, rigid=True, speed=0.0)),
                     "flexible_at_rest": solve(seed_bearing(g, speed=0.0))}
        fe = fe_loads(g, SPEED, fast)
        if fe is not None:
            out[name]["fe"] = fe
    return out


def misalignment() -> dict[str, Any]:
    """Fig. 8: ``M_y = 13.7 N m`` added to the preloaded bearing (10 slices)."""
    bearing = seed_bearing(CLEARANCES["preload"])
    tilted = solve(bearing, [*LOAD[:4], MOMENT])
    straight = solve(bearing)
    j = MOST_LOADED - 1
    change = np.abs(tilted["inner_load"] - straight["inner_load"]).max() \
        / straight["inner_load"].max()
    return {"positions": bearing.slices.positions, "widths": bearing.slices.widths,
            "tilted": tilted, "straight": straight, "roller": MOST_LOADED,
            "inner_slices": tilted["slice_load"][j], "outer_slices": tilted["outer_slice_load"][j],
            "load_change": float(change), "tilt": float(tilted["displacement"][4])}


def summary_numbers(dist: dict[str, dict[str, Any]]) -> dict[str, float]:
    """Peak loads, rigid/flexible ratios and the flexible model's deviation from the FE."""
    num: dict[str, float] = {}
    for name, d in dist.items():
        for model in ("rigid", "flexible", "rigid_at_rest", "flexible_at_rest", "fe"):
            if model in d:
                num[f"{name}_{model}_max"] = float(d[model]["inner_load"].max())
        num[f"{name}_ratio"] = num[f"{name}_rigid_max"] / num[f"{name}_flexible_max"]
        num[f"{name}_ratio_at_rest"] = num[f"{name}_rigid_at_rest_max"] \
            / num[f"{name}_flexible_at_rest_max"]
        if "fe" in d:
            q_fe, q = d["fe"]["inner_load"], d["flexible"]["inner_load"]
            num[f"{name}_fe_max_error"] = float(q.max() / q_fe.max() - 1.0)
            num[f"{name}_fe_rms_error"] = float(np.sqrt(np.mean((q - q_fe) ** 2)) / q_fe.max())
            num[f"{name}_rigid_fe_ratio"] = num[f"{name}_rigid_max"] / float(q_fe.max())
    return num


# ------------------------------------------------------------------------ figures
def _figures(out: Path, dist: dict[str, dict[str, Any]], mis: dict[str, Any]) -> list[str]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    numbers = np.arange(1, SEED["n_rollers"] + 1)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    styles = (("rigid", "rigid rings", "s-"), ("flexible", "flexible rings (seed 001 model)",
                                               "o-"), ("fe", "flexible rings, 2D ring FE", "^--"))
    for ax, (name, g) in zip(axes, CLEARANCES.items(), strict=True):
        for key, label, style in styles:
            if key in dist[name]:
                ax.plot(numbers, dist[name][key]["inner_load"], style, ms=4, label=label)
        ax.set_title(f"g = {g * 1e6:+.0f} um, Fx = 5000 N, 12000 rpm")
        ax.set_xlabel("roller number")
        ax.set_ylabel("inner contact load Q_i [N]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "fig5_roller_loads.png", dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    s_mm = mis["positions"] * 1e3
    j = mis["roller"] - 1
    q_per_mm = 1e-3 / mis["widths"]
    ax.plot(s_mm, mis["inner_slices"] * q_per_mm, "o-", label=f"inner, My = {MOMENT} N m")
    ax.plot(s_mm, mis["outer_slices"] * q_per_mm, "s-", label=f"outer, My = {MOMENT} N m")
    ax.plot(s_mm, mis["straight"]["slice_load"][j] * q_per_mm, "k:", label="inner, My = 0")
    ax.set_xlabel("slice position along the roller s [mm]")
    ax.set_ylabel("line load [N/mm]")
    ax.set_title(f"roller {mis['roller']}, g = -40 um, 10 slices")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "fig8_misalignment.png", dpi=120)
    plt.close(fig)
    return ["fig5_roller_loads.png", "fig8_misalignment.png"]


def _report(out: dict[str, Any]) -> str:
    num = out["numbers"]
    lines = ["seed 001 flexible-ring roller bearing (Fx = 5000 N, 12000 rpm)"]
    for name, g in CLEARANCES.items():
        lines.append(f"  g = {g * 1e6:+.0f} um: max Q_i rigid {num[f'{name}_rigid_max']:.0f} N, "
                     f"flexible {num[f'{name}_flexible_max']:.0f} N, ratio "
                     f"{num[f'{name}_ratio']:.3f} (at rest {num[f'{name}_ratio_at_rest']:.3f})")
        if f"{name}_fe_max" in num:
            lines.append(f"      2D ring FE max Q_i {num[f'{name}_fe_max']:.0f} N: flexible model "
                         f"{100 * num[f'{name}_fe_max_error']:+.1f} % (rms "
                         f"{100 * num[f'{name}_fe_rms_error']:.1f} % of the FE peak)")
    mis = out["misalignment"]
    lines.append(f"  My = {MOMENT} N m: roller loads change by {100 * mis['load_change']:.3f} %, "
                 f"tilt ry = {mis['tilt'] * 1e3:.4f} mrad, roller {mis['roller']} inner slice "
                 f"loads {mis['inner_slices'].min():.0f}..{mis['inner_slices'].max():.0f} N")
    lines.append(f"  static solve (bearing_equilibrium): {1e3 * out['solve_time']:.1f} ms")
    return "\n".join(lines)


def main(fast: bool = False, outdir: str | Path | None = None) -> dict[str, Any]:
    """Run the seed 001 cases, write the figures, return the measured numbers.

    Parameters
    ----------
    fast : bool
        Coarser mesh of the ring FE comparison (the bearing model itself is the same).
    outdir : path, optional
        Folder of the figures; default ``docs/figures/seed001``.

    Returns
    -------
    dict
        ``distributions`` (per clearance: ``rigid``, ``flexible``, ``rigid_at_rest``,
        ``flexible_at_rest`` and, when available, ``fe`` results), ``numbers`` (peak loads,
        ratios, FE deviations), ``misalignment``, ``solve_time`` [s] of the flexible
        preloaded case, ``figures`` (file names) and ``fe_available``.
    """
    dist = load_distributions(fast)
    mis = misalignment()
    out: dict[str, Any] = {"distributions": dist, "numbers": summary_numbers(dist),
                           "misalignment": mis,
                           "solve_time": dist["preload"]["flexible"]["wall_time"],
                           "fe_available": "fe" in dist["preload"]}
    out["figures"] = _figures(Path(outdir) if outdir is not None else FIGURES, dist, mis)
    return out


def _cli() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="coarse FE mesh")
    parser.add_argument("--out", default=None, help="figure folder")
    args = parser.parse_args()
    print(_report(main(fast=args.fast, outdir=args.out)))


if __name__ == "__main__":
    _cli()

