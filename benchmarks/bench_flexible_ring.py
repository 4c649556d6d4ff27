"""Flexible-ring roller bearing (seed 001) performance against the issue 5 targets (one core).

Prints:

* the throughput of :meth:`FlexibleRingBearingElement.force` (force and condensed exact
  tangent, 12 DOFs) of the seed 001 bearing (24 rollers, 10 slices, 4 internal DOFs per
  roller, 12000 rpm, ``g = -40 um``) for batches of S = 1024 samples of a whirling orbit:
  cold (no ``internal``) and warm-started from the ``internal`` of the previous call after a
  small change of the orbit (as in a time step or a harmonic-balance iteration);
  target 20,000 samples/s;
* the time of one static solve of the seed case
  (:func:`~rotorsim.analyses.statics.bearing_statics.bearing_equilibrium`, ``F_x = 5000 N``);
  target < 50 ms;
* the inner Newton statistics of these calls.

Run: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_flexible_ring.py
[--repeat N]``. Each time is the best of ``N`` runs (default 5), so background load inflates
it least.
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
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core, as the targets say

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from examples import seed001_flexible_rings as seed  # noqa: E402
from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium  # noqa: E402
from rotorsim.elements.rolling.flexible_ring.element import (  # noqa: E402
    FlexibleRingBearingElement,
)

TARGETS = {"samples_per_s": 20_000.0, "solve_ms": 50.0}
BATCH = 1024


def best_time(fun: Callable[[], object], repeat: int) -> float:
    """Shortest wall time [s] of ``repeat`` calls (after one warm-up call)."""
    fun()
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fun()
        times.append(time.perf_counter() - start)
    return min(times)


def orbit(scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Element DOFs (S, 12) of a whirling, tilting inner ring over one revolution, and the
    shaft angles (S,)."""
    phi = np.linspace(0.0, 2.0 * math.pi, BATCH, endpoint=False)
    u = np.zeros((BATCH, 12))
    u[:, 0] = 4.2e-6 + scale * 1.5e-6 * np.cos(phi)
    u[:, 1] = scale * 1.5e-6 * np.sin(phi)
    u[:, 3] = scale * 2e-5 * np.sin(2.0 * phi)
    u[:, 4] = 1e-5 + scale * 1e-5 * np.cos(phi)
    return u, phi


def throughput(repeat: int) -> dict[str, Any]:
    """Samples per second of ``force()`` (cold and warm) for S = 1024."""
    element = FlexibleRingBearingElement(seed.seed_bearing(-40e-6), n=0, n_link=1)
    u, phi = orbit()
    u2, _ = orbit(1.0 + 1e-4)
    v = np.zeros_like(u)
    first = element.force(u, v, phi, seed.SPEED)
    cold = best_time(lambda: element.force(u, v, phi, seed.SPEED), repeat)
    warm = best_time(lambda: element.force(u2, v, phi, seed.SPEED, first.internal), repeat)
    st_cold = element.state(u, phi, seed.SPEED, details=False)
    st_warm = element.state(u2, phi, seed.SPEED, first.internal, details=False)
    return {"cold": BATCH / cold, "warm": BATCH / warm, "cold_stats": st_cold.inner,
            "warm_stats": st_warm.inner}


def static_solves(repeat: int) -> dict[str, float]:
    """Best time [ms] of one bearing equilibrium of the seed cases."""
    out = {}
    for name, g, load in (("g=-40um", -40e-6, seed.LOAD),
                          ("g=+10um", 10e-6, seed.LOAD),
                          ("g=-40um, My=13.7", -40e-6, (*seed.LOAD[:4], seed.MOMENT))):
        bearing = seed.seed_bearing(g)
        out[name] = 1e3 * best_time(functools.partial(bearing_equilibrium, bearing, load),
                                    repeat)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    tp = throughput(args.repeat)
    print(f"flexible-ring bearing, 24 rollers x 10 slices, S = {BATCH} "
          f"(OPENBLAS_NUM_THREADS={os.environ['OPENBLAS_NUM_THREADS']})")
    for key in ("cold", "warm"):
        st = tp[f"{key}_stats"]
        print(f"  force + condensed tangent, {key:4s}: {tp[key]:10.0f} samples/s "
              f"(target {TARGETS['samples_per_s']:.0f}, ratio "
              f"{tp[key] / TARGETS['samples_per_s']:.2f}); inner Newton: {st.iterations} "
              f"iterations, {st.system_iterations / st.systems:.2f} per roller, "
              f"{st.backtracks} backtracks, {st.failures} failures")
    for name, ms in static_solves(args.repeat).items():
        print(f"  static solve {name:18s}: {ms:7.1f} ms (target {TARGETS['solve_ms']:.0f} ms, "
              f"ratio {ms / TARGETS['solve_ms']:.2f})")


if __name__ == "__main__":
    main()
