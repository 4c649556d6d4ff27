"""Rolling-bearing performance against the issue 4 targets (one core).

Prints:

* ``state()`` throughput (force + exact tangent) of a 12-ball bearing and a 14-roller,
  20-slice roller bearing for a batch of S = 4096 samples (targets 200,000 and 50,000
  samples/s);
* the time of one bearing equilibrium solve (Newton and energy method; target < 5 ms);
* the time of the global search of one load case (target < 1 s; the seed reports "several
  seconds" in MATLAB).

Run: ``.venv/bin/python benchmarks/bench_bearings.py [--repeat N]``. Each time is the best
of ``N`` runs (default 5), so background load inflates it least.
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core, as the targets say

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from examples import seed000_load_cases as seed  # noqa: E402
from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium  # noqa: E402
from rotorsim.elements.rolling.ball.bearing import BallBearing  # noqa: E402
from rotorsim.elements.rolling.roller.bearing import RollerBearing  # noqa: E402

TARGETS = {"ball": 200_000.0, "roller": 50_000.0, "solve_ms": 5.0, "global_s": 1.0}


def best_time(fun: Callable[[], object], repeat: int) -> float:
    """Shortest wall time [s] of ``repeat`` calls (after one warm-up call)."""
    fun()
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fun()
        times.append(time.perf_counter() - start)
    return min(times)


def throughput(repeat: int) -> dict[str, float]:
    """Samples per second of ``state()`` for S = 4096."""
    rng = np.random.default_rng(0)
    n_samples = 4096
    ball = BallBearing(n_balls=12, pitch_diameter=39.3e-3, ball_diameter=7.9e-3, Kn=8.5e9,
                       A0=0.05e-3, contact_angle=math.radians(25.0))
    roller = RollerBearing(14, 42.5e-3, 7.5e-3, 10e-3, Kn=3.0e8, model="slices", n_slices=20,
                           contact_angle=math.radians(10.0))
    out = {}
    for name, bearing in (("ball", ball), ("roller", roller)):
        delta = rng.normal(size=(n_samples, 5)) * [15e-6, 15e-6, 15e-6, 5e-4, 5e-4]
        delta[:, 2] += 10e-6
        psi = bearing.element_angles(rng.uniform(0, 2 * math.pi, n_samples))
        out[name] = n_samples / best_time(functools.partial(bearing.state, delta, psi),
                                          repeat)
    return out


def solves(repeat: int) -> dict[str, float]:
    """Wall time [s] of one equilibrium solve per method, seed 000 cases (ii) and (v)."""
    cases = {"ball (ii), 25 deg": (seed.ball_bearing(25.0), seed.LOAD_CASES["ii"][1]),
             "roller (v), 20 deg": (seed.roller_bearing(20.0), seed.LOAD_CASES["v"][1])}
    out = {}
    for label, (bearing, load) in cases.items():
        for method in ("newton", "energy", "global"):
            out[f"{label}: {method}"] = best_time(
                functools.partial(bearing_equilibrium, bearing, load, method=method),
                repeat)
    return out


def main(repeat: int = 5) -> dict[str, float]:
    rates = throughput(repeat)
    times = solves(repeat)
    print("state() throughput, S = 4096 (force + tangent)")
    print(f"  12-ball bearing:              {rates['ball']:>10,.0f} samples/s   "
          f"target {TARGETS['ball']:,.0f}  ratio {rates['ball'] / TARGETS['ball']:.2f}")
    print(f"  14-roller, 20 slices:         {rates['roller']:>10,.0f} samples/s   "
          f"target {TARGETS['roller']:,.0f}  ratio {rates['roller'] / TARGETS['roller']:.2f}")
    print("bearing equilibrium (best of runs)")
    for label, seconds in times.items():
        global_search = label.endswith("global")
        target = TARGETS["global_s"] if global_search else TARGETS["solve_ms"] * 1e-3
        print(f"  {label:<30} {1e3 * seconds:8.2f} ms   target {1e3 * target:6.0f} ms  "
              f"ratio {target / seconds:.1f}")
    return {**rates, **times}


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per timing (best kept)")
    main(parser.parse_args().repeat)
