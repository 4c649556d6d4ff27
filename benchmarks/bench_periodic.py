"""Periodic-response (harmonic balance + continuation) performance against the issue 7
targets (one core).

The model: a 0.8 m, 40 mm steel shaft in 16 Timoshenko elements (102 DOFs) with two
200 mm disks, on two 9-ball deep-groove bearings with 10 um diametral clearance (Hertz,
nonlinear; cages held so that the unbalance response is exactly periodic), viscous
dampers at the bearings (3000 N s/m) and the disks (300 N s/m), gravity and two
unbalances. Prints

* the wall time of a 300-point branch at ``H = 10`` (target < 30 s), without and with
  Floquet multipliers (Hsu's method on the Craig-Bampton stability model);
* the time-integration alternative on a subset of the branch points (stable, more than 3 %
  from any fold, where the steady state is unique): ``rs.transient``
  (average acceleration) at each point's speed, started from the static equilibrium, with
  the step refined (64, 128, 256, ... steps per period) until its steady peak-to-peak
  amplitude of the disk matches HB within ``--accuracy`` (default 1e-3; HB's own error,
  measured against ``H = 20``, is far below it), and charged only up to the period where
  it settled within that accuracy (an oracle stop, which favours time integration). The
  mean cost per point times the branch's points is compared with the HB branch
  (target: HB >= 50x faster).

Run: ``.venv/bin/python benchmarks/bench_periodic.py [--points N] [--subset K] [--quick]``.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")   # one core, as the targets say

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import rotorsim as rs  # noqa: E402
from rotorsim.analyses.periodic.periodic import periodic  # noqa: E402
from rotorsim.analyses.transient.transient import transient  # noqa: E402
from rotorsim.elements.rolling.ball.bearing import BallBearing  # noqa: E402
from rotorsim.elements.rolling.element import RollingBearing  # noqa: E402
from rotorsim.results.periodic import PeriodicResult  # noqa: E402

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
UNBALANCE = [(5, 2e-5, 0.0), (11, 2e-5, 1.0)]
DISK = 5
TARGET_S, TARGET_RATIO = 30.0, 50.0


def benchmark_rotor() -> rs.Rotor:
    """The 102-DOF rotor of the module docstring."""
    shaft = [rs.ShaftElement(L=0.05, idl=0.0, odl=0.04, material=STEEL) for _ in range(16)]
    disks = [rs.DiskElement.from_geometry(n=n, material=STEEL, width=0.03, i_d=0.04,
                                          o_d=0.2) for n in (5, 11)]
    ball = BallBearing(n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794, Kn=9.3e9,
                       f_i=0.52, f_o=0.52, diametral_clearance=10e-6, cage="fixed")
    bearings = [RollingBearing(ball, n=n, tag=f"B{n}") for n in (1, 15)]
    dampers = [rs.BearingElement(n=n, kxx=0.0, cxx=c) for n, c in
               ((1, 3000.0), (15, 3000.0), (5, 300.0), (11, 300.0))]
    return rs.Rotor(shaft, disks, dampers, nonlinear_elements=bearings, fixed=[(8, "uz")])


def hb_branch(rotor: rs.Rotor, points: int, stability: str | None) -> PeriodicResult:
    res = periodic(rotor, start=200.0, stop=3000.0, harmonics=10, unbalance=UNBALANCE,
                   continuation=rs.ContinuationOptions(max_points=points, max_step=0.05,
                                                       tol=1e-8),
                   stability=rs.StabilityOptions(stability, bifurcations=stability is not None),
                   nodes=[5, 11])
    assert isinstance(res, PeriodicResult)     # fixed cages: a periodic problem
    return res


def comparable_points(branch: PeriodicResult, count: int) -> np.ndarray:
    """``count`` stable points, evenly spread over the eligible ones, more than 3 % in speed
    away from every fold: there the steady state a transient reaches is unique."""
    folds = np.array([b.parameter for b in branch.events("fold")])
    far = np.all(np.abs(branch.parameter[:, None] / folds[None, :] - 1) > 0.03, axis=1) \
        if folds.size else np.ones(len(branch), dtype=bool)
    eligible = np.flatnonzero(branch.stable & far)
    eligible = eligible[eligible > 0]
    return eligible[np.linspace(0, eligible.size - 1, count).astype(int)]


def hb_reference(rotor: rs.Rotor, speed: float) -> float:
    """Disk peak-to-peak at ``speed`` with ``H = 20`` (the accuracy reference of HB)."""
    res = periodic(rotor, start=speed, stop=speed * 1.001, harmonics=20, unbalance=UNBALANCE,
                   continuation=rs.ContinuationOptions(max_points=2, tol=1e-10),
                   stability=rs.StabilityOptions(None, bifurcations=False), nodes=[DISK])
    return float(res.amplitude(DISK, "uy", "peak_to_peak")[0])


def transient_cost(rotor: rs.Rotor, speed: float, target: float, accuracy: float,
                   periods: int) -> dict[str, float]:
    """Cheapest step (64 * 2^k per period) reaching ``accuracy``; cost up to settling."""
    T = 2 * np.pi / speed
    for steps in (64, 128, 256, 512, 1024):
        clock = time.perf_counter()
        res = transient(rotor, periods * T, T / steps, speed=speed, unbalance=UNBALANCE,
                        nodes=[DISK])
        spent = time.perf_counter() - clock
        y = res.displacement(DISK, "uy")
        k = np.minimum((res.t / T).astype(int), periods - 1)
        ptp = np.array([np.ptp(y[k == j]) for j in range(periods)])
        error = abs(ptp[-1] / target - 1)
        off = np.flatnonzero(np.abs(ptp / ptp[-1] - 1) > accuracy)
        settled = int(off[-1] + 1) if off.size else 1
        if error <= accuracy and settled < periods - 2:
            return {"speed": speed, "steps_per_period": steps, "settle_periods": settled,
                    "error": error, "cost": spent * (settled + 1) / periods}
    return {"speed": speed, "steps_per_period": np.nan, "settle_periods": np.nan,
            "error": error, "cost": np.nan}


def run(points: int = 300, subset: int = 5, accuracy: float = 1e-3,
        periods: int = 120) -> dict[str, Any]:
    rotor = benchmark_rotor()
    clock = time.perf_counter()
    branch = hb_branch(rotor, points, None)
    t_hb = time.perf_counter() - clock
    clock = time.perf_counter()
    with_floquet = hb_branch(rotor, points, "hsu")
    t_floquet = time.perf_counter() - clock
    picks = comparable_points(with_floquet, subset)
    rows = []
    hb_ptp = with_floquet.amplitude(DISK, "uy", "peak_to_peak")
    for i in picks:
        W = float(with_floquet.parameter[i])
        ref = hb_reference(rotor, W)
        row = transient_cost(rotor, W, ref, accuracy, periods)
        row["hb_error"] = abs(hb_ptp[i] / ref - 1)
        rows.append(row)
    cost = float(np.nanmean([r["cost"] for r in rows]))
    return {"points": len(branch), "speed_range": (float(branch.parameter[0]),
                                                   float(branch.parameter[-1])),
            "dofs": rotor.ndof, "hb_time": t_hb, "hb_floquet_time": t_floquet,
            "floquet_method": with_floquet.stability_method,
            "stability_modes": with_floquet.options["stability_model_modes"],
            "unstable_points": int(np.sum(~with_floquet.stable)),
            "bifurcations": [(b.kind, round(b.parameter, 1)) for b in
                             with_floquet.bifurcations],
            "per_point_ms": 1e3 * t_hb / len(branch), "stats": branch.stats,
            "transient": rows, "transient_per_point": cost,
            "transient_branch_estimate": cost * len(branch),
            "ratio": cost * len(branch) / t_hb}


def format_report(out: dict[str, Any]) -> str:
    lo, hi = out["speed_range"]
    lines = [f"rotor: {out['dofs']} DOFs, two nonlinear ball bearings, H = 10",
             f"HB branch: {out['points']} points ({lo:.0f} -> {hi:.0f} rad/s) in "
             f"{out['hb_time']:.2f} s ({out['per_point_ms']:.1f} ms/point; target < "
             f"{TARGET_S:.0f} s: {'met' if out['hb_time'] < TARGET_S else 'MISSED'})",
             f"  with Floquet ({out['floquet_method']}, stability model "
             f"{out['stability_modes']} modes) and bifurcations: {out['hb_floquet_time']:.2f} s;"
             f" {out['unstable_points']} unstable points, {out['bifurcations']}",
             f"  residual evaluations {out['stats']['residual_evaluations']:.0f}, "
             f"corrector iterations/point {out['stats']['iterations_per_point']:.2f}, "
             f"rejected steps {out['stats']['rejected_steps']:.0f}",
             "time integration to steady state at the same accuracy:"]
    for r in out["transient"]:
        lines.append(f"  {r['speed']:7.1f} rad/s: {r['steps_per_period']:4.0f} steps/period,"
                     f" settled after {r['settle_periods']:3.0f} periods, error "
                     f"{r['error']:.1e} (HB error {r['hb_error']:.1e}), cost {r['cost']:.2f} s")
    lines.append(f"  mean {out['transient_per_point']:.2f} s/point -> "
                 f"{out['transient_branch_estimate']:.0f} s for the branch; HB is "
                 f"{out['ratio']:.0f}x faster (target >= {TARGET_RATIO:.0f}x: "
                 f"{'met' if out['ratio'] >= TARGET_RATIO else 'MISSED'})")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=300)
    parser.add_argument("--subset", type=int, default=5)
    parser.add_argument("--accuracy", type=float, default=1e-3)
    parser.add_argument("--quick", action="store_true", help="60 points, 2 transients")
    args = parser.parse_args(argv)
    if args.quick:
        args.points, args.subset = 60, 2
    out = run(args.points, args.subset, args.accuracy)
    print(format_report(out))
    return out


if __name__ == "__main__":
    main()
