"""Transient performance against the issue 6 targets (one core).

The model: a 20-element steel shaft with two disks on two 12-ball bearings (ground,
clearance, proportional contact damping), gravity and an unbalance, at constant speed
(126 free DOFs). Prints

* the wall time of 100,000 average-acceleration steps (target < 60 s);
* an equal-accuracy comparison with ``scipy.integrate.solve_ivp`` (Radau and LSODA, given
  the exact Jacobian) on the same first-order system with the same force model: the
  largest error over a 4 ms run against a tight reference (LSODA, rtol 1e-10), relative to
  the motion, and the time of the cheapest run of each method that reaches 1e-3 and 1e-4
  (target: rotorsim >= 10x faster);
* memory: the peak traced allocation of runs with 10x more steps keeping 3 DOFs stays flat.

Run: ``.venv/bin/python benchmarks/bench_transient.py [--steps N] [--quick]``.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
import tracemalloc
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

import rotorsim as rs  # noqa: E402
from rotorsim.analyses.transient.transient import transient  # noqa: E402
from rotorsim.assembly.system import assemble  # noqa: E402
from rotorsim.elements.rolling.ball.bearing import BallBearing  # noqa: E402
from rotorsim.elements.rolling.element import RollingBearing  # noqa: E402

SPEED = 600.0  # rad/s
UNBALANCE = [(10, 2e-5, 0.0)]
TARGETS = {"steps_s": 60.0, "speedup": 10.0}


def model() -> tuple[rs.Rotor, list[RollingBearing]]:
    """The benchmark rotor (module docstring)."""
    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    shaft = [rs.ShaftElement(L=0.04, idl=0.0, odl=0.04, material=steel) for _ in range(20)]
    disks = [rs.DiskElement.from_geometry(n=n, material=steel, width=0.03, i_d=0.04,
                                          o_d=0.18) for n in (7, 14)]
    ball = BallBearing(n_balls=12, pitch_diameter=0.0585, ball_diameter=0.0119, Kn=1.2e10,
                       diametral_clearance=10e-6, f_i=0.52, f_o=0.52)
    bearings = [RollingBearing(ball, n=n, tag=t, contact_damping="proportional",
                               damping_factor=2e-5) for n, t in ((0, "A"), (20, "B"))]
    return rs.Rotor(shaft, disks), bearings


def rotorsim_run(t_end: float, dt: float, times: Any = None):
    rotor, bearings = model()
    return transient(rotor, t_end, dt, nonlinear=bearings, speed=SPEED, unbalance=UNBALANCE,
                     nodes=[10], output=rs.Output(times=[t_end] if times is None else times))


def steps(n_steps: int, dt: float = 2e-5) -> dict[str, float]:
    start = time.perf_counter()
    res = rotorsim_run(n_steps * dt, dt)
    wall = time.perf_counter() - start
    return {"steps": float(res.stats["steps"]), "wall_s": wall,
            "us_per_step": 1e6 * wall / res.stats["steps"],
            "iterations_per_step": float(res.stats["iterations_per_step"]),
            "factorizations": float(res.stats["factorizations"])}


def first_order(t_end: float):
    """``y = [q, v]`` right-hand side and Jacobian with the same force model."""
    rotor, bearings = model()
    system = assemble(rotor, bearings)
    from rotorsim.analyses.transient.speed_profile import ConstantSpeed
    from rotorsim.analyses.transient.start import initial_state
    from rotorsim.analyses.transient.transient import _problem

    profile = ConstantSpeed(SPEED).bind(0.0, t_end)
    problem, loads = _problem(system, profile, 0.0, UNBALANCE, 9.80665, (0, -1, 0), (),
                              None, None)
    n = system.n_free
    M = np.asarray(problem.mass)
    Minv = np.linalg.inv(M)  # baseline only: dense inverse of a 126x126 mass matrix
    K, C, G = (np.asarray(m) for m in (problem.stiffness, problem.damping,
                                       problem.gyroscopic))
    D = C + SPEED * G
    restoring = problem.restoring
    assert restoring is not None

    def rhs(t, y):
        q, v = y[:n], y[n:]
        r, _, _ = restoring(q, v, t)
        return np.concatenate([v, Minv @ (loads(t) - K @ q - D @ v - r)])

    def jac(t, y):
        q, v = y[:n], y[n:]
        _, kt, ct = restoring(q, v, t)
        J = np.zeros((2 * n, 2 * n))
        J[:n, n:] = np.eye(n)
        J[n:, :n] = -Minv @ (K + kt.toarray())
        J[n:, n:] = -Minv @ (D + ct.toarray())
        return J

    q0, _ = initial_state(system, "static", loads.constant, profile, 0.0)
    return rhs, jac, np.concatenate([q0, np.zeros(n)]), system.dofs_of(10, ("uy",))[0]


def equal_accuracy(t_end: float = 0.004, reference_rtol: float = 1e-10,
                   targets: tuple[float, ...] = (1e-3, 1e-4)) -> dict[str, float]:
    """Cost of rotorsim and of solve_ivp (Radau, LSODA; exact Jacobian) for the same
    accuracy: the largest error of the probe DOF over 41 times of a ``t_end`` run against a
    tight LSODA solution, relative to the probe's motion; for each target the cheapest run
    of each method that reaches it, and the ratio of the times."""
    rhs, jac, y0, probe = first_order(t_end)
    times = np.linspace(0.0, t_end, 41)
    ref = solve_ivp(rhs, (0.0, t_end), y0, method="LSODA", jac=jac, rtol=reference_rtol,
                    atol=reference_rtol * 1e-8, t_eval=times).y[probe]
    motion = float(np.ptp(ref))
    runs: dict[str, list[tuple[float, float]]] = {"rotorsim": [], "Radau": [], "LSODA": []}
    out: dict[str, float] = {"probe motion [m]": motion}
    for dt in (4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6):
        start = time.perf_counter()
        res = rotorsim_run(t_end, dt, times=times)
        wall = time.perf_counter() - start
        err = float(np.max(np.abs(res.displacement(10, "uy") - ref))) / motion
        runs["rotorsim"].append((err, wall))
        out[f"rotorsim dt={dt:g}: error"] = err
        out[f"rotorsim dt={dt:g}: s"] = wall
    for method in ("Radau", "LSODA"):
        for rtol in (1e-3, 1e-4, 1e-5):
            start = time.perf_counter()
            sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, jac=jac, rtol=rtol,
                            atol=rtol * 1e-6, t_eval=times)
            wall = time.perf_counter() - start
            err = float(np.max(np.abs(sol.y[probe] - ref))) / motion if sol.success \
                else math.inf
            runs[method].append((err, wall))
            out[f"{method} rtol={rtol:g}: error"] = err
            out[f"{method} rtol={rtol:g}: s"] = wall
    for target in targets:
        cost = {m: min((w for e, w in r if e <= target), default=math.inf)
                for m, r in runs.items()}
        for method in ("Radau", "LSODA"):
            out[f"speed-up vs {method} at {target:g}"] = cost[method] / cost["rotorsim"]
    return out


def memory(n_steps: int) -> dict[str, float]:
    """Peak traced memory [MB] of linear runs of n and 10 n steps keeping 3 DOFs."""
    rotor, _ = model()
    rotor = rs.Rotor(rotor.shaft_elements, rotor.disk_elements,
                     [rs.BearingElement(n=0, kxx=1e8, cxx=1e3),
                      rs.BearingElement(n=20, kxx=1e8, cxx=1e3)])
    out = {}
    for k in (n_steps, 10 * n_steps):
        tracemalloc.start()
        transient(rotor, k * 1e-5, 1e-5, speed=SPEED, unbalance=UNBALANCE,
                  nodes=[10], excitation=rs.Excitation(gravity=None), output=rs.Output(every=10),
                  initial="zero")
        out[f"{k} steps peak MB"] = tracemalloc.get_traced_memory()[1] / 1e6
        tracemalloc.stop()
    return out


def main(argv: list[str] | None = None) -> dict[str, dict[str, float]]:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100_000)
    parser.add_argument("--quick", action="store_true", help="5,000 steps, short runs")
    args = parser.parse_args(argv)
    n = 5_000 if args.quick else args.steps
    report = {"steps": steps(n), "accuracy": equal_accuracy(0.004),
              "memory": memory(2_000 if args.quick else 10_000)}
    for name, values in report.items():
        print(f"\n[{name}]")
        for key, value in values.items():
            print(f"  {key:32s} {value:.6g}")
    return report


if __name__ == "__main__":
    main()
