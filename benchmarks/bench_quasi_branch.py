"""The default model's quasi-periodic branch (issue 17 performance target: the speed range
of its ``branch`` analysis, 500-2500 rpm, in under 60 s on one core).

``rs.periodic`` on ``models/default.toml`` with the analysis's own settings (H = 6, so the
box (6, 2) of 32 tones; pseudo-arclength continuation through the first critical speed's
folds), once without and once with the stability of every torus (quasi-periodic Hill
method). Prints the points, wall and CPU times, the time spent on the exponents, the peak
response and where it lies. CPU time is printed beside wall time: on a shared machine read
the CPU column.

Run: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_quasi_branch.py``.

``--with-stability``: only the branch with stability, as the first run in its process.
``--default-threads``: leave the BLAS thread count as the environment has it (by default
the script sets one thread, as the target says; rotorsim caps its own hot loops anyway).
``--compare``: the exponents of the same 190 tori twice in one run, with the box grown at
every torus and by :func:`~rotorsim.analyses.quasiperiodic.branch_stability.
branch_stability`'s rules: CPU times, tori checked, the largest difference of the largest
real parts and of the verdicts.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path
from typing import Any

if "--default-threads" not in sys.argv[1:]:    # else BLAS keeps its own thread count
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


def compare() -> None:
    import rotorsim.analyses.quasiperiodic.branch as qb

    captured: list[Any] = []
    schedule = qb.branch_stability

    def capture(points: Any, every: int = 8) -> Any:
        captured.extend(points)
        return schedule(points, every)

    qb.branch_stability = capture          # the branch's own tori, solved once
    model = rs.load_model(ROOT / "models" / "default.toml")
    spec: Any = model.analyses["branch"]
    rs.periodic(model, start=spec.start, stop=spec.stop, harmonics=spec.harmonics,
                unbalance=list(model.loads.unbalance), nodes=list(spec.nodes or ()),
                continuation=spec.continuation, stability=rs.StabilityOptions(beyond=0))
    qb.branch_stability = schedule
    results = {}
    for label, every in (("box grown at every torus", 1), ("branch_stability rules", 8)):
        cpu = time.process_time()
        results[label] = schedule(captured, every)
        cpu = time.process_time() - cpu
        checked = sum(s.checked for s in results[label])
        print(f"{label:26s} {len(captured)} tori, {checked:3d} checked, CPU {cpu:6.1f} s")
    every_torus, rules = results.values()
    big = np.array([s.exponents.largest for s in every_torus])
    small = np.array([s.exponents.largest for s in rules])
    rel = np.abs(small - big) / np.abs(big)
    k = int(np.argmax(rel))
    same = sum(a.stable == b.stable for a, b in zip(every_torus, rules, strict=True))
    print(f"largest real parts: max difference {rel[k]:.2e} of itself "
          f"({abs(small[k] - big[k]):.2e} 1/s, at {captured[k].speed / RPM:.1f} rpm, where "
          f"the full check tried {len(every_torus[k].boxes)} boxes); same verdict at "
          f"{same}/{len(captured)} tori")


if __name__ == "__main__":
    if "--compare" in sys.argv[1:]:
        compare()
    elif "--with-stability" in sys.argv[1:]:     # alone: the first run in its process
        run("auto")
    else:
        run(None)
        run("auto")
