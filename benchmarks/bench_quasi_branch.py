"""The default model's quasi-periodic branch (issue 17 performance target: the speed range
of its ``branch`` analysis, 500-2500 rpm, in under 60 s on one core).

``rs.periodic`` on ``models/default.toml`` with the analysis's own settings (H = 6, so the
box (6, 2) of 32 tones; pseudo-arclength continuation through the first critical speed's
folds), once without and once with the stability of every torus (quasi-periodic Hill
method). Prints the points, wall and CPU times, the time spent on the exponents, the peak
response and where it lies. CPU time is printed beside wall time: on a shared machine read
the CPU column.

Run: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_quasi_branch.py``.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")   # one core, as the target says

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import rotorsim as rs  # noqa: E402

RPM = np.pi / 30


def run(stability: str | None) -> None:
    model = rs.load_model(ROOT / "models" / "default.toml")
    spec: Any = model.analyses["branch"]      # a PeriodicSpec
    wall, cpu = time.perf_counter(), time.process_time()
    res = rs.periodic(model, start=spec.start, stop=spec.stop, harmonics=spec.harmonics,
                      unbalance=list(model.loads.unbalance), nodes=list(spec.nodes or ()),
                      continuation=spec.continuation, stability=stability)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    assert isinstance(res, rs.QuasiPeriodicResult)
    amp = res.amplitude(12, "uy", "peak_to_peak")
    k = int(np.argmax(amp))
    label = "with stability" if stability else "without stability"
    print(f"{label:18s} {len(res):4d} points, status {res.status.name}, wall {wall:6.1f} s, "
          f"CPU {cpu:6.1f} s, exponents {res.stats['stability_time']:5.1f} s; "
          f"max uy p-p at node 12 {amp[k] * 1e6:.1f} um at {res.speed[k] / RPM:.1f} rpm"
          + (f"; stable {int(res.stable.sum())}/{len(res)}, events {len(res.events)}"
             if stability else ""))


if __name__ == "__main__":
    run(None)
    run("auto")
