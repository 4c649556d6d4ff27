"""Stability map: least logarithmic decrement over bearing stiffness x spin speed.

The two-disk rotor of Friswell et al. (2010, examples 5.9.x) runs on two identical
isotropic supports of stiffness ``k`` and damping ``c`` that also carry a destabilising
cross-coupled stiffness growing with speed, as in a seal or a plain journal bearing:
``kxy = -kyx = q(W) = swirl * c * W`` (``swirl``: average circumferential swirl ratio of
the fluid, 0.5 for a plain bearing). The sweep evaluates the least log dec of the lateral
modes at every (``k``, ``W``) of a grid and draws the map with its zero contour, the
stability boundary.

Energy balance gives the boundary independently. The supports are isotropic, so the
modes whirl on circles; per cycle of a forward mode of frequency ``w`` a support
transfers ``pi r^2 (q - c w)`` to the rotor (``r``: whirl radius there). On the boundary
(``Re lam = 0``) the total vanishes: ``q = c w``, i.e. ``swirl * W = w``, and ``w`` is
then a forward natural frequency of the undamped rotor on supports of stiffness ``k``.
The onset speed ``W*`` solves ``swirl * W* = w_f(W*)`` with ``w_f`` the first forward
undamped natural frequency: half-frequency whirl for ``swirl = 0.5``.

Run: ``python examples/stability_map.py [--out DIR] [--fast] [--workers N]``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np
from scipy.optimize import brentq

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples.textbook_rotors import friswell_two_disk_rotor  # noqa: E402
from rotorsim.analyses.linear.modal import modal  # noqa: E402
from rotorsim.analyses.sweep.sweep import Grid, min_log_dec, set_bearing_stiffness, sweep  # noqa: E402
from rotorsim.elements.linear_bearing import BearingElement  # noqa: E402
from rotorsim.model.rotor import Rotor  # noqa: E402
from rotorsim.results.sweep import SweepResult  # noqa: E402

DAMPING = 2e3
"""Support damping c [N s/m]."""
SWIRL = 0.5
"""Average swirl ratio: cross-coupled stiffness ``q = SWIRL * c * W``."""
MAX_SPEED = 600.0
"""Top spin speed of the map [rad/s]."""


def seal_rotor(stiffness: float = 1e6, damping: float = DAMPING, swirl: float = SWIRL,
               max_speed: float = MAX_SPEED) -> Rotor:
    """The two-disk rotor on supports with ``kxy = -kyx = swirl * c * W``.

    The cross-coupling is tabulated linearly from 0 to ``max_speed`` [rad/s] (held beyond).
    Axial and torsional DOFs are fixed: the map is about lateral stability.
    """
    speed = np.array([0.0, max_speed])
    q = swirl * damping * speed
    bearings = [BearingElement(n=n, kxx=stiffness, cxx=damping, kxy=q, kyx=-q,
                               frequency=speed, tag=f"seal_bearing_{i}")
                for i, n in enumerate((0, 6))]
    return friswell_two_disk_rotor().with_bearings(bearings).without_axial_torsion()


def stability_grid(fast: bool = False) -> Grid:
    """Bearing stiffness (log-spaced, 0.1 to 100 MN/m) x spin speed (0 to MAX_SPEED)."""
    n_k, n_w = (6, 9) if fast else (25, 41)
    return Grid({"bearing_k": np.logspace(5.0, 8.0, n_k),
                 "speed": np.linspace(0.0, MAX_SPEED, n_w)})


def first_forward_frequency(stiffness: float, speed: float) -> float:
    """First forward natural frequency [rad/s] of the undamped rotor on supports of
    ``stiffness`` (no cross-coupling) spinning at ``speed``."""
    rotor = friswell_two_disk_rotor(kxx=stiffness).without_axial_torsion()
    m = modal(rotor, speed, 4, sparse=False)
    forward = [w for w, whirl in zip(m.wd, m.whirl, strict=True) if whirl == "forward"]
    return float(min(forward))


def energy_balance_onset(stiffness: float, swirl: float = SWIRL,
                         max_speed: float = MAX_SPEED) -> float:
    """Onset speed ``W*`` solving ``swirl * W* = w_f(W*)`` (NaN if above ``max_speed``)."""
    gap = lambda w: swirl * w - first_forward_frequency(stiffness, w)  # noqa: E731
    if gap(max_speed) <= 0:
        return float("nan")
    return float(brentq(gap, 0.0, max_speed, xtol=1e-10, rtol=1e-14))


def onset_from_map(result: SweepResult) -> np.ndarray:
    """Lowest speed where the least log dec crosses zero, per stiffness (linear
    interpolation between grid speeds; NaN if the row stays stable)."""
    log_dec, speed = result.reshape("log_dec_min"), result.axis("speed")
    onset = np.full(log_dec.shape[0], np.nan)
    for row, values in enumerate(log_dec):
        below = np.flatnonzero(values < 0)
        if below.size and below[0] > 0:
            j = below[0]
            t = values[j - 1] / (values[j - 1] - values[j])
            onset[row] = speed[j - 1] + t * (speed[j] - speed[j - 1])
    return onset


def stability_sweep(out: Path, fast: bool = False, swirl: float = SWIRL,
                    executor: Any = "serial", max_workers: int | None = None) -> SweepResult:
    """Run (or resume) the map sweep, stored in ``out/stability_map[_fast].h5``."""
    out.mkdir(parents=True, exist_ok=True)
    name = f"stability_map_swirl{swirl:g}{'_fast' if fast else ''}.h5"
    return sweep(seal_rotor(swirl=swirl), stability_grid(fast),
                 set_bearing_stiffness([0, 1], "bearing_k"),
                 min_log_dec("speed", num_modes=6, sparse=False), store=out / name,
                 executor=executor, max_workers=max_workers, progress=not fast)


def draw(result: SweepResult, onset: np.ndarray, path: Path) -> None:
    """Filled contours of the least log dec, its zero contour and the energy-balance onset."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    k, w = result.axis("bearing_k"), result.axis("speed")
    z = result.reshape("log_dec_min").T
    fig, ax = plt.subplots(figsize=(7, 4.5))
    limit = float(np.nanmax(np.abs(z)))
    filled = ax.contourf(k, w, z, levels=np.linspace(-limit, limit, 21), cmap="RdBu")
    ax.contour(k, w, z, levels=[0.0], colors="k", linewidths=2.0)
    ax.plot(k, onset, "o", color="gold", mec="k", label="energy balance: swirl W = w_f(W)")
    ax.set_xscale("log")
    ax.set_xlabel("bearing stiffness k [N/m]")
    ax.set_ylabel("spin speed W [rad/s]")
    ax.set_title("least log dec (black: stability boundary, blue: stable)")
    fig.colorbar(filled, ax=ax, label="log dec [-]")
    ax.legend(loc="upper left", fontsize=8)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)


def main(fast: bool = False, out: str | Path = "results/examples", executor: Any = "serial",
         max_workers: int | None = None) -> dict[str, Any]:
    """Run the map, draw ``stability_map.png`` and return the numbers behind it."""
    out = Path(out)
    result = stability_sweep(out, fast, SWIRL, executor, max_workers)
    onset = np.array([energy_balance_onset(k) for k in result.axis("bearing_k")])
    figure = out / ("stability_map_fast.png" if fast else "stability_map.png")
    draw(result, onset, figure)
    mapped = onset_from_map(result)
    print(f"stability map: {result.n_points} points, {int(result.stats['evaluated'])}"
          f" evaluated, {int(result.stats['resumed'])} resumed from the store")
    for k, a, b in zip(result.axis("bearing_k"), mapped, onset, strict=True):
        print(f"  k = {k:9.3g} N/m: onset {a:7.1f} rad/s (map), {b:7.1f} rad/s"
              " (energy balance)")
    return {"result": result, "onset_map": mapped, "onset_energy": onset, "figure": figure}


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="results/examples")
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--workers", type=int, default=0, help="local processes (0: serial)")
    args = parser.parse_args()
    main(args.fast, args.out, "process" if args.workers else "serial", args.workers or None)
