"""Campbell diagrams against ROSS on three 100-element rotors, and a 5,000-DOF two-spool machine
(issue 15, "Performance").

Usage::

    OPENBLAS_NUM_THREADS=1 ROSS_VENV=/tmp/rossenv313 .venv/bin/python \\
        benchmarks/bench_campbell_machines.py [--no-ross] [--json out.json]

1. For each rotor (the benchmark rotor of ``bench_model.py`` and the two of
   ``machine_models.py``) the speed range runs to 1.2 times its fourth synchronous critical
   speed (found once, untimed); 50 speeds, 12 modes. rotorsim's reduced Campbell (the
   default) and its full per-speed ARPACK one are timed, then ROSS's ``run_campbell`` in its
   own virtualenv (``ross_side.py``), then rotorsim again (the slower time is kept). Ratio
   target: ROSS / rotorsim >= 50. The frequencies of the three are compared.
2. The two-spool machine with 5,010 DOFs (``machine_models.two_spool_machine``): Campbell over
   50 speeds (< 10 s), unbalance response of both spools over 500 speeds (< 5 s), both
   checked against the full solvers; and ``assemble`` per element for the machine against
   one line of as many elements.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_model import benchmark_description, build_rotorsim
from bench_vs_ross import compare_frequencies, compare_log_dec, ross_python, run_ross
from machine_models import stepped_description, three_bearing_description, two_spool_machine

TARGET_RATIO = 50.0
N_SPEEDS, NUM_MODES = 50, 12


def timed(fn, *args, repeat: int = 3, **kwargs) -> tuple[float, Any]:
    """Median wall time [s] of ``repeat`` calls and the last result."""
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*args, **kwargs)
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def cpu_timed(fn, *args, repeat: int = 3, **kwargs) -> tuple[float, float, Any]:
    """Median wall and process-CPU time [s] of ``repeat`` calls, and the last result (CPU
    time is what a shared machine disturbs least: ROSS's side reports it too)."""
    wall, cpu, out = [], [], None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn(*args, **kwargs)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return float(np.median(wall)), float(np.median(cpu)), out


def speed_range(rotor) -> tuple[float, float]:
    """1.2 times the fourth forward/backward 1X critical speed [rad/s] (untimed probe)."""
    import rotorsim as rs

    stop = 1000.0
    for _ in range(6):
        c = rs.campbell(rotor, np.linspace(0.0, stop, 80), num_modes=NUM_MODES, method="full")
        crit = np.sort(c.critical_speeds(harmonic=1).speed)
        if crit.size >= 4:
            return float(crit[3]), 1.2 * float(crit[3])
        stop *= 2.0
    raise RuntimeError("fewer than four critical speeds found")


def compare_rotor(desc: dict[str, Any], use_ross: bool, repeat: int) -> dict[str, Any]:
    import rotorsim as rs

    rotor = build_rotorsim(desc)
    fourth, stop = speed_range(rotor)
    speeds = np.linspace(0.0, stop, N_SPEEDS)
    rs.campbell(rotor, speeds[:3], num_modes=4)  # warm-up (imports)
    t_red, c_red, red = cpu_timed(rs.campbell, rotor, speeds, num_modes=NUM_MODES,
                                  repeat=repeat)
    t_full, full = timed(rs.campbell, rotor, speeds, num_modes=NUM_MODES, method="full",
                         repeat=1)
    row: dict[str, Any] = {
        "rotor": desc["name"], "dofs": desc["n_dof"], "fourth_critical": fourth,
        "stop": stop, "reduced_s": t_red, "full_s": t_full, "load": os.getloadavg()[0],
        "reduced_stats": {k: red.stats[k] for k in ("basis_size", "refinements",
                                                     "full_solves", "max_residual")},
        "reduced_vs_full": {
            "wd_max_rel": float(np.nanmax(np.abs(red.wd - full.wd) / full.wd)),
            "log_dec_max_abs": float(np.nanmax(np.abs(red.log_dec - full.log_dec)))},
    }
    if use_ross:
        req = {"description": desc, "warmup": benchmark_description(20),
               "tasks": [{"kind": "campbell", "speeds": speeds.tolist(),
                          "num_modes": NUM_MODES, "repeat": 1}]}
        ross = run_ross(req)["results"][0]
        t_again, c_again, _ = cpu_timed(rs.campbell, rotor, speeds, num_modes=NUM_MODES,
                                        repeat=repeat)
        row["reduced_s_before_after"] = [t_red, t_again]
        row["reduced_s"] = t_red = max(t_red, t_again)
        row["reduced_cpu_s"] = c_red = max(c_red, c_again)
        row["ross_s"] = ross["time_s"]
        row["ross_cpu_s"] = ross["cpu_s"]
        row["ratio"] = ross["time_s"] / t_red
        row["ratio_cpu"] = ross["cpu_s"] / c_red
        row["ratio_full"] = ross["time_s"] / t_full
        row["vs_ross"] = {**compare_frequencies(red.wd, ross["wd"], NUM_MODES - 2),
                          "log_dec_max_abs": compare_log_dec(red.wd, red.log_dec, ross["wd"],
                                                             ross["log_dec"], NUM_MODES - 2)}
        row["load_after"] = os.getloadavg()[0]
    return row


def machine_runs(repeat: int) -> dict[str, Any]:
    import rotorsim as rs
    import rotorsim.analyses.linear.frequency_response as fr

    rotor, unbalance = two_spool_machine()
    n_el = sum(len(line.elements) for line in rotor.layout.lines)
    one_line = build_one_line(n_el)
    machine_t, line_t = [], []
    for _ in range(7):  # interleaved, so both see the same machine load
        machine_t.append(timed(rs.assemble, rotor, repeat=1)[0])
        line_t.append(timed(rs.assemble, one_line, repeat=1)[0])
    t_asm, t_one = float(np.median(machine_t)), float(np.median(line_t))
    system = rs.assemble(rotor)
    speeds = np.linspace(0.0, 1500.0, N_SPEEDS)
    t_c, red = timed(rs.campbell, system, speeds, num_modes=NUM_MODES, repeat=1)
    t_cf, full = timed(rs.campbell, system, speeds, num_modes=NUM_MODES, method="full",
                       repeat=1)
    unb_speeds = np.linspace(10.0, 1500.0, 500)
    t_u, u = timed(rs.unbalance_response, system, unb_speeds, unbalance, repeat=1)
    saved = fr.REDUCED_MIN_DOFS
    fr.REDUCED_MIN_DOFS = 10**9  # the direct solve at every point, for the check
    try:
        t_ud, d = timed(rs.unbalance_response, system, unb_speeds, unbalance, repeat=1)
    finally:
        fr.REDUCED_MIN_DOFS = saved
    peak = np.abs(d.response).max(axis=(0, 1))
    ok = np.isfinite(full.wd) & (full.wd > 0)
    return {
        "dofs": system.n_free, "elements": n_el, "lines": len(rotor.layout.lines),
        "assemble_s": t_asm, "assemble_us_per_element": 1e6 * t_asm / n_el,
        "one_line_us_per_element": 1e6 * t_one / n_el,
        "campbell_s": t_c, "campbell_full_s": t_cf, "campbell_stats": {
            k: red.stats[k] for k in ("basis_size", "refinements", "full_solves",
                                      "max_residual")},
        "campbell_wd_max_rel": float(np.max(np.abs(red.wd - full.wd)[ok] / full.wd[ok])),
        "campbell_log_dec_max_abs": float(np.nanmax(np.abs(red.log_dec - full.log_dec))),
        "campbell_sorted_wn_max_rel": float(np.nanmax(
            np.abs(np.sort(red.wn, axis=1) - np.sort(full.wn, axis=1))
            / np.sort(full.wn, axis=1))),
        "unbalance_s": t_u, "unbalance_direct_s": t_ud,
        "unbalance_stats": {k: u.stats[k] for k in ("basis_size", "direct_solves",
                                                    "max_residual")},
        "unbalance_max_err_of_peak": float(
            (np.abs(u.response - d.response).max(axis=(0, 1)) / peak).max()),
        "load": os.getloadavg()[0],
    }


def build_one_line(n_elements: int):
    """One line of ``n_elements`` shaft elements with the machine's kind of extras: a disk and
    two bearings to pedestal point masses on springs to ground (whose rotations, unconnected,
    make ``assemble`` run a second pass on every model that has them)."""
    import rotorsim as rs

    steel = rs.Material(name="steel", E=205e9, G_s=79e9, rho=7850)
    shaft = [rs.ShaftElement(L=1.6 / n_elements, idl=0.04, odl=0.06, material=steel)
             for _ in range(n_elements)]
    ped = n_elements + 1
    B = rs.BearingElement
    return rs.Rotor(shaft, [rs.DiskElement(n=n_elements // 2, m=10.0, Id=0.1, Ip=0.2)],
                    [B(n=0, n_link=ped, kxx=1e8, kzz=1e8, tag="a"),
                     B(n=n_elements, n_link=ped + 1, kxx=1e8, kzz=1e8, tag="b"),
                     B(n=ped, kxx=5e8, kzz=5e8, tag="c"), B(n=ped + 1, kxx=5e8, kzz=5e8,
                                                             tag="d")],
                    [rs.PointMass(n=ped, m=60.0), rs.PointMass(n=ped + 1, m=60.0)])


def format_report(rep: dict[str, Any]) -> str:
    lines = [f"OPENBLAS_NUM_THREADS {os.environ.get('OPENBLAS_NUM_THREADS')}; load average "
             f"{rep['load_before']:.2f} at start"]
    lines.append(f"{'rotor':<18} {'DOF':>4} {'4th crit':>9} {'range':>7} {'reduced':>8} "
                 f"{'full':>7} {'ROSS':>7} {'ratio':>6} {'full':>6} {'CPU ratio':>14}  "
                 "agreement")
    for r in rep["rotors"]:
        ross = (f"{r['ross_s']:7.2f} {r['ratio']:5.1f}x {r['ratio_full']:5.1f}x "
                f"{r['ratio_cpu']:5.1f}x ({r['reduced_cpu_s']:.3f} s)") \
            if "ross_s" in r else f"{'-':>7} {'-':>6} {'-':>6} {'-':>14}"
        agree = (f"reduced vs full: wd {r['reduced_vs_full']['wd_max_rel']:.1e}, log dec "
                 f"{r['reduced_vs_full']['log_dec_max_abs']:.1e}")
        if "vs_ross" in r:
            agree += (f"; vs ROSS: wd {r['vs_ross']['max_rel']:.1e}, log dec "
                      f"{r['vs_ross']['log_dec_max_abs']:.1e}")
        lines.append(f"{r['rotor']:<18} {r['dofs']:>4} {r['fourth_critical']:9.0f} "
                     f"{r['stop']:7.0f} {r['reduced_s']:8.3f} {r['full_s']:7.3f} {ross}  "
                     f"{agree}  [basis {r['reduced_stats']['basis_size']:.0f}, refinements "
                     f"{r['reduced_stats']['refinements']:.0f}, load {r['load']:.1f}]")
    m = rep.get("machine")
    if m:
        lines += [
            f"two-spool machine: {m['dofs']} DOFs, {m['lines']} lines, {m['elements']} "
            f"elements; load {m['load']:.1f}",
            f"  assemble: {m['assemble_s']:.3f} s, {m['assemble_us_per_element']:.1f} us per "
            f"element (one line of as many elements: {m['one_line_us_per_element']:.1f}; "
            f"ratio {m['assemble_us_per_element'] / m['one_line_us_per_element']:.2f})",
            f"  Campbell 50 speeds, 12 modes: {m['campbell_s']:.2f} s (full ARPACK "
            f"{m['campbell_full_s']:.2f} s) [< 10 s: {'yes' if m['campbell_s'] < 10 else 'NO'}]"
            f"; reduced vs full: wd max rel diff {m['campbell_wd_max_rel']:.1e} (tracks), "
            f"{m['campbell_sorted_wn_max_rel']:.1e} (wn sorted per speed), log dec "
            f"{m['campbell_log_dec_max_abs']:.1e}",
            f"  unbalance 500 speeds, 2 spools: {m['unbalance_s']:.2f} s (direct "
            f"{m['unbalance_direct_s']:.2f} s) [< 5 s: {'yes' if m['unbalance_s'] < 5 else 'NO'}]"
            f"; max error {m['unbalance_max_err_of_peak']:.1e} of the peak"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--no-ross", action="store_true")
    p.add_argument("--no-machine", action="store_true")
    p.add_argument("--only-machine", action="store_true")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--json", type=Path)
    args = p.parse_args(argv)
    use_ross = not args.no_ross and ross_python() is not None
    rep: dict[str, Any] = {"load_before": os.getloadavg()[0], "rotors": []}
    for desc in () if args.only_machine else (
            benchmark_description(100), stepped_description(), three_bearing_description()):
        rep["rotors"].append(compare_rotor(desc, use_ross, args.repeat))
    if not args.no_machine:
        rep["machine"] = machine_runs(args.repeat)
    print(format_report(rep))
    if args.json:
        args.json.write_text(json.dumps(rep, indent=1))
    return rep


if __name__ == "__main__":
    main()
