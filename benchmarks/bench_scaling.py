"""Scaling of rotorsim: assembly cost against element count, and modal analysis of a 10k-DOF rotor.

Usage::

    .venv/bin/python benchmarks/bench_scaling.py [--sizes 100 1000 10000 30000] [--json out.json]

Targets (the issue): assembly time per element roughly constant (log-log slope near 1) and the
lowest 20 modes of a 10,000-DOF rotor in under 5 s. The rotor is the benchmark rotor of
``bench_model.py`` meshed finer; the Rotor objects are built before the clock starts.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

# Single-threaded BLAS unless the caller chose otherwise: on a shared 2-core machine,
# multi-threaded OpenBLAS makes both codes up to 20x slower whenever another process
# runs (see docs/benchmarks.md). Must be set before numpy is imported.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_model import benchmark_description, build_rotorsim

MODAL_TARGET_S = 5.0
"""Wall-time limit for the lowest 20 modes of a 10,000-DOF rotor (the issue)."""


def _median_time(fn, repeat: int) -> tuple[float, Any]:
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def assembly_scaling(sizes: tuple[int, ...], repeat: int = 3) -> dict[str, Any]:
    """Median ``assemble`` time for each element count and the fitted log-log slope.

    Returns
    -------
    dict
        ``rows`` (elements, dofs, nnz, build_s, assemble_s, us_per_element) and ``slope``
        of ``log(assemble_s)`` against ``log(elements)`` (1 = linear).
    """
    from rotorsim.assembly.system import assemble

    assemble(build_rotorsim(benchmark_description(20)))  # warm-up (imports, caches)
    rows = []
    for n in sizes:
        t0 = time.perf_counter()
        rotor = build_rotorsim(benchmark_description(n))
        build_s = time.perf_counter() - t0
        t_asm, system = _median_time(lambda r=rotor: assemble(r), repeat)
        rows.append({"elements": n, "dofs": system.n_free, "nnz": system.pattern.nnz,
                     "build_s": build_s, "assemble_s": t_asm,
                     "us_per_element": 1e6 * t_asm / n})
    n_el = np.array([r["elements"] for r in rows], dtype=float)
    t = np.array([r["assemble_s"] for r in rows])
    slope = float(np.polyfit(np.log(n_el), np.log(t), 1)[0]) if len(rows) > 1 else float("nan")
    return {"rows": rows, "slope": slope}


def modal_10k(num_modes: int = 20, speed: float = 500.0, repeat: int = 3) -> dict[str, Any]:
    """Time the lowest ``num_modes`` modes of the benchmark rotor with about 10,000 DOFs."""
    from rotorsim.analyses.linear.modal import modal
    from rotorsim.assembly.system import assemble

    n_elements = 1666  # 1667 nodes x 6 = 10,002 DOFs
    rotor = build_rotorsim(benchmark_description(n_elements))
    modal(build_rotorsim(benchmark_description(20)), speed, 4)  # warm-up
    t_full, res = _median_time(lambda: modal(rotor, speed, num_modes), repeat)
    system = assemble(rotor)
    t_solve, _ = _median_time(lambda: modal(system, speed, num_modes), repeat)
    return {
        "elements": n_elements, "dofs": system.n_free, "num_modes": num_modes,
        "speed": speed, "time_s": t_full, "time_without_assembly_s": t_solve,
        "target_s": MODAL_TARGET_S, "meets_target": bool(t_full < MODAL_TARGET_S),
        "wd_lowest": res.wd[:6].tolist(), "rigid_body_modes": res.rigid_body_modes,
        "stats": res.stats,
    }


def format_report(rep: dict[str, Any]) -> str:
    lines = ["Assembly (assemble(rotor), median of repeats):",
             f"{'elements':>9} {'DOFs':>7} {'nnz':>9} {'assemble [s]':>13} "
             f"{'per element [us]':>17}"]
    for r in rep["assembly"]["rows"]:
        lines.append(f"{r['elements']:>9} {r['dofs']:>7} {r['nnz']:>9} "
                     f"{r['assemble_s']:>13.4f} {r['us_per_element']:>17.2f}")
    lines.append(f"log-log slope of assembly time vs elements: {rep['assembly']['slope']:.3f}")
    m = rep["modal"]
    ok = "yes" if m["meets_target"] else "NO"
    lines.append(f"Modal, {m['dofs']} DOFs, lowest {m['num_modes']} modes at "
                 f"{m['speed']:g} rad/s: {m['time_s']:.3f} s with assembly, "
                 f"{m['time_without_assembly_s']:.3f} s on the assembled system "
                 f"[< {m['target_s']:g} s: {ok}]")
    lines.append("  lowest wd [rad/s]: " + ", ".join(f"{w:.2f}" for w in m["wd_lowest"]))
    return "\n".join(lines)


def run(sizes: tuple[int, ...] = (100, 1000, 10000, 30000), repeat: int = 3) -> dict[str, Any]:
    return {"assembly": assembly_scaling(sizes, repeat), "modal": modal_10k(repeat=repeat)}


def main(argv: list[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[100, 1000, 10000, 30000])
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--json", type=Path)
    args = p.parse_args(argv)
    rep = run(tuple(args.sizes), args.repeat)
    print(format_report(rep))
    if args.json:
        args.json.write_text(json.dumps(rep, indent=1))
    return rep


if __name__ == "__main__":
    main()
