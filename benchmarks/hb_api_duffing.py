"""Per-point cost of ``rs.hb.frequency_response`` on NLvib's examples 01-03, optionally
against NLvib itself (GNU Octave) in the same run.

For each example (the settings of ``examples/nlvib_examples.py``: NLvib's ``H`` and
``N``) the branch is traced without stability (NLvib's ``solve_and_continue`` computes
none) and with Floquet stability and bifurcation location; the time per branch point is
the wall time over the points. With ``--nlvib DIR`` (a checkout of
github.com/maltekrack/NLvib) and ``octave`` on the PATH, NLvib's HB continuation of the
same three systems runs in Octave (its analytic Jacobian, ``HB_residual``; the step sizes
of its example scripts), timed with tic/toc around ``solve_and_continue`` alone, and the
ratios are printed. Octave 7 lacks ``optimset(@fsolve)``: a temporary copy of NLvib's
``SRC`` uses ``optimset('fsolve')`` instead. Octave is never needed by the tests.

Run: ``.venv/bin/python benchmarks/hb_api_duffing.py [--nlvib DIR] [--repeat N]``.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402
from examples import nlvib_examples as ex  # noqa: E402

CASES: dict[str, tuple[Callable[[], rs.hb.System], dict[str, Any]]] = {
    "01 Duffing (H=7, N=29)": (
        lambda: rs.hb.System(1.0, 1.0, 0.05, forcing=[0.18],
                             elements=[rs.hb.CubicSpring(0, k3=0.1)]),
        dict(start=0.5, stop=1.6, harmonics=7, samples=29)),
    "02 2-DOF cubic (H=7, N=29)": (
        lambda: _chain_system(ex.chain([1.0, 0.05], [0.002, 0.013, 0.0], [1.0, 0.0453, 0.0]),
                              [0.11, 0.0], [rs.hb.CubicSpring(0, k3=1.0),
                                            rs.hb.CubicSpring(0, k3=0.0042, other=1)]),
        dict(start=0.8, stop=1.4, harmonics=7, samples=29)),
    "03 unilateral contact (H=21, N=1024)": (
        lambda: _chain_system(ex.chain([1.0, 1.0], [0.0, 0.03, 0.03], [0.0, 1.0, 1.0]),
                              [0.0, 0.1], [rs.hb.UnilateralSpring(0, stiffness=100.0,
                                                                  gap=1.0)]),
        dict(start=0.8, stop=0.5, harmonics=21, samples=1024)),
}

OCTAVE_SETUP = {
    "01 Duffing (H=7, N=29)": (
        "ne = {struct('type','cubicSpring','stiffness',0.1,'force_direction',1)};"
        "sys = SingleMassOscillator(1,0.05,1,ne,0.18); H = 7; N = 29; Om_s = 0.5;"
        "Om_e = 1.6; ds = 0.01; Sopt = struct();"),
    "02 2-DOF cubic (H=7, N=29)": (
        "ne{1} = struct('type','cubicSpring','stiffness',1,'force_direction',[1;0]);"
        "ne{2} = struct('type','cubicSpring','stiffness',.0042,'force_direction',[1;-1]);"
        "sys = ChainOfOscillators([1 .05],[.002 .013 0],[1 .0453 0],ne,[.11;0]); H = 7;"
        "N = 29; Om_s = 0.8; Om_e = 1.4; ds = 0.02; Sopt = struct('Dscale',"
        "[ones(2*(2*H+1),1);Om_s]);"),
    "03 unilateral contact (H=21, N=1024)": (
        "ne = struct('type','unilateralSpring','stiffness',1e2,'gap',1,"
        "'force_direction',[1;0]); sys = ChainOfOscillators([1 1],.03*[0 1 1],[0 1 1],"
        "ne,[0;.1]); H = 21; N = 2^10; Om_s = 0.8; Om_e = 0.5; ds = 0.0085;"
        "Sopt = struct('Dscale',[ones(2*(2*H+1),1);Om_s]);"),
}

OCTAVE_RUN = (
    "Q1 = (-Om_s^2*sys.M + 1i*Om_s*sys.D + sys.K)\\sys.Fex1; n = length(Q1);"
    "y0 = zeros((2*H+1)*n,1); y0(n+(1:2*n)) = [real(Q1);-imag(Q1)]; t0 = tic;"
    "X = solve_and_continue(y0,@(X) HB_residual(X,sys,H,N,'frf'),Om_s,Om_e,ds,Sopt);"
    "t = toc(t0); printf('NLVIB %d %.6f %.6f\\n', columns(X), t, X(end,end));")


def _chain_system(mdk: tuple[Any, ...], forcing: list[float],
                  elements: list[Any]) -> rs.hb.System:
    M, D, K = mdk
    return rs.hb.System(M, K, D, forcing=forcing, elements=elements)


def rotorsim_times(repeat: int) -> dict[str, dict[str, float]]:
    """Best-of-``repeat`` wall time per point, without and with stability."""
    out: dict[str, dict[str, float]] = {}
    for name, (make, kw) in CASES.items():
        row: dict[str, float] = {}
        options: tuple[tuple[str, dict[str, Any]], ...] = (
            ("plain", {"stability": None, "bifurcations": False}), ("stability", {}))
        for label, extra in options:
            if label == "stability" and kw["samples"] > 512:
                continue        # example 03: events at the contact resonance (issue 16)
            best = float("inf")
            for _ in range(repeat):
                clock = time.perf_counter()
                frf = rs.hb.frequency_response(make(), **kw, **extra)
                best = min(best, time.perf_counter() - clock)
            row[f"{label}_points"] = len(frf)
            row[f"{label}_ms_per_point"] = 1e3 * best / len(frf)
            row[f"{label}_end"] = float(frf.omega[-1])
        out[name] = row
    return out


def nlvib_times(nlvib: Path) -> dict[str, dict[str, float]]:
    """NLvib's continuation in Octave: points, seconds and last frequency per case."""
    out: dict[str, dict[str, float]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "SRC"
        shutil.copytree(nlvib / "SRC", src)
        driver = src / "solve_and_continue.m"
        driver.write_text(driver.read_text().replace("optimset(@fsolve)", "optimset('fsolve')"))
        for name, setup in OCTAVE_SETUP.items():
            script = (f"addpath('{src}'); addpath('{src / 'MechanicalSystems'}');"
                      f"{setup}{OCTAVE_RUN}")
            done = subprocess.run(["octave", "--no-gui", "--no-window-system", "-q",
                                   "--eval", script], capture_output=True, text=True,
                                  timeout=1200)
            m = re.search(r"NLVIB (\d+) ([\d.]+) ([\d.]+)", done.stdout)
            if m is None:
                print(f"{name}: NLvib failed:\n{done.stderr[-2000:]}")
                continue
            points, seconds = int(m.group(1)), float(m.group(2))
            out[name] = {"points": points, "ms_per_point": 1e3 * seconds / points,
                         "end": float(m.group(3))}
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nlvib", type=Path, help="NLvib checkout (needs octave)")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    ours = rotorsim_times(args.repeat)
    theirs = nlvib_times(args.nlvib) if args.nlvib and shutil.which("octave") else {}
    print(f"{'case':40s} {'points':>7s} {'ms/pt':>8s} {'+stab ms/pt':>12s} "
          f"{'NLvib pts':>9s} {'NLvib ms/pt':>11s} {'ratio':>6s}")
    for name, row in ours.items():
        ref = theirs.get(name, {})
        stab = row.get("stability_ms_per_point")
        ratio = ref["ms_per_point"] / row["plain_ms_per_point"] if ref else None
        print(f"{name:40s} {row['plain_points']:7d} {row['plain_ms_per_point']:8.2f} "
              f"{'-' if stab is None else f'{stab:.2f}':>12s} "
              f"{ref.get('points', '-')!s:>9s} "
              f"{'-' if not ref else format(ref['ms_per_point'], '.2f'):>11s} "
              f"{'-' if ratio is None else format(ratio, '.1f'):>6s}")
        if ref:
            print(f"{'':40s} end W: rotorsim {row['plain_end']:.4f}, NLvib {ref['end']:.4f}")


if __name__ == "__main__":
    main()
