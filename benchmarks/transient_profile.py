"""Where the automatic transient path spends its time on the small benchmark rotors.

Wraps the automatic Craig-Bampton reduction ahead of exponential collocation (its choice
and basis, ``exponential_reduction``), the eigen-decomposition (``LinearModes.build``), the
batched bearing evaluations (``RestoringForce.batch``), the steps (``Exponential.step``)
and the dense output (``Exponential.interpolate``) with ``time.process_time`` counters and
runs ``rs.transient(..., rtol=)`` on the ``bench`` and ``issue14`` models of
``bench_transient.py`` (same start, output times and model objects built once), five times
each; prints CPU ms per run and the shares. The steps include their bearing evaluations.
With ``--long`` it also runs ``issue14`` over 50 ms (8 revolutions) at rtol 1e-3 and 1e-5
by exponential collocation and by Radau IIA (the automatic path with the exponential
path's size limit set to 0) and prints their CPU times, steps and difference.

Run: ``OPENBLAS_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python benchmarks/transient_profile.py
[--long]``.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parents[1]
for _path in (ROOT, ROOT / "benchmarks"):
    if str(_path) not in sys.path:
        sys.path.insert(0, str(_path))

import numpy as np  # noqa: E402
from bench_transient import MODELS, first_order, rotorsim_run  # noqa: E402

import rotorsim.analyses.transient.auto_exponential as auto_exponential  # noqa: E402
import rotorsim.analyses.transient.exponential_reduction as reduction  # noqa: E402
import rotorsim.analyses.transient.loads as loads  # noqa: E402
import rotorsim.time_integration.exponential as exponential  # noqa: E402
import rotorsim.time_integration.exponential_modes as modes  # noqa: E402

CASES = (("issue14", 3e-2), ("issue14", 1e-3), ("bench", 3e-3), ("bench", 1e-4))
"""Model and rtol: the cheapest runs at 1e-3 and 1e-5 of the motion in the benchmark."""
REPEATS = 5


def timed(owner: Any, name: str, key: str, clock: dict[str, float]) -> None:
    """Replace ``owner.name`` by a wrapper adding its CPU time to ``clock[key]``."""
    inner: Callable[..., Any] = getattr(owner, name)

    def wrapper(*args: Any, **kwargs: Any) -> Any:
        start = time.process_time()
        try:
            return inner(*args, **kwargs)
        finally:
            clock[key] = clock.get(key, 0.0) + time.process_time() - start

    setattr(owner, name, wrapper)


def main() -> None:
    clock: dict[str, float] = {}
    timed(reduction, "exponential_reduction", "reduction (choice and basis)", clock)
    timed(modes.LinearModes, "build", "eigen-decomposition", clock)
    timed(loads.RestoringForce, "batch", "bearing evaluations", clock)
    timed(exponential.Exponential, "step", "steps (with their bearings)", clock)
    timed(exponential.Exponential, "interpolate", "dense output", clock)
    for name, rtol in CASES:
        bench = MODELS[name]
        _, _, _, _, full = first_order(bench)
        start, model = (full, np.zeros_like(full)), bench.build()
        times = np.linspace(0.0, bench.t_end, 41)
        rotorsim_run(bench, bench.t_end, None, times=times, initial=start, rtol=rtol,
                     model=model)
        clock.clear()
        begin = time.process_time()
        for _ in range(REPEATS):
            res = rotorsim_run(bench, bench.t_end, None, times=times, initial=start,
                               rtol=rtol, model=model)
        total = (time.process_time() - begin) / REPEATS
        print(f"{name} rtol {rtol:g} ({res.method}): {1e3 * total:.1f} ms CPU per run, "
              f"{res.stats['steps']} steps + {res.stats['rejected_steps']} rejected, "
              f"{res.stats['residual_evaluations']} bearing calls, reduced to "
              f"{(res.options['reduction'] or {}).get('size', 'none')}")
        for key, value in clock.items():
            share = value / REPEATS
            print(f"  {key:30s} {1e3 * share:7.1f} ms {100 * share / total:5.1f} %")


def long_run(t_end: float = 0.05) -> None:
    """Exponential collocation against Radau IIA on ``issue14`` over ``t_end``."""
    bench = MODELS["issue14"]
    _, _, _, _, full = first_order(bench)
    start, model = (full, np.zeros_like(full)), bench.build()
    times = np.linspace(0.0, t_end, 201)
    limit, probe = auto_exponential.EXPONENTIAL_LIMIT, {}
    try:
        for size in (limit, 0):
            auto_exponential.EXPONENTIAL_LIMIT = size
            for rtol in (1e-3, 1e-5):
                begin = time.process_time()
                res = rotorsim_run(bench, t_end, None, times=times, initial=start,
                                   rtol=rtol, model=model)
                cpu = time.process_time() - begin
                probe[(res.method, rtol)] = res.displacement(bench.probe, "uy")
                print(f"issue14 over {1e3 * t_end:g} ms, {res.method} rtol {rtol:g}: "
                      f"{cpu:.3f} s CPU, {res.stats['steps']} steps")
    finally:
        auto_exponential.EXPONENTIAL_LIMIT = limit
    for rtol in (1e-3, 1e-5):
        a, b = probe[("exponential", rtol)], probe[("radau5", rtol)]
        print(f"rtol {rtol:g}: the two differ by {np.max(np.abs(a - b)) / np.ptp(b):.2g} "
              "of the motion")


if __name__ == "__main__":
    main()
    if "--long" in sys.argv[1:]:
        long_run()
