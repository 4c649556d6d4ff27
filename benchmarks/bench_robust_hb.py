"""Issue 16 performance: the clearance rotor's branch, and the per-point cost of a smooth
branch before and after (one core).

1. ``models/clearance_rotor.toml`` from 100 to 400 rad/s at ``H = 8`` with Floquet
   stability and confirmed bifurcations: wall time (target < 30 s), points, the split into
   continuation, Floquet and event confirmation/location (target: events under a quarter
   of the branch time), and the counts of candidates, confirmed events and unresolved ones.
2. The smooth branch of ``benchmarks/bench_periodic.py`` (102 DOFs, two ball bearings,
   ``H = 10``, 200 -> 3000 rad/s, no stability): wall time per point here and, with
   ``--baseline REV``, at git revision ``REV`` (checked out in a temporary worktree and run
   in a subprocess by this same script). The ratio comes from one run of both.

Run: ``.venv/bin/python benchmarks/bench_robust_hb.py [--baseline cfb4ab6] [--skip-clearance]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")   # one core, as the targets say

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

SMOOTH_POINTS = 150


def clearance_branch() -> dict[str, float]:
    """Time and counts of the clearance rotor's branch (item 1)."""
    import rotorsim as rs

    model = rs.load_model(ROOT / "models" / "clearance_rotor.toml")
    clock = time.perf_counter()
    res = rs.periodic(model, start=100.0, stop=400.0, harmonics=8,
                      unbalance=[(10, 1e-4, 0.0)], nodes=[10])
    wall = time.perf_counter() - clock
    assert isinstance(res, rs.PeriodicResult)      # fixed cages: a periodic problem
    s = res.stats
    return {"wall_time": wall, "points": len(res), "reached": float(res.parameter[-1]),
            "floquet_time": s["floquet_time"], "event_time": s["bifurcation_time"],
            "candidates": s["candidates"], "confirmed": s["confirmed"],
            "unresolved": len(res.unresolved)}


def smooth_per_point() -> dict[str, float]:
    """Per-point wall time of the smooth 102-DOF branch (item 2), in this checkout."""
    from bench_periodic import UNBALANCE, benchmark_rotor  # this folder (sys.path[0])

    import rotorsim as rs

    rotor = benchmark_rotor()
    opts = rs.ContinuationOptions(max_points=SMOOTH_POINTS, max_step=0.05, tol=1e-8)
    rs.periodic(rotor, start=200.0, stop=210.0, harmonics=10, unbalance=UNBALANCE,
                continuation=rs.ContinuationOptions(max_points=3), stability=None,
                nodes=[5])                                  # warm-up: imports, caches
    clock = time.perf_counter()
    res = rs.periodic(rotor, start=200.0, stop=3000.0, harmonics=10, unbalance=UNBALANCE,
                      continuation=opts, stability=None, nodes=[5, 11])
    wall = time.perf_counter() - clock
    return {"points": len(res), "wall_time": wall, "per_point": wall / len(res),
            "evaluations_per_point": res.stats["residual_evaluations"] / len(res)}


def baseline(rev: str) -> dict[str, float]:
    """Item 2 at git revision ``rev``: a temporary worktree, this script in a subprocess."""
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp) / "base"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(tree),
                        rev], check=True, capture_output=True)
        try:
            script = tree / "benchmarks" / "_bench_robust_smooth.py"
            script.write_text(Path(__file__).read_text())
            env = {**os.environ, "PYTHONPATH": str(tree)}
            out = subprocess.run([sys.executable, str(script), "--smooth-json"], env=env,
                                 cwd=tree, check=True, capture_output=True, text=True)
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force",
                            str(tree)], check=False, capture_output=True)
    return dict(json.loads(out.stdout.strip().splitlines()[-1]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--baseline", help="git revision to compare the smooth branch with")
    parser.add_argument("--skip-clearance", action="store_true")
    parser.add_argument("--smooth-json", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.smooth_json:
        print(json.dumps(smooth_per_point()))
        return
    if not args.skip_clearance:
        c = clearance_branch()
        share = c["event_time"] / c["wall_time"]
        print(f"clearance rotor 100 -> {c['reached']:g} rad/s: {c['points']} points in "
              f"{c['wall_time']:.1f} s (target < 30 s: {'yes' if c['wall_time'] < 30 else 'no'});"
              f" Floquet {c['floquet_time']:.1f} s, events {c['event_time']:.1f} s "
              f"({share:.0%} of the branch, target < 25 %)")
        print(f"  candidates {c['candidates']:.0f}, confirmed {c['confirmed']:.0f}, "
              f"unresolved records {c['unresolved']}")
    here = smooth_per_point()
    print(f"smooth branch here: {here['points']} points, {here['per_point'] * 1e3:.1f} ms "
          f"per point ({here['evaluations_per_point']:.2f} residual evaluations per point)")
    if args.baseline:
        base = baseline(args.baseline)
        print(f"smooth branch at {args.baseline}: {base['points']} points, "
              f"{base['per_point'] * 1e3:.1f} ms per point "
              f"({base['evaluations_per_point']:.2f} evaluations per point)")
        print(f"per-point cost here / at {args.baseline}: "
              f"{here['per_point'] / base['per_point']:.2f}")


if __name__ == "__main__":
    main()
