"""The 1,000-DOF rotor of ``bench_transient.py`` against solve_ivp, in a shorter protocol.

``bench_transient.py --models rotor1000`` takes its reference from Radau at rtol 1e-10 and
runs every solve_ivp method at rtol 1e-2 ... 1e-4: more than an hour on a shared machine.
This script keeps its model, start, per-component tolerances, error measure and CPU timing,
and differs in two points only: the reference is LSODA at rtol 1e-8 (about 8 s of CPU;
rotorsim at rtol 1e-8 agrees with it to three digits of every error it reports), and the
peers run cheapest first (the settings that were cheapest in earlier runs), each line printed
as it ends, so that a stopped run still gives the fastest peer.

Run: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/transient_rotor1000.py``.
"""

from __future__ import annotations

import math
import os
import sys
import time
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parents[1]
for _path in (ROOT, ROOT / "benchmarks"):
    if str(_path) not in sys.path:
        sys.path.insert(0, str(_path))

import numpy as np  # noqa: E402
from bench_transient import MODELS, first_order, rotorsim_run  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

PEERS = (("LSODA", 1e-4), ("Radau", 1e-2), ("LSODA", 1e-2), ("BDF", 1e-2), ("Radau", 1e-3),
         ("Radau", 1e-4), ("LSODA", 1e-3), ("BDF", 1e-3), ("BDF", 1e-4))
"""solve_ivp runs, cheapest first."""


def main() -> None:
    bench = MODELS["rotor1000"]
    rhs, jac, y0, probe, full = first_order(bench)
    n = y0.size // 2
    times = np.linspace(0.0, bench.t_end, 41)
    start = (full, np.zeros_like(full))
    scout = rotorsim_run(bench, bench.t_end, min(bench.steps), times=times, initial=start,
                         velocities=True)
    scales = (float(np.ptp(scout.displacement(bench.probe, "uy"))),
              float(np.ptp(scout.velocity(bench.probe, "uy"))))
    per_component = np.concatenate([np.full(n, scales[0]), np.full(n, scales[1])])
    clock = time.process_time()
    ref = solve_ivp(rhs, (0.0, bench.t_end), y0, method="LSODA", jac=jac, rtol=1e-8,
                    atol=1e-8 * per_component, t_eval=times).y[probe]
    motion = float(np.ptp(ref))
    print(f"reference LSODA rtol 1e-8: {time.process_time() - clock:.1f} s CPU, "
          f"motion {motion:.4g} m", flush=True)
    model = bench.build()
    for rtol in bench.auto_rtols:
        clock = time.process_time()
        res = rotorsim_run(bench, bench.t_end, None, times=times, initial=start, rtol=rtol,
                           model=model)
        cpu = time.process_time() - clock
        err = float(np.max(np.abs(res.displacement(bench.probe, "uy") - ref))) / motion
        print(f"rotorsim auto rtol={rtol:g}: error {err:.3g}, {cpu:.3f} s, "
              f"{res.stats['steps']} steps, reduced {res.options['auto_reduction']['reduced']}",
              flush=True)
    for method, rtol in PEERS:
        clock = time.process_time()
        sol = solve_ivp(rhs, (0.0, bench.t_end), y0, method=method, jac=jac, rtol=rtol,
                        atol=rtol * per_component, t_eval=times)
        cpu = time.process_time() - clock
        err = float(np.max(np.abs(sol.y[probe] - ref))) / motion if sol.success else math.inf
        print(f"{method} rtol={rtol:g}: error {err:.3g}, {cpu:.3f} s", flush=True)


if __name__ == "__main__":
    main()
