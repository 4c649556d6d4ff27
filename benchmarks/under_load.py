"""rotorsim next to a busy process: the BLAS thread caps of the hot loops (issue 12).

Two cases:

* ``runup``: the run-up transient of ``models/default.toml`` (analysis ``runup``: 0 ->
  4500 rpm in 0.5 s on the nonlinear ball bearings, 5000 steps), run as the CLI runs it;
  ``--quick`` runs its first 0.05 s (500 steps, the CLI's ``--fast``);
* ``campbell``: a 50-speed Campbell (0 ... 1000 rad/s, 12 modes) of the 100-element,
  606-DOF benchmark rotor of ``bench_model.py``.

Each case is timed in a fresh process, in five settings:

* ``alone-1``: alone, one BLAS thread (the reference);
* ``alone-old`` / ``alone-new``: alone, default threading, caps off / on;
* ``loaded-1``: next to one busy process (a numpy matmul loop with the default BLAS
  threads, or with one thread: ``--neighbour single``), one BLAS thread throughout: what
  is left is the CPU the neighbour takes, which no thread setting can give back;
* ``loaded-old`` / ``loaded-new``: next to the busy process, default threading, caps off /
  on.

"caps off" is the behaviour before the caps (``ROTORSIM_BLAS_CAP=off``). The goal is
``loaded-new / alone-1 <= 2``. Run it WITHOUT ``OMP_NUM_THREADS``/``OPENBLAS_NUM_THREADS``
set (the point is the default threading); the script removes them from its child
processes and says so.

Run: ``.venv/bin/python benchmarks/under_load.py [--quick] [--cases runup campbell]
[--neighbour blas|single]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
THREAD_VARS = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
SETTINGS = ("alone-1", "alone-old", "alone-new", "loaded-1", "loaded-old", "loaded-new")
BUSY = ("import numpy as np\n"
        "a = np.random.default_rng(0).standard_normal((600, 600))\n"
        "while True:\n"
        "    a = a @ a\n"
        "    a /= np.abs(a).max()\n")
GOAL = 2.0


def run_case(case: str, quick: bool) -> float:
    """Wall time [s] of one case in this process."""
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    if case == "runup":
        from rotorsim.io.model_file import load_model, run_analysis

        model = load_model(ROOT / "models" / "default.toml")
        clock = time.perf_counter()
        run_analysis(model, "runup", fast=quick)
        return time.perf_counter() - clock
    import numpy as np

    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_model import benchmark_description, build_rotorsim

    from rotorsim.analyses.linear.campbell import campbell

    rotor = build_rotorsim(benchmark_description(100))
    clock = time.perf_counter()
    campbell(rotor, np.linspace(0.0, 1000.0, 50), num_modes=12)
    return time.perf_counter() - clock


def child(case: str, setting: str, quick: bool) -> None:
    """Body of one timing process: prints ``{"seconds": ...}``."""
    from threadpoolctl import threadpool_limits

    if setting.endswith("-1"):
        with threadpool_limits(limits=1, user_api="blas"):
            seconds = run_case(case, quick)
    else:
        seconds = run_case(case, quick)
    print(json.dumps({"seconds": seconds}))


def clean_env(setting: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARS}
    env.pop("ROTORSIM_BLAS_CAP", None)
    if setting.endswith("-old"):
        env["ROTORSIM_BLAS_CAP"] = "off"
    return env


def timed(case: str, setting: str, quick: bool, neighbour: str = "blas") -> float:
    """Run one setting in a fresh process, with a busy neighbour when ``loaded``:
    ``blas`` uses the default BLAS threads (every core), ``single`` one thread (one core)."""
    env = clean_env(setting)
    busy = None
    if setting.startswith("loaded"):
        busy_env = clean_env("alone")
        if neighbour == "single":
            busy_env["OPENBLAS_NUM_THREADS"] = busy_env["OMP_NUM_THREADS"] = "1"
        busy = subprocess.Popen([sys.executable, "-c", BUSY], env=busy_env)
        time.sleep(1.0)
    try:
        cmd = [sys.executable, __file__, "--child", case, setting] + (["--quick"] if quick
                                                                     else [])
        out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True,
                             cwd=ROOT)
    finally:
        if busy is not None:
            busy.kill()
            busy.wait()
    return float(json.loads(out.stdout.strip().splitlines()[-1])["seconds"])


def cap_overhead(samples: int = 200) -> float:
    """Mean cost [s] of entering and leaving the outermost cap (once per analysis)."""
    sys.path.insert(0, str(ROOT))
    import rotorsim  # noqa: F401  (loads numpy's and scipy's BLAS)
    from rotorsim.solvers.threads import one_blas_thread

    with one_blas_thread():
        pass
    clock = time.perf_counter()
    for _ in range(samples):
        with one_blas_thread():
            pass
    return (time.perf_counter() - clock) / samples


def report(case: str, times: dict[str, float]) -> dict[str, Any]:
    ref = times["alone-1"]
    ratios = {s: times[s] / ref for s in SETTINGS}
    print(f"\n== {case} ==")
    for s in SETTINGS:
        print(f"  {s:<11} {times[s]:8.2f} s   x{ratios[s]:6.2f} of alone-1")
    met = ratios["loaded-new"] <= GOAL
    print(f"  next to a busy process: caps off x{ratios['loaded-old']:.2f}, caps on "
          f"x{ratios['loaded-new']:.2f} (goal <= {GOAL:g}: {'met' if met else 'NOT met'}); "
          f"one thread throughout x{ratios['loaded-1']:.2f}")
    return {"times": times, "ratios": ratios, "goal_met": met}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true",
                        help="first 0.05 s of the run-up instead of 0.5 s")
    parser.add_argument("--cases", nargs="+", default=["runup", "campbell"],
                        choices=["runup", "campbell"])
    parser.add_argument("--child", nargs=2, metavar=("CASE", "SETTING"),
                        help=argparse.SUPPRESS)
    parser.add_argument("--neighbour", choices=["blas", "single"], default="blas",
                        help="busy neighbour: a matmul loop on the default BLAS threads "
                             "(every core) or on one thread (one core)")
    parser.add_argument("--json", type=Path, help="write the results to this file")
    args = parser.parse_args(argv)
    if args.child:
        child(args.child[0], args.child[1], args.quick)
        return 0
    preset = [v for v in THREAD_VARS if v in os.environ]
    if preset:
        print(f"note: {', '.join(preset)} set here; removed for the timed processes")
    print(f"neighbour: {args.neighbour}; cpus {os.cpu_count()}, load average "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print(f"cost of entering + leaving the outermost cap: {cap_overhead() * 1e3:.3f} ms "
          "(once per analysis)", flush=True)
    results = {}
    for case in args.cases:
        times = {}
        for setting in SETTINGS:
            times[setting] = timed(case, setting, args.quick, args.neighbour)
            print(f"  {case} {setting}: {times[setting]:.2f} s", flush=True)
        results[case] = report(case, times)
    if args.json is not None:
        args.json.write_text(json.dumps(results, indent=2))
    return 0 if all(r["goal_met"] for r in results.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
