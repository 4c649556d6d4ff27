"""Transient performance and a fair equal-accuracy comparison with solve_ivp (one core).

Two models (:data:`MODELS`), both steel shafts on two ball bearings with clearance and
proportional contact damping, under gravity and an unbalance at constant speed:

* ``"bench"``: 20 elements, two disks, two 12-ball bearings, 600 rad/s, 4 ms (126 free DOFs);
* ``"issue14"``: 24 elements, one disk, two 9-ball bearings, 1000 rad/s, 10 ms (the model
  of issue 14).

It prints

* the wall time of 100,000 average-acceleration steps of the ``bench`` model;
* for each model, an equal-accuracy comparison with ``scipy.integrate.solve_ivp`` (Radau,
  BDF and LSODA, given the exact Jacobian, rtol 1e-2 ... 1e-6) on the same first-order
  system ``y = [q, v]`` with the same force model. Tolerances are set as a user would set
  them: ``atol`` is ``rtol`` times the scale of each component, the displacements' and the
  velocities' separately (the peak-to-peak motion and velocity of the probe DOF in the
  reference run). The error is the largest deviation of the probe DOF (mid-span ``uy``) over
  41 times from a tight reference (LSODA, rtol 1e-10, the same per-component scales times
  1e-10), relative to its peak-to-peak motion. For the accuracies 1e-3 and 1e-5 it reports
  the cheapest run of each method that reaches it and rotorsim's speed-up against the
  fastest solve_ivp method;
* memory: the peak traced allocation of runs with 10x more steps keeping 3 DOFs stays flat.

Ratios come from one run; absolute times are noisy.

Run: ``.venv/bin/python benchmarks/bench_transient.py [--steps N] [--quick]
[--models bench issue14]``.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
import tracemalloc
from dataclasses import dataclass
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

TARGETS = {"steps_s": 60.0, "speedup": 10.0}
ACCURACIES = (1e-3, 1e-5)
"""Accuracies (error relative to the probe's motion) at which the costs are compared."""
RTOLS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)
"""Relative tolerances of the solve_ivp runs."""
IVP_METHODS = ("Radau", "BDF", "LSODA")


@dataclass(frozen=True)
class BenchModel:
    """A benchmark rotor: shaft, disks and two ball bearings, its speed, unbalance, probe
    node (mid-span), run length and the rotorsim time steps tried."""

    elements: int
    element_length: float
    diameter: float
    disk_nodes: tuple[int, ...]
    disk_diameter: float
    ball: dict[str, float]
    speed: float
    t_end: float
    steps: tuple[float, ...]

    @property
    def probe(self) -> int:
        return self.elements // 2

    @property
    def unbalance(self) -> list[tuple[int, float, float]]:
        return [(self.probe, 2e-5, 0.0)]

    def build(self) -> tuple[rs.Rotor, list[RollingBearing]]:
        steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
        shaft = [rs.ShaftElement(L=self.element_length, idl=0.0, odl=self.diameter,
                                 material=steel) for _ in range(self.elements)]
        disks = [rs.DiskElement.from_geometry(n=n, material=steel, width=0.03,
                                              i_d=self.diameter, o_d=self.disk_diameter)
                 for n in self.disk_nodes]
        ball = BallBearing(**self.ball, f_i=0.52, f_o=0.52)  # type: ignore[arg-type]
        bearings = [RollingBearing(ball, n=n, tag=t, contact_damping="proportional",
                                   damping_factor=2e-5)
                    for n, t in ((0, "A"), (self.elements, "B"))]
        return rs.Rotor(shaft, disks), bearings


MODELS = {
    "bench": BenchModel(20, 0.04, 0.04, (7, 14), 0.18,
                        {"n_balls": 12, "pitch_diameter": 0.0585, "ball_diameter": 0.0119,
                         "Kn": 1.2e10, "diametral_clearance": 10e-6},
                        speed=600.0, t_end=0.004,
                        steps=(4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6)),
    "issue14": BenchModel(24, 0.0333, 0.04, (12,), 0.25,
                          {"n_balls": 9, "pitch_diameter": 0.039, "ball_diameter": 0.00794,
                           "Kn": 8.0e9, "diametral_clearance": 10e-6},
                          speed=1000.0, t_end=0.010,
                          steps=(4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6)),
}
"""The two benchmark models (module docstring)."""


def rotorsim_run(bench: BenchModel, t_end: float, dt: float, times: Any = None):
    rotor, bearings = bench.build()
    return transient(rotor, t_end, dt, nonlinear=bearings, speed=bench.speed,
                     unbalance=bench.unbalance, nodes=[bench.probe],
                     output=rs.Output(times=[t_end] if times is None else times))


def steps(n_steps: int, dt: float = 2e-5) -> dict[str, float]:
    start = time.perf_counter()
    res = rotorsim_run(MODELS["bench"], n_steps * dt, dt)
    wall = time.perf_counter() - start
    return {"steps": float(res.stats["steps"]), "wall_s": wall,
            "us_per_step": 1e6 * wall / res.stats["steps"],
            "iterations_per_step": float(res.stats["iterations_per_step"]),
            "factorizations": float(res.stats["factorizations"])}


def first_order(bench: BenchModel):
    """``y = [q, v]`` right-hand side and Jacobian with the same force model, the start
    ``y0`` (static equilibrium at rest) and the index of the probe DOF."""
    rotor, bearings = bench.build()
    system = assemble(rotor, bearings)
    t_end, speed = bench.t_end, bench.speed
    from rotorsim.analyses.transient.speed_profile import ConstantSpeed
    from rotorsim.analyses.transient.start import initial_state
    from rotorsim.analyses.transient.transient import _problem

    profile = ConstantSpeed(speed).bind(0.0, t_end)
    problem, loads = _problem(system, profile, 0.0, rs.Excitation(unbalance=bench.unbalance))
    n = system.n_free
    M = np.asarray(problem.mass)
    Minv = np.linalg.inv(M)  # baseline only: dense inverse of the small mass matrix
    K, C, G = (np.asarray(m) for m in (problem.stiffness, problem.damping,
                                       problem.gyroscopic))
    D = C + speed * G
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
    return rhs, jac, np.concatenate([q0, np.zeros(n)]), \
        system.dofs_of(bench.probe, ("uy",))[0]


def equal_accuracy(bench: BenchModel, reference_rtol: float = 1e-10,
                   rtols: tuple[float, ...] = RTOLS) -> dict[str, float]:
    """Cost of rotorsim (average acceleration over ``bench.steps``) and of solve_ivp
    (Radau, BDF, LSODA over ``rtols``) for the same accuracy (module docstring): the error
    of each run, and for each of :data:`ACCURACIES` the cheapest run of each method that
    reaches it and rotorsim's speed-up against the fastest solve_ivp method."""
    rhs, jac, y0, probe = first_order(bench)
    n = y0.size // 2
    t_end = bench.t_end
    times = np.linspace(0.0, t_end, 41)
    # scales of the displacements and of the velocities, as a user knows them: the motion
    # and the velocity of the probe in a fine rotorsim run
    scout = rotorsim_run(bench, t_end, min(bench.steps), times=times)
    scales = (float(np.ptp(scout.displacement(bench.probe, "uy"))),
              float(np.ptp(scout.velocity(bench.probe, "uy"))))
    per_component = np.concatenate([np.full(n, scales[0]), np.full(n, scales[1])])
    ref = solve_ivp(rhs, (0.0, t_end), y0, method="LSODA", jac=jac, rtol=reference_rtol,
                    atol=reference_rtol * per_component, t_eval=times).y[probe]
    motion = float(np.ptp(ref))
    runs: dict[str, list[tuple[float, float]]] = {"rotorsim": [],
                                                  **{m: [] for m in IVP_METHODS}}
    out: dict[str, float] = {"probe motion [m]": motion,
                             "probe velocity scale [m/s]": scales[1]}
    for dt in bench.steps:
        start = time.perf_counter()
        res = rotorsim_run(bench, t_end, dt, times=times)
        wall = time.perf_counter() - start
        err = float(np.max(np.abs(res.displacement(bench.probe, "uy") - ref))) / motion
        runs["rotorsim"].append((err, wall))
        out[f"rotorsim dt={dt:g}: error"] = err
        out[f"rotorsim dt={dt:g}: s"] = wall
    for method in IVP_METHODS:
        for rtol in rtols:
            start = time.perf_counter()
            sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, jac=jac, rtol=rtol,
                            atol=rtol * per_component, t_eval=times)
            wall = time.perf_counter() - start
            err = float(np.max(np.abs(sol.y[probe] - ref))) / motion if sol.success \
                else math.inf
            runs[method].append((err, wall))
            out[f"{method} rtol={rtol:g}: error"] = err
            out[f"{method} rtol={rtol:g}: s"] = wall
    for target in ACCURACIES:
        cost = {m: min((w for e, w in r if e <= target), default=math.inf)
                for m, r in runs.items()}
        fastest = min(IVP_METHODS, key=lambda m: cost[m])
        for method in IVP_METHODS:
            out[f"{method} cheapest at {target:g}: s"] = cost[method]
        out[f"rotorsim cheapest at {target:g}: s"] = cost["rotorsim"]
        # NaN: rotorsim does not reach the accuracy with the steps tried
        out[f"speed-up vs fastest ({fastest}) at {target:g}"] = \
            cost[fastest] / cost["rotorsim"] if math.isfinite(cost["rotorsim"]) else math.nan
    return out


def memory(n_steps: int) -> dict[str, float]:
    """Peak traced memory [MB] of linear runs of n and 10 n steps keeping 3 DOFs."""
    rotor, _ = MODELS["bench"].build()
    speed, unbalance = MODELS["bench"].speed, MODELS["bench"].unbalance
    rotor = rs.Rotor(rotor.shaft_elements, rotor.disk_elements,
                     [rs.BearingElement(n=0, kxx=1e8, cxx=1e3),
                      rs.BearingElement(n=20, kxx=1e8, cxx=1e3)])
    out = {}
    for k in (n_steps, 10 * n_steps):
        tracemalloc.start()
        transient(rotor, k * 1e-5, 1e-5, speed=speed, unbalance=unbalance,
                  nodes=[10], excitation=rs.Excitation(gravity=None), output=rs.Output(every=10),
                  initial="zero")
        out[f"{k} steps peak MB"] = tracemalloc.get_traced_memory()[1] / 1e6
        tracemalloc.stop()
    return out


def main(argv: list[str] | None = None) -> dict[str, dict[str, float]]:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100_000)
    parser.add_argument("--quick", action="store_true",
                        help="5,000 steps, rtol 1e-2 and 1e-3 only")
    parser.add_argument("--models", nargs="+", choices=sorted(MODELS), default=list(MODELS))
    args = parser.parse_args(argv)
    n = 5_000 if args.quick else args.steps
    rtols = RTOLS[:2] if args.quick else RTOLS
    report = {"steps": steps(n),
              **{f"accuracy {name}": equal_accuracy(MODELS[name], rtols=rtols)
                 for name in args.models},
              "memory": memory(2_000 if args.quick else 10_000)}
    for name, values in report.items():
        print(f"\n[{name}]")
        for key, value in values.items():
            print(f"  {key:32s} {value:.6g}")
    return report


if __name__ == "__main__":
    main()
