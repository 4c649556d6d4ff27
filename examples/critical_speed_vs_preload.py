"""Critical speeds of a rotor on ball bearings against the radial load and the preload.

The rotor of ``models/rolling_ball.toml`` (a disk on two 6205-like deep-groove ball
bearings). Its bearings are not given a stiffness: each is the rolling-element model of
seed 000 linearised at the rotor's nonlinear static equilibrium
(:func:`rotorsim.linearize_rolling_bearings`). Two studies:

1. a radial load at the disk (e.g. a belt pull) from 0 to 2 kN, with the 5 um radial
   clearance of the file;
2. the bearing clearance from +10 um (loose) to -5 um (interference: preload), with gravity
   only.

Hertz contacts stiffen with load (``k ~ Q^(1/3)`` per ball), and clearance leaves fewer
balls in the load zone, so the first forward critical speed rises with load and with preload.
The figure ``critical_speed_vs_preload.png`` shows both curves.

Run: ``python examples/critical_speed_vs_preload.py [--out DIR] [--fast]``.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402

RPM = 30.0 / np.pi


def first_forward_critical(model: rs.Model, *, loads=(), bearings=None) -> tuple[float, float]:
    """First forward 1X critical speed [rad/s] and the radial bearing stiffness kyy [N/m]
    of bearing 0, with the rolling bearings linearised at the static equilibrium."""
    rolling = model.rolling_bearings if bearings is None else bearings
    lin = rs.linearize_rolling_bearings(model.rotor, rolling, loads=loads)
    crit = rs.critical_speeds(lin.rotor, 1, num_modes=1, whirl="forward")
    return float(crit.speed[0]), float(lin.bearings[0].stiffness_matrix[1, 1])


def run(out: Path, fast: bool = False) -> dict[str, np.ndarray]:
    """Both studies; writes the figure to ``out`` and returns the curves."""
    model = rs.load_model(ROOT / "models" / "rolling_ball.toml")
    disk = model.rotor.disk_elements[0].n
    loads = np.linspace(0.0, 2000.0, 4 if fast else 9)
    by_load = np.array([first_forward_critical(model, loads=[(disk, "uy", -f)])
                        for f in loads])
    clearances = np.linspace(10e-6, -5e-6, 4 if fast else 7)
    by_clearance = []
    for c in clearances:
        bearings = tuple(dataclasses.replace(rb, bearing=dataclasses.replace(
            rb.bearing, radial_clearance=float(c), diametral_clearance=None))
            for rb in model.rolling_bearings)
        by_clearance.append(first_forward_critical(model, bearings=bearings))
    by_clearance_arr = np.array(by_clearance)
    _figure(out, loads, by_load, clearances, by_clearance_arr)
    for name, x, unit, table in (("radial load at the disk", loads, "N", by_load),
                                 ("radial clearance", clearances * 1e6, "um",
                                  by_clearance_arr)):
        print(f"first forward critical speed vs {name}:")
        for xi, (w, k) in zip(x, table, strict=True):
            print(f"  {xi:8.1f} {unit}: {w * RPM:8.1f} rpm   kyy = {k:.3e} N/m")
    return {"loads": loads, "by_load": by_load, "clearances": clearances,
            "by_clearance": by_clearance_arr}


def _figure(out: Path, loads, by_load, clearances, by_clearance) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.plot(loads, by_load[:, 0] * RPM, "o-")
    left.set_xlabel("radial load at the disk [N]")
    right.plot(clearances * 1e6, by_clearance[:, 0] * RPM, "s-")
    right.invert_xaxis()
    right.set_xlabel("radial clearance [um] (negative: preload)")
    for ax in (left, right):
        ax.set_ylabel("first forward critical speed [rpm]")
        ax.grid(alpha=0.3)
    fig.suptitle("Ball bearings linearised at the static equilibrium (seed 000 model)")
    fig.savefig(out / "critical_speed_vs_preload.png", dpi=110, bbox_inches="tight")
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "examples")
    parser.add_argument("--fast", action="store_true", help="fewer points (tests)")
    args = parser.parse_args(argv)
    run(args.out, fast=args.fast)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
