"""Run every rotorsim benchmark and print a summary table of times, ratios and targets.

Usage::

    .venv/bin/python benchmarks/run_all.py [--quick] [--profile] [--json report.json]
    ROSS_VENV=/path/to/venv .venv/bin/python benchmarks/run_all.py

Without a ROSS virtualenv (``$ROSS_VENV`` or ``.venv-ross``) the ROSS comparisons are skipped
with a note on how to set it up (``bash benchmarks/setup_ross_env.sh``); the rotorsim-only
benchmarks still run. ``--quick`` uses fewer speeds and smaller meshes (a smoke test, not the
issue's targets).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
from pathlib import Path
from typing import Any

# single-threaded BLAS by default, for this process and the ROSS subprocess (bench_vs_ross.py)
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_scaling
import bench_vs_ross

HERE = Path(__file__).resolve().parent
NONLINEAR: tuple[tuple[str, list[str], list[str]], ...] = (
    ("bench_bearings.py", [], []),
    ("bench_flexible_ring.py", [], ["--repeat", "1"]),
    ("bench_transient.py", [], ["--quick"]),
    ("bench_harmonic_balance.py", [], ["--repeat", "1"]),
    ("bench_periodic.py", [], ["--points", "30", "--subset", "1"]),
    ("bench_bearing_life.py", [], ["--repeat", "3", "--steps", "10000"]),
)
"""The nonlinear benchmarks (issues 4-7), run as scripts after the linear ones: (script,
full arguments, --quick arguments)."""


def machine() -> dict[str, Any]:
    import numpy
    import scipy

    import rotorsim

    return {"python": platform.python_version(), "numpy": numpy.__version__,
            "scipy": scipy.__version__, "rotorsim": rotorsim.__version__,
            "cpus": os.cpu_count(), "platform": platform.platform()}


def summary_rows(vs: dict[str, Any], sc: dict[str, Any]) -> list[tuple[str, ...]]:
    """Rows (benchmark, rotorsim, ROSS, wall ratio, CPU ratio, target, met) of the summary."""
    rows: list[tuple[str, ...]] = []
    m = vs["model"]
    labels = {"modal": f"modal, 1 speed, {m['num_modes']} modes",
              "campbell": f"campbell, {m['campbell_speeds']} speeds",
              "unbalance": f"unbalance, {m['unbalance_speeds']} speeds"}
    comp = vs.get("comparison", {})
    for kind, label in labels.items():
        label = f"{label} ({m['dofs']} DOF)"
        if kind in comp:
            c = comp[kind]
            target = ">= 20x" if "target" in c else "-"
            met = "-" if "target" not in c else ("yes" if c["meets_target"] else "NO")
            rows.append((label, f"{c['rotorsim_s']:.3f} s", f"{c['ross_s']:.2f} s",
                         f"{c['speedup']:.0f}x", f"{c['cpu_speedup']:.0f}x", target, met))
        elif kind in vs["rotorsim"]:
            rows.append((label, f"{vs['rotorsim'][kind]['time_s']:.3f} s", "skipped", "-",
                         "-", ">= 20x" if kind != "modal" else "-", "?"))
        else:
            rows.append((label, "missing", "-", "-", "-", "-", "?"))
    asm = sc["assembly"]
    per = [r["us_per_element"] for r in asm["rows"]]
    sizes = [r["elements"] for r in asm["rows"]]
    rows.append((f"assemble, {sizes[0]}..{sizes[-1]} elements",
                 f"{min(per):.0f}-{max(per):.0f} us/el", "-", f"slope {asm['slope']:.2f}", "-",
                 "slope < 1.2", "yes" if asm["slope"] < 1.2 else "NO"))
    mod = sc["modal"]
    rows.append((f"modal, {mod['dofs']} DOF, {mod['num_modes']} modes",
                 f"{mod['time_s']:.2f} s", "-", "-", "-", f"< {mod['target_s']:g} s",
                 "yes" if mod["meets_target"] else "NO"))
    return rows


def agreement_lines(vs: dict[str, Any]) -> list[str]:
    if "comparison" not in vs:
        return []
    lines = ["agreement with ROSS: global matrices max rel diff "
             + ", ".join(f"{k} {v:.1e}" for k, v in vs["matrix_diff"].items())]
    for kind, c in vs["comparison"].items():
        if "max_rel" in c:
            lines.append(f"  {kind}: damped frequencies max rel diff {c['max_rel']:.1e}")
        else:
            lines.append(f"  {kind}: amplitude max diff {c['max_rel_to_peak']:.1e} of peak")
    return lines


def format_table(rows: list[tuple[str, ...]]) -> str:
    header = ("benchmark", "rotorsim", "ROSS", "ratio", "CPU ratio", "target", "met")
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]
    fmt = "  ".join(f"{{:<{w}}}" for w in widths)
    return "\n".join([fmt.format(*header), fmt.format(*("-" * w for w in widths)),
                      *(fmt.format(*r) for r in rows)])


def main(argv: list[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--quick", action="store_true", help="small smoke-test sizes")
    p.add_argument("--ross-repeat", type=int, default=1,
                   help="ROSS repetitions of Campbell and unbalance (median)")
    p.add_argument("--profile", action="store_true", help="cProfile rotorsim's analyses")
    p.add_argument("--json", type=Path, help="write the full report here")
    args = p.parse_args(argv)
    info = machine()
    print("machine:", ", ".join(f"{k} {v}" for k, v in info.items()))
    print("OPENBLAS_NUM_THREADS:", os.environ.get("OPENBLAS_NUM_THREADS", "default"),
          "| load average:", " ".join(f"{x:.2f}" for x in os.getloadavg()))
    if bench_vs_ross.ross_python() is None:
        print(bench_vs_ross.setup_hint())
    if args.quick:
        vs = bench_vs_ross.run(n_elements=40, n_campbell=5, n_unbalance=20, repeat=1)
        sc = bench_scaling.run(sizes=(100, 1000, 3000), repeat=1)
    else:
        vs = bench_vs_ross.run(ross_repeat=args.ross_repeat)
        sc = bench_scaling.run()
    print("\n== rotorsim vs ROSS ==\n" + bench_vs_ross.format_report(vs))
    print("\n== scaling ==\n" + bench_scaling.format_report(sc))
    print("\n== summary ==\n" + format_table(summary_rows(vs, sc)))
    print("\n".join(agreement_lines(vs)))
    if args.profile:
        print(bench_vs_ross.profile_rotorsim())
    for script, full, quick in NONLINEAR:
        print(f"\n== {script} ==", flush=True)
        subprocess.run([sys.executable, str(HERE / script), *(quick if args.quick else full)],
                       check=True)
    report = {"machine": info, "vs_ross": vs, "scaling": sc}
    if args.json:
        args.json.write_text(json.dumps(report, indent=1))
    return report


if __name__ == "__main__":
    main()
