"""Default showcase (``make run``): the damped two-disk rotor of Friswell et al. (2010).

Builds the rotor of example 5.9.5, then runs, prints and draws:

1. the modes at rest,
2. a Campbell diagram with forward/backward whirl and log decrements, and the 1X
   critical speeds (from the Campbell crossings and from the exact undamped solve),
3. the unbalance response (Bode and polar plots, peak amplitudes),
4. the static deflection under gravity with bearing reactions and bending moment,
5. the undamped critical-speed map.

Figures and a text summary go to ``results/default/``.

Run: ``python examples/showcase.py [--out DIR] [--fast]``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402
from examples.textbook_rotors import friswell_5_9_5  # noqa: E402

RPM = 30.0 / np.pi


def _table(rows: list[tuple], header: tuple[str, ...]) -> str:
    widths = [max(len(str(x)) for x in col) for col in zip(header, *rows, strict=True)]
    line = "  ".join(f"{h:>{w}}" for h, w in zip(header, widths, strict=True))
    body = ["  ".join(f"{x:>{w}}" for x, w in zip(r, widths, strict=True)) for r in rows]
    return "\n".join([line, "-" * len(line), *body])


def run(out: Path, fast: bool = False) -> dict[str, object]:
    """Run every analysis of the showcase, write figures to ``out`` and return key numbers."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    rotor = friswell_5_9_5(n_elements=6 if fast else 24)
    report: list[str] = [f"rotorsim {rs.__version__} showcase: {rotor.tag} (Friswell 5.9.5)"]
    s = rotor.summary()
    report.append(f"nodes {s['nodes']}, DOFs {s['dofs']}, shaft {s['mass_shaft_kg']:.2f} kg, "
                  f"disks {s['mass_disks_kg']:.2f} kg, length {s['length_m']:.3f} m")
    t0 = time.perf_counter()

    modes = rs.modal(rotor, speed=0.0, num_modes=8)
    report.append("\nModes at rest")
    report.append(_table([(i, f"{modes.wn[i]:.2f}", f"{modes.wd[i]:.2f}",
                           f"{modes.wd[i] / 2 / np.pi:.2f}", f"{modes.log_dec[i]:.4f}",
                           modes.kind[i]) for i in range(8)],
                         ("mode", "wn [rad/s]", "wd [rad/s]", "fd [Hz]", "log dec", "kind")))

    speeds = np.linspace(0.0, 4500.0 / RPM, 31 if fast else 91)
    camp = rs.campbell(rotor, speeds, num_modes=8)
    crit = camp.critical_speeds(harmonic=1)
    exact = rs.critical_speeds(rotor, harmonic=1, num_modes=6)
    report.append("\n1X critical speeds (damped, from the Campbell diagram)")
    report.append(_table([(f"{w * RPM:.0f}", f"{w:.2f}", wh, f"{ld:.4f}")
                          for w, wh, ld in zip(crit.speed, crit.whirl, crit.log_dec,
                                               strict=True) if w * RPM <= 4500],
                         ("rpm", "rad/s", "whirl", "log dec")))
    report.append("\nUndamped 1X critical speeds (exact synchronous solve)")
    report.append(_table([(f"{w * RPM:.0f}", f"{w:.2f}", wh)
                          for w, wh, kind in zip(exact.speed, exact.whirl, exact.kind,
                                                 strict=True) if kind == "lateral"],
                         ("rpm", "rad/s", "whirl")))

    disk_nodes = [d.n for d in rotor.disk_elements]
    unbalance = [(disk_nodes[1], 1e-4, 0.0)]
    resp_speeds = np.linspace(10.0 / RPM, 4500.0 / RPM, 151 if fast else 901)
    unb = rs.unbalance_response(rotor, resp_speeds, unbalance)
    report.append(f"\nUnbalance response to {unbalance[0][1]:g} kg m at node {disk_nodes[1]}")
    rows = []
    for node in disk_nodes:
        w, a = unb.peak(node, "ux")
        rows.append((node, f"{w * RPM:.0f}", f"{a * 1e6:.2f}"))
    report.append(_table(rows, ("node", "peak at [rpm]", "peak ux [um]")))

    stat = rs.static(rotor)
    assert stat.bearing_forces is not None
    report.append("\nStatic deflection under gravity")
    report.append(f"max |uy| = {np.abs(stat.deflection('uy')).max() * 1e6:.1f} um; bearing "
                  "reactions (y) = " + ", ".join(f"{f:.1f} N" for f in stat.bearing_forces[:, 1]))

    cmap = rs.critical_speed_map(rotor, (1e5, 1e9), num_points=12 if fast else 40,
                                 num_modes=4)
    elapsed = time.perf_counter() - t0
    report.append(f"\nall analyses: {elapsed:.2f} s")

    figures = {
        "campbell.png": rs.plot(camp, units="rpm"),
        "campbell_logdec.png": rs.plot(camp, units="rpm", color_by="log_dec"),
        "unbalance_bode.png": rs.plot(unb, node=disk_nodes[1]),
        "unbalance_polar.png": rs.plot(unb, node=disk_nodes[1], polar=True),
        "static.png": rs.plot(stat),
        "critical_speed_map.png": rs.plot(cmap),
    }
    for j in range(4):
        figures[f"mode_{j}.png"] = rs.plot(modes, mode=j)
    for name, fig in figures.items():
        fig.savefig(out / name, dpi=110, bbox_inches="tight")
        plt.close(fig)
    text = "\n".join(report)
    (out / "summary.txt").write_text(text + "\n")
    print(text)
    print(f"\nfigures and summary written to {out}/")
    return {"critical_speeds": crit, "exact": exact, "modes": modes, "unbalance": unb,
            "static": stat, "elapsed": elapsed, "figures": sorted(figures)}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "default")
    parser.add_argument("--fast", action="store_true", help="coarser grids (for tests)")
    args = parser.parse_args(argv)
    run(args.out, fast=args.fast)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
