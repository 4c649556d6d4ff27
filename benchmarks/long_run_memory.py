"""Memory of a long transient: reducers and ``every`` against storing every step.

Model: ``models/rolling_ball.toml`` (a 10-element shaft with a disk on two 9-ball bearings
with clearance, 66 free DOFs), gravity, an unbalance of 1e-5 kg m at the disk, 1000 rad/s,
average acceleration with ``dt = 20 us``, all nodes kept, three outputs of the same run:

* ``everything``: every step, displacements and velocities (the old default);
* ``every step``: every step, displacements only (the new default);
* ``reducers``: every 1000th step, and the reducers ``max_abs``, ``peak_to_peak`` (per
  revolution), ``max_amplitude`` and ``rms`` over every step.

For each it prints the bytes of the result's arrays (``nbytes`` of every array field,
dict entries and the final state included), the peak memory traced by ``tracemalloc``
during the run (a separate run: tracing slows the steps) and the wall time. Ratios come
from one run; absolute times are noisy on a shared machine.

Run: ``.venv/bin/python benchmarks/long_run_memory.py [--steps N] [--quick]`` (default
100,000 steps; ``--quick``: 5,000).
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
import time
import tracemalloc
from pathlib import Path
from typing import Any

import numpy as np

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import rotorsim as rs

MODEL = Path(__file__).resolve().parents[1] / "models" / "rolling_ball.toml"
DT, SPEED = 2e-5, 1000.0
OUTPUTS: dict[str, rs.Output] = {
    "everything": rs.Output(velocities=True),
    "every step": rs.Output(),
    "reducers": rs.Output(every=1000, reducers=("max_abs", "peak_to_peak", "max_amplitude",
                                                "rms")),
}


def result_bytes(value: Any) -> int:
    """Bytes of the arrays held by a result (fields, dict entries, nested dataclasses)."""
    if isinstance(value, np.ndarray):
        return int(value.nbytes)
    if isinstance(value, dict):
        return sum(result_bytes(v) for v in value.values())
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return sum(result_bytes(getattr(value, f.name)) for f in dataclasses.fields(value))
    return 0


def run(rotor: rs.Rotor, steps: int, output: rs.Output) -> rs.TransientResult:
    return rs.transient(rotor, steps * DT, DT, speed=SPEED, unbalance=[(5, 1e-5, 0.0)],
                        output=output)


def measure(steps: int) -> list[tuple[str, int, int, float, int]]:
    """``(name, result bytes, traced peak bytes, wall time [s], samples)`` per output."""
    model = rs.load_model(MODEL)
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    rows = []
    for name, output in OUTPUTS.items():
        clock = time.perf_counter()
        result = run(rotor, steps, output)
        wall = time.perf_counter() - clock
        tracemalloc.start()
        run(rotor, steps, output)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        rows.append((name, result_bytes(result), peak, wall, int(result.t.size)))
    return rows


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100_000)
    parser.add_argument("--quick", action="store_true", help="5,000 steps")
    args = parser.parse_args(argv)
    steps = 5_000 if args.quick else args.steps
    revolutions = steps * DT * SPEED / (2 * np.pi)
    print(f"rolling_ball.toml, 66 free DOFs, {steps} steps of {DT * 1e6:.0f} us at "
          f"{SPEED:.0f} rad/s ({revolutions:.0f} revolutions), all nodes kept")
    rows = measure(steps)
    base = rows[0]
    print(f"{'output':<12} {'samples':>8} {'result [MB]':>12} {'peak traced [MB]':>17} "
          f"{'time [s]':>9} {'memory ratio':>13} {'time ratio':>11}")
    for name, nbytes, peak, wall, samples in rows:
        print(f"{name:<12} {samples:>8} {nbytes / 1e6:>12.3f} {peak / 1e6:>17.3f} "
              f"{wall:>9.2f} {base[1] / nbytes:>12.0f}x {wall / base[3]:>11.2f}")


if __name__ == "__main__":
    main()
