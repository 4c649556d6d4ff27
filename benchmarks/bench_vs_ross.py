"""rotorsim against ROSS on the same rotor, in the same run: speed ratios and result agreement.

ROSS is never imported here: ``ross_side.py`` runs in the ROSS virtualenv (``$ROSS_VENV``, default
``.venv-ross`` in the repository; ``benchmarks/setup_ross_env.sh`` creates it) and exchanges JSON.

Usage::

    .venv/bin/python benchmarks/bench_vs_ross.py [--elements 100] [--profile] [--json out.json]

Checks (issue targets): Campbell over 50 speeds and unbalance response over 500 speeds at least
20x faster than ROSS on the 100-element rotor, with the global matrices, natural frequencies and
unbalance amplitudes agreeing between the two codes.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import json
import os
import pstats
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

# Single-threaded BLAS unless the caller chose otherwise: on a shared 2-core machine,
# multi-threaded OpenBLAS makes both codes up to 20x slower whenever another process
# runs (see docs/benchmarks.md). Must be set before numpy is imported.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_model import benchmark_description, build_rotorsim, unbalance_list

HERE = Path(__file__).resolve().parent
TARGET_RATIO = 20.0
"""Required speed-up over ROSS for Campbell and unbalance response (the issue)."""


# ----------------------------------------------------------------------------- ROSS process
def ross_python() -> Path | None:
    """Python of the ROSS virtualenv (``$ROSS_VENV`` or ``<repo>/.venv-ross``), if present."""
    venv = Path(os.environ.get("ROSS_VENV", HERE.parent / ".venv-ross"))
    py = venv / "bin" / "python"
    return py if py.exists() else None


def setup_hint() -> str:
    return ("ROSS virtualenv not found: run `bash benchmarks/setup_ross_env.sh` (creates "
            ".venv-ross) or set ROSS_VENV to a virtualenv with `ross-rotordynamics`.")


def run_ross(request: dict[str, Any], timeout: float = 3600.0) -> dict[str, Any]:
    """Run ``ross_side.py`` with ``request`` in the ROSS virtualenv; returns its JSON result."""
    py = ross_python()
    if py is None:
        raise FileNotFoundError(setup_hint())
    with tempfile.TemporaryDirectory() as tmp:
        req, res = Path(tmp) / "request.json", Path(tmp) / "result.json"
        req.write_text(json.dumps(request))
        proc = subprocess.run([str(py), str(HERE / "ross_side.py"), str(req), str(res)],
                              capture_output=True, text=True, timeout=timeout, check=False)
        if proc.returncode != 0 or not res.exists():
            raise RuntimeError(f"ross_side.py failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
        return json.loads(res.read_text())


# ----------------------------------------------------------------------------- rotorsim side
def rotorsim_api() -> dict[str, Any]:
    """The rotorsim analysis functions, or the reason each one is unavailable."""
    api: dict[str, Any] = {}
    from rotorsim.analyses.linear.modal import modal

    api["modal"] = modal
    try:
        from rotorsim.analyses.linear.campbell import campbell

        api["campbell"] = campbell
    except ImportError as exc:
        api["campbell"] = f"unavailable: {exc}"
    try:
        from rotorsim.analyses.linear.frequency_response import unbalance_response

        api["unbalance"] = unbalance_response
    except ImportError as exc:
        api["unbalance"] = f"unavailable: {exc}"
    return api


def timed(fn, *args, repeat: int = 3, **kwargs) -> tuple[dict[str, float], Any]:
    """Median wall and process-CPU time [s] of ``repeat`` calls, and the last result."""
    wall, cpu, out = [], [], None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn(*args, **kwargs)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return {"time_s": float(np.median(wall)), "cpu_s": float(np.median(cpu))}, out


def rotorsim_runs(desc, cfg, api, repeat: int) -> dict[str, Any]:
    """Time rotorsim's modal, Campbell and unbalance response on a Rotor (assembly included)."""
    warm = benchmark_description(20)
    rotor_w = build_rotorsim(warm)
    rotor = build_rotorsim(desc)
    out: dict[str, Any] = {}
    api["modal"](rotor_w, 10.0, 4)
    t, res = timed(api["modal"], rotor, cfg["modal_speed"], cfg["num_modes"], repeat=repeat)
    out["modal"] = {**t, "wd": res.wd.tolist(), "log_dec": res.log_dec.tolist()}
    if callable(api["campbell"]):
        api["campbell"](rotor_w, np.array([0.0, 10.0]), num_modes=4)
        t, res = timed(api["campbell"], rotor, cfg["campbell_speeds"],
                       num_modes=cfg["num_modes"], repeat=repeat)
        out["campbell"] = {**t, "wd": np.asarray(res.wd).tolist(),
                           "log_dec": np.asarray(res.log_dec).tolist()}
    if callable(api["unbalance"]):
        api["unbalance"](rotor_w, np.array([10.0, 20.0]), unbalance=unbalance_list(warm))
        t, res = timed(api["unbalance"], rotor, cfg["unbalance_speeds"],
                       unbalance=unbalance_list(desc), repeat=repeat)
        resp = {f"{n}:{d}": np.asarray(res.complex(n, d)) for n in cfg["nodes_out"]
                for d in ("ux", "uy")}
        out["unbalance"] = {**t, "re": {k: v.real.tolist() for k, v in resp.items()},
                            "im": {k: v.imag.tolist() for k, v in resp.items()}}
    return out


def slower_of(before: dict[str, Any], after: dict[str, Any]) -> dict[str, Any]:
    """Per analysis, the larger of two rotorsim timings (taken before and after ROSS ran)."""
    out = {}
    for kind, row in after.items():
        out[kind] = {**row, "time_s": max(row["time_s"], before[kind]["time_s"]),
                     "cpu_s": max(row["cpu_s"], before[kind]["cpu_s"]),
                     "time_before_after_s": [before[kind]["time_s"], row["time_s"]]}
    return out


# ----------------------------------------------------------------------------- comparisons
def compare_matrices(desc, npz_path: str, speed: float) -> dict[str, float]:
    """Max |rotorsim - ROSS| / max |ROSS| of the global M, K, C, G (all DOFs, same order)."""
    from rotorsim.assembly.system import assemble

    mats = assemble(build_rotorsim(desc)).matrices(speed)
    ross = np.load(npz_path)
    return {k: float(np.abs(getattr(mats, k).toarray() - ross[k]).max()
                     / max(np.abs(ross[k]).max(), 1e-300)) for k in "MKCG"}


def compare_frequencies(ours, theirs, n_compare: int) -> dict[str, float]:
    """Relative difference of the ``n_compare`` lowest damped frequencies, sorted per speed."""
    a = np.sort(np.atleast_2d(ours), axis=1)[:, :n_compare]
    b = np.sort(np.atleast_2d(theirs), axis=1)[:, :n_compare]
    rel = np.abs(a - b) / np.abs(b)
    return {"max_rel": float(rel.max()), "median_rel": float(np.median(rel))}


def compare_log_dec(ours_wd, ours_ld, ross_wd, ross_ld, n_compare: int) -> float:
    """Max |log dec difference| of modes paired by sorted damped frequency."""
    diffs = []
    for wa, la, wb, lb in zip(np.atleast_2d(ours_wd), np.atleast_2d(ours_ld),
                              np.atleast_2d(ross_wd), np.atleast_2d(ross_ld), strict=True):
        ia, ib = np.argsort(wa)[:n_compare], np.argsort(wb)[:n_compare]
        diffs.append(np.abs(np.asarray(la)[ia] - np.asarray(lb)[ib]))
    return float(np.max(diffs))


def compare_unbalance(ours: dict[str, Any], ross: dict[str, Any]) -> dict[str, float]:
    """Response differences at the output DOFs over all speeds.

    ``max_rel_to_peak``: max |(|a| - |b|)| / max |b| of the amplitudes; ``max_rel_pointwise``:
    the same relative to |b| at each speed (speeds with |b| > 1e-3 max |b|);
    ``max_complex_rel``: max |a - b| / max |b| of the complex amplitudes (phase included).
    """
    resp = np.asarray(ross["re"]) + 1j * np.asarray(ross["im"])
    peak, point, cplx = 0.0, 0.0, 0.0
    for row, dof in enumerate(ross["dofs"]):
        node, local = divmod(dof, 6)
        key = f"{node}:{('ux', 'uy')[local]}"
        a = np.asarray(ours["re"][key]) + 1j * np.asarray(ours["im"][key])
        b = resp[row]
        damp = np.abs(np.abs(a) - np.abs(b))
        big = np.abs(b) > 1e-3 * np.abs(b).max()
        peak = max(peak, float(damp.max() / np.abs(b).max()))
        point = max(point, float((damp[big] / np.abs(b[big])).max()))
        cplx = max(cplx, float(np.abs(a - b).max() / np.abs(b).max()))
    return {"max_rel_to_peak": peak, "max_rel_pointwise": point, "max_complex_rel": cplx}


# ----------------------------------------------------------------------------- driver
def config(n_elements: int, n_campbell: int, n_unbalance: int, num_modes: int):
    desc = benchmark_description(n_elements)
    nodes_out = sorted({u["n"] for u in desc["unbalance"]} | {desc["bearings"][0]["n"]})
    return desc, {
        "num_modes": num_modes,
        "modal_speed": 500.0,
        "campbell_speeds": np.linspace(0.0, 1000.0, n_campbell),
        "unbalance_speeds": np.linspace(10.0, 1200.0, n_unbalance),
        "nodes_out": nodes_out,
    }


def ross_request(desc, cfg, npz: str, max_gb: float, repeat: int) -> dict[str, Any]:
    tasks: list[dict[str, Any]] = [
        {"kind": "build", "repeat": 3},
        {"kind": "matrices", "speed": cfg["modal_speed"], "npz": npz},
        {"kind": "modal", "speed": cfg["modal_speed"], "num_modes": cfg["num_modes"],
         "repeat": 3},
        {"kind": "campbell", "speeds": cfg["campbell_speeds"].tolist(),
         "num_modes": cfg["num_modes"], "repeat": repeat},
        {"kind": "unbalance", "speeds": cfg["unbalance_speeds"].tolist(),
         "nodes_out": cfg["nodes_out"], "max_bytes": max_gb * 1e9, "repeat": repeat},
    ]
    return {"description": desc, "warmup": benchmark_description(20), "tasks": tasks}


def run(n_elements: int = 100, n_campbell: int = 50, n_unbalance: int = 500,
        num_modes: int = 12, repeat: int = 3, max_gb: float = 4.0,
        ross_repeat: int = 1) -> dict[str, Any]:
    """Run both codes and compare; returns a JSON-able report (ROSS parts absent if no venv)."""
    desc, cfg = config(n_elements, n_campbell, n_unbalance, num_modes)
    api = rotorsim_api()
    report: dict[str, Any] = {
        "model": {"elements": n_elements, "dofs": desc["n_dof"], "disks": len(desc["disks"]),
                  "bearings": len(desc["bearings"]), "campbell_speeds": n_campbell,
                  "unbalance_speeds": n_unbalance, "num_modes": num_modes},
        "missing": {k: v for k, v in api.items() if not callable(v)},
        "load_before": os.getloadavg(),
        "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS", "default"),
        "rotorsim": rotorsim_runs(desc, cfg, api, repeat),
    }
    if ross_python() is None:
        report["ross_skipped"] = setup_hint()
        return report
    with tempfile.TemporaryDirectory() as tmp:
        npz = str(Path(tmp) / "ross_matrices.npz")
        ross = run_ross(ross_request(desc, cfg, npz, max_gb, ross_repeat))
        report["matrix_diff"] = compare_matrices(desc, npz, cfg["modal_speed"])
    report["load_after"] = os.getloadavg()
    # the machine's load may change while ROSS runs: keep rotorsim's slower timing
    report["rotorsim"] = slower_of(report["rotorsim"], rotorsim_runs(desc, cfg, api, repeat))
    report["ross_versions"] = ross["versions"]
    report["ross"] = {r["kind"]: r for r in ross["results"]}
    report["comparison"] = comparisons(report["rotorsim"], report["ross"], num_modes)
    return report


def comparisons(ours: dict[str, Any], ross: dict[str, Any], num_modes: int) -> dict[str, Any]:
    n_cmp = num_modes - 2  # the top of either list may hold a different mode near the cut
    out: dict[str, Any] = {}
    for kind in ("modal", "campbell", "unbalance"):
        if kind not in ours:
            continue
        row: dict[str, Any] = {"rotorsim_s": ours[kind]["time_s"],
                               "ross_s": ross[kind]["time_s"],
                               "speedup": ross[kind]["time_s"] / ours[kind]["time_s"],
                               "cpu_speedup": ross[kind]["cpu_s"] / ours[kind]["cpu_s"]}
        if kind == "unbalance":
            row.update(compare_unbalance(ours[kind], ross[kind]))
            row["ross_chunks"] = ross[kind]["chunks"]
        else:
            row.update(compare_frequencies(ours[kind]["wd"], ross[kind]["wd"], n_cmp))
            row["max_abs_log_dec_diff"] = compare_log_dec(
                ours[kind]["wd"], ours[kind]["log_dec"], ross[kind]["wd"],
                ross[kind]["log_dec"], n_cmp)
        if kind != "modal":
            row["target"] = TARGET_RATIO
            row["meets_target"] = bool(row["speedup"] >= TARGET_RATIO)
        out[kind] = row
    return out


def profile_rotorsim(n_elements: int = 100, top: int = 18) -> str:
    """cProfile summaries (cumulative time) of rotorsim's Campbell and unbalance response."""
    desc, cfg = config(n_elements, 50, 500, 12)
    api = rotorsim_api()
    rotor = build_rotorsim(desc)
    text = []
    calls = {"campbell": lambda: api["campbell"](rotor, cfg["campbell_speeds"], num_modes=12),
             "unbalance": lambda: api["unbalance"](rotor, cfg["unbalance_speeds"],
                                                   unbalance=unbalance_list(desc))}
    for name, call in calls.items():
        if not callable(api[name]):
            continue
        prof = cProfile.Profile()
        prof.runcall(call)
        buf = io.StringIO()
        pstats.Stats(prof, stream=buf).sort_stats("cumulative").print_stats(top)
        text.append(f"==== rotorsim {name} ====\n{buf.getvalue()}")
    return "\n".join(text)


def format_report(rep: dict[str, Any]) -> str:
    m = rep["model"]
    lines = [f"Model: {m['elements']} shaft elements, {m['dofs']} DOFs, {m['disks']} disks, "
             f"{m['bearings']} bearings; {m['num_modes']} modes"]
    for kind, why in rep["missing"].items():
        lines.append(f"rotorsim {kind}: {why}")
    if "ross_skipped" in rep:
        lines.append(rep["ross_skipped"])
        lines += [f"rotorsim {k}: {v['time_s']:.4f} s" for k, v in rep["rotorsim"].items()]
        return "\n".join(lines)
    lines.append(f"ROSS {rep['ross_versions']['ross']} (rotor build "
                 f"{rep['ross']['build']['time_s']:.3f} s, not counted); load average "
                 f"{rep['load_before'][0]:.2f} before, {rep['load_after'][0]:.2f} after; "
                 f"OPENBLAS_NUM_THREADS {rep['blas_threads']}")
    lines.append("global matrices, max|rotorsim - ROSS| / max|ROSS|: " + ", ".join(
        f"{k} {v:.1e}" for k, v in rep["matrix_diff"].items()))
    lines.append(f"{'analysis':<10} {'rotorsim [s]':>13} {'ROSS [s]':>10} {'speed-up':>9} "
                 f"{'CPU ratio':>9}  agreement")
    for kind, row in rep["comparison"].items():
        if kind == "unbalance":
            agree = (f"amplitude max rel diff {row['max_rel_to_peak']:.1e} of peak, "
                     f"{row['max_rel_pointwise']:.1e} pointwise, complex "
                     f"{row['max_complex_rel']:.1e}")
        else:
            agree = (f"wd max rel diff {row['max_rel']:.1e}, log dec max abs diff "
                     f"{row['max_abs_log_dec_diff']:.1e}")
        flag = "" if "target" not in row else (
            "  [>= 20x: yes]" if row["meets_target"] else "  [>= 20x: NO]")
        lines.append(f"{kind:<10} {row['rotorsim_s']:>13.4f} {row['ross_s']:>10.3f} "
                     f"{row['speedup']:>8.1f}x {row['cpu_speedup']:>8.1f}x  {agree}{flag}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--elements", type=int, default=100)
    p.add_argument("--campbell-speeds", type=int, default=50)
    p.add_argument("--unbalance-speeds", type=int, default=500)
    p.add_argument("--num-modes", type=int, default=12)
    p.add_argument("--repeat", type=int, default=3, help="rotorsim repetitions (median)")
    p.add_argument("--ross-repeat", type=int, default=1,
                   help="ROSS repetitions of Campbell and unbalance (median; modal uses 3)")
    p.add_argument("--ross-max-gb", type=float, default=4.0,
                   help="memory for ROSS's stored transfer matrices before chunking speeds")
    p.add_argument("--profile", action="store_true", help="cProfile rotorsim's analyses")
    p.add_argument("--json", type=Path, help="write the full report here")
    args = p.parse_args(argv)
    rep = run(args.elements, args.campbell_speeds, args.unbalance_speeds, args.num_modes,
              args.repeat, args.ross_max_gb, args.ross_repeat)
    print(format_report(rep))
    if args.profile:
        print(profile_rotorsim(args.elements))
    if args.json:
        args.json.write_text(json.dumps(rep, indent=1))
    return rep


if __name__ == "__main__":
    main()
