"""Cost per step of a run-up against a constant-speed run (issue 14, parts 3 and 4).

A run-up changes the gyroscopic term ``W(t) G`` (and tabulated bearing coefficients) at every
step. rotorsim factorises the iteration matrix at a few speed nodes and iterates with it in
between; the old behaviour, a factorisation at every step, is ``Newmark(max_contraction=0)``.
Three models, each run over the same span and step at constant top speed, as a run-up
(speed nodes, the default) and as a run-up refactorising at every step:

* ``default``: models/default.toml, two-disk rotor on two ball bearings with clearance
  (nonlinear), 0 -> 4500 rpm in 0.5 s at 100 us: the model file's ``runup`` analysis;
* ``tilting_pad``: models/compressor_tilting_pad.toml, tilting-pad bearings tabulated over
  speed (affine), 2000 -> 11000 rpm at 50 us;
* ``large``: models/large_rotor.toml, linear bearings, 726 unknowns (sparse), 0 -> 1000 rad/s
  at 100 us.

Times are CPU time (``time.process_time``: the machine is shared). Each model's three rows
are run ``--repeat`` times (default 3) in turn and the shortest time of each row is kept, so
that a burst of load on the machine does not land on one row only; the ratios come from one
run of the script.

Run: ``OPENBLAS_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python benchmarks/runup_cost.py [--quick]
[--repeat N]``
(``PYTHONPATH=.`` so that a worktree runs its own ``rotorsim``, not the installed one).
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import rotorsim as rs
from rotorsim.solvers.threads import one_blas_thread

ROOT = Path(__file__).resolve().parents[1]
RPM = math.pi / 30.0


@dataclass(frozen=True)
class Case:
    """A model and its run: span [s], step [s], speeds [rad/s] and transient keywords."""

    name: str
    path: str
    t_end: float
    dt: float
    start: float
    stop: float
    nonlinear: bool
    keywords: dict[str, Any]


CASES = (
    Case("default", "models/default.toml", 0.5, 1e-4, 0.0, 4500 * RPM, True,
         dict(unbalance=[(8, 1e-4, 0.0)], nodes=[8, 16])),
    Case("tilting_pad", "models/compressor_tilting_pad.toml", 1.0, 5e-5, 2000 * RPM,
         11000 * RPM, False, dict(unbalance=[(8, 7.6e-5, 0.0)], nodes=[15])),
    Case("large", "models/large_rotor.toml", 0.5, 1e-4, 0.0, 1000.0, False,
         dict(unbalance=[(60, 1e-4, 0.0)], nodes=[60],
              excitation=rs.Excitation(gravity=None), initial="zero")),
)


def run(case: Case, speed: Any, method: rs.Newmark, t_end: float) -> dict[str, float]:
    """One run's CPU time per step [us], factorisations and Newton iterations per step."""
    model = rs.load_model(ROOT / case.path)
    rotor = model.rotor.with_nonlinear(model.rolling_bearings) if case.nonlinear \
        else model.rotor
    clock = time.process_time()
    res = rs.transient(rotor, t_end, case.dt, speed=speed, method=method, **case.keywords)
    wall = time.process_time() - clock
    steps = float(res.stats["steps"])
    return {"us_per_step": 1e6 * wall / steps, "factorizations": res.stats["factorizations"],
            "iterations": res.stats["iterations_per_step"], "steps": steps,
            "end": float(np.max(np.abs(res.q[-1])))}


@one_blas_thread()
def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="a fifth of each span")
    parser.add_argument("--repeat", type=int, default=3, help="runs of each row (fastest kept)")
    parser.add_argument("--cases", nargs="+", default=[c.name for c in CASES],
                        choices=[c.name for c in CASES])
    args = parser.parse_args()
    print("| model | run | steps | factorisations | Newton iterations per step | us per step "
          "| ratio to constant speed |")
    print("|---|---|---|---|---|---|---|")
    for case in CASES:
        if case.name not in args.cases:
            continue
        t_end = case.t_end / 5 if args.quick else case.t_end
        ramp = rs.LinearSpeed(case.start, case.stop, 0.0, t_end)
        rows = [("constant top speed", case.stop, rs.Newmark()),
                ("run-up, speed nodes", ramp, rs.Newmark()),
                ("run-up, factorised every step", ramp, rs.Newmark(max_contraction=0.0))]
        outs: list[dict[str, float]] = [{} for _ in rows]
        for _ in range(max(1, args.repeat)):
            for out, (_, speed, method) in zip(outs, rows, strict=True):
                new = run(case, speed, method, t_end)
                if not out or new["us_per_step"] < out["us_per_step"]:
                    out.update(new)
        base = outs[0]["us_per_step"]
        for out, (label, _, _) in zip(outs, rows, strict=True):
            print(f"| `{case.name}` | {label} | {out['steps']:.0f} | "
                  f"{out['factorizations']:.0f} | {out['iterations']:.2f} | "
                  f"{out['us_per_step']:.0f} | {out['us_per_step'] / base:.2f} |")


if __name__ == "__main__":
    main()
