"""Bearing life and contact pressure cost against the issue 18 targets (one core).

Prints

* the cost of the life and pressures of one equilibrium (``rs.bearing_life`` given the
  solved equilibrium: ISO 281, ISO/TS 16281, Hertz pressure of every contact) as a
  fraction of the equilibrium solve (``rs.bearing_equilibrium``), for a 9-ball bearing, a
  14-roller, 20-slice roller bearing and a double-row unit of two such roller rows
  (target: under 10 %);
* the time of ``rs.transient_life`` over a 100,000-step transient of a rotor on two such
  bearings (target: under 1 s), the transient itself not counted: wall time and the
  process's CPU time (the second is less sensitive to other jobs on a shared machine; for
  the equilibrium part the 10th percentile of many runs).

Run: ``.venv/bin/python benchmarks/bench_bearing_life.py [--repeat N] [--steps N]``
(``--steps 0``: the equilibrium part only).
Each time is the best of ``N`` runs (default 5), so background load inflates it least.
"""

from __future__ import annotations

import argparse
import functools
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

import rotorsim as rs  # noqa: E402

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def best(fn: Callable[[], object], repeat: int,
         clock: Callable[[], float] = time.perf_counter) -> float:
    times = []
    for _ in range(repeat):
        t0 = clock()
        fn()
        times.append(clock() - t0)
    return min(times)


def low_cpu(fn: Callable[[], object], repeat: int) -> float:
    """10th percentile of the process CPU time of ``repeat`` runs: steadier than the
    wall-clock minimum when other jobs share the cores."""
    times = sorted(best(fn, 1, time.process_time) for _ in range(repeat))
    return times[len(times) // 10]


def bearings() -> dict[str, object]:
    ball = rs.BallBearing.from_geometry(n_balls=9, pitch_diameter=38.5e-3,
                                        ball_diameter=7.938e-3, f_i=0.52, f_o=0.53,
                                        diametral_clearance=10e-6)
    roller = rs.RollerBearing(14, 65e-3, 10e-3, 9.6e-3, model="slices", n_slices=20,
                              diametral_clearance=10e-6)
    double = rs.DoubleRowBearing(roller, row_spacing=0.03)
    return {"ball (9 balls)": ball, "roller (14 x 20 slices)": roller,
            "double row (2 x 14 x 20)": double}


def equilibrium_overhead(repeat: int) -> None:
    loads = {"ball (9 balls)": [2000.0, 0.0, 300.0, 0.0, 0.0],
             "roller (14 x 20 slices)": [8000.0, 0.0, 0.0, 0.0, 2.0],
             "double row (2 x 14 x 20)": [16000.0, 0.0, 0.0, 0.0, 20.0]}
    print("life and pressures of one equilibrium (best of", repeat, "runs)")
    for name, bearing in bearings().items():
        load = loads[name]
        eq = rs.bearing_equilibrium(bearing, load)
        rs.bearing_life(bearing, equilibrium=eq)  # warm-up: first use imports scipy.special
        solve = functools.partial(rs.bearing_equilibrium, bearing, load)
        rate = functools.partial(rs.bearing_life, bearing, equilibrium=eq)
        t_eq, t_life = best(solve, repeat), best(rate, repeat)
        c_eq, c_life = low_cpu(solve, 60 * repeat), low_cpu(rate, 60 * repeat)
        print(f"  {name:24s} equilibrium {1e3 * t_eq:7.3f} ms, life + pressures "
              f"{1e3 * t_life:7.3f} ms = {100 * t_life / t_eq:5.1f} % wall; "
              f"{100 * c_life / c_eq:5.1f} % CPU (target < 10 %)")


def rotor(bearing: object) -> tuple[rs.Rotor, list[rs.RollingBearing]]:
    shaft = [rs.ShaftElement(L=0.15, idl=0.0, odl=0.04, material=STEEL) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=STEEL, width=0.04, i_d=0.04, o_d=0.2)
    elements = [rs.RollingBearing(bearing, n=n, tag=f"B{n}") for n in (0, 2)]
    dampers = [rs.BearingElement(n=n, kxx=0.0, cxx=3000.0, cyy=3000.0) for n in (0, 2)]
    return (rs.Rotor(shaft, [disk], dampers, nonlinear_elements=elements,
                     fixed=[(1, "uz")]), elements)


def transient_overhead(repeat: int, steps: int) -> None:
    print(f"life over a {steps}-step transient (best of {repeat} runs)")
    for name, bearing in bearings().items():
        model, elements = rotor(bearing)
        t0 = time.perf_counter()
        res = rs.transient(model, steps * 2e-5, 2e-5, speed=600.0,
                           unbalance=[(1, 2e-5, 0.0)])
        t_run = time.perf_counter() - t0
        rate = functools.partial(rs.transient_life, res, elements[0])
        t_life = best(rate, repeat)
        t_cpu = best(rate, repeat, time.process_time)
        life = rate()
        print(f"  {name:24s} {res.t.size - 1} steps in {t_run:6.1f} s; transient_life "
              f"{t_life:6.3f} s wall, {t_cpu:6.3f} s CPU (target < 1 s); "
              f"L10r = {life.L10r:.4g} Mrev")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--steps", type=int, default=100_000)
    args = parser.parse_args()
    equilibrium_overhead(args.repeat)
    if args.steps > 0:  # --steps 0: the equilibrium part only
        transient_overhead(max(1, args.repeat // 2), args.steps)


if __name__ == "__main__":
    main()
