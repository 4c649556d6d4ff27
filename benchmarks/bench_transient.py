"""Transient performance and a fair equal-accuracy comparison with solve_ivp (one core).

Three models (:data:`MODELS`), steel shafts on ball bearings with clearance and proportional
contact damping, under gravity and an unbalance at constant speed:

* ``"bench"``: 20 elements, two disks, two 12-ball bearings, 600 rad/s, 4 ms (126 free DOFs);
* ``"issue14"``: 24 elements, one disk, two 9-ball bearings, 1000 rad/s, 10 ms (the model
  of issue 14);
* ``"rotor1000"``: 165 elements (996 free DOFs), three disks, four 12-ball bearings,
  600 rad/s, 4 ms (sparse matrices in rotorsim; the reference is Radau, LSODA being too
  slow at rtol 1e-10 with a dense 1992 x 1992 Jacobian, and solve_ivp runs at rtol 1e-2 to
  1e-4 only, each costing minutes).

It prints

* the wall time of 100,000 average-acceleration steps of the ``bench`` model;
* for each model, an equal-accuracy comparison of rotorsim (fixed-step average acceleration
  over the model's steps, and the automatic path ``rs.transient(..., rtol=)`` over rtol
  1e-1 ... 1e-7; exponential collocation on the small models at constant speed, Radau IIA
  otherwise) with ``scipy.integrate.solve_ivp`` (Radau,
  BDF and LSODA, given the exact Jacobian, rtol 1e-1 ... 1e-6) on the same first-order
  system ``y = [q, v]`` with the same force model. Tolerances are set as a user would set
  them: ``atol`` is ``rtol`` times the scale of each component, the displacements' and the
  velocities' separately (the peak-to-peak motion and velocity of the probe DOF in the
  reference run). The error is the largest deviation of the probe DOF (mid-span ``uy``) over
  41 times from a tight reference (LSODA, or Radau for ``rotor1000``, rtol 1e-10, the same
  per-component scales times 1e-10), relative to its peak-to-peak motion. For the
  accuracies 1e-3 and 1e-5 it reports the cheapest run of each method that reaches it and
  rotorsim's speed-up against the fastest solve_ivp method;
* memory: the peak traced allocation of runs with 10x more steps keeping 3 DOFs stays flat.

The model objects (shaft elements, disks, bearings) are built once outside the timing, as
the peers' right-hand side and Jacobian are; rotorsim's time includes its assembly, static
start and set-up inside ``rs.transient``.

The equal-accuracy costs are CPU times of this process (``time.process_time``; one BLAS
thread, so equal to the wall time on an idle machine and robust on a shared one), each the
least of ``--repeat`` timings (3 by default) of the same run, rotorsim's and solve_ivp's
alike. Every run starts from the same static equilibrium, computed once. Ratios come from
one run; absolute times are noisy.

Run: ``.venv/bin/python benchmarks/bench_transient.py [--steps N] [--quick] [--repeat R]
[--models bench issue14 rotor1000] [--peers-cache FILE]`` (``--steps 0`` skips the
100,000-step and memory parts). ``--quick`` (CI size: a minute or two) runs 5,000
steps and the models ``bench`` and ``issue14`` unless ``--models`` says otherwise; the full
run takes about an hour, most of it solve_ivp on ``rotor1000``.
"""

from __future__ import annotations

import argparse
import json
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
import scipy.sparse as sp  # noqa: E402
import scipy.sparse.linalg as spl  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

import rotorsim as rs  # noqa: E402
from rotorsim.analyses.transient.transient import transient  # noqa: E402
from rotorsim.assembly.system import assemble  # noqa: E402
from rotorsim.elements.rolling.ball.bearing import BallBearing  # noqa: E402
from rotorsim.elements.rolling.element import RollingBearing  # noqa: E402

TARGETS = {"steps_s": 60.0, "speedup": 10.0}
ACCURACIES = (1e-3, 1e-5)
"""Accuracies (error relative to the probe's motion) at which the costs are compared."""
RTOLS = (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4, 1e-5, 1e-6)
"""Relative tolerances of the solve_ivp runs (from 1e-1: on the small models Radau at
rtol 3e-2 reaches 1e-3 of the motion more cheaply than at 1e-2)."""
IVP_METHODS = ("Radau", "BDF", "LSODA")
AUTO_RTOLS = (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7)
"""Accuracies asked of rotorsim's automatic path (``rs.transient(..., rtol=)``)."""


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
    bearing_nodes: tuple[int, ...] = ()
    rtols: tuple[float, ...] = RTOLS
    auto_rtols: tuple[float, ...] = AUTO_RTOLS
    reference: str = "LSODA"

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
        nodes = self.bearing_nodes or (0, self.elements)
        bearings = [RollingBearing(ball, n=n, tag="ABCDEFGH"[i], contact_damping="proportional",
                                   damping_factor=2e-5)
                    for i, n in enumerate(nodes)]
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
    "rotor1000": BenchModel(165, 0.02, 0.06, (27, 82, 137), 0.24,
                            {"n_balls": 12, "pitch_diameter": 0.085, "ball_diameter": 0.0127,
                             "Kn": 1.2e10, "diametral_clearance": 10e-6},
                            speed=600.0, t_end=0.004, steps=(2e-5, 1e-5, 5e-6, 2.5e-6),
                            bearing_nodes=(0, 55, 110, 165), rtols=(1e-2, 1e-3, 1e-4),
                            auto_rtols=(1e-2, 1e-3, 1e-4, 1e-5, 1e-6), reference="Radau"),
}
"""The benchmark models (module docstring)."""


def rotorsim_run(bench: BenchModel, t_end: float, dt: float | None, times: Any = None,
                 initial: Any = "static", rtol: float | None = None,
                 velocities: bool = False, model: Any = None):
    """rotorsim on ``bench``: fixed steps ``dt`` (average acceleration), or the automatic
    path at ``rtol`` (``dt`` None); ``velocities`` keeps the velocities too. ``model`` is
    ``bench.build()`` when already built (the timed runs get it built, as the peers get
    their right-hand side built)."""
    rotor, bearings = bench.build() if model is None else model
    return transient(rotor, t_end, dt, nonlinear=bearings, speed=bench.speed,
                     unbalance=bench.unbalance, nodes=[bench.probe], initial=initial,
                     rtol=rtol, output=rs.Output(times=[t_end] if times is None else times,
                                                velocities=velocities))


def steps(n_steps: int, dt: float = 2e-5) -> dict[str, float]:
    start = time.perf_counter()
    res = rotorsim_run(MODELS["bench"], n_steps * dt, dt)
    wall = time.perf_counter() - start
    return {"steps": float(res.stats["steps"]), "wall_s": wall,
            "us_per_step": 1e6 * wall / res.stats["steps"],
            "iterations_per_step": float(res.stats["iterations_per_step"]),
            "factorizations": float(res.stats["factorizations"])}


def first_order(bench: BenchModel):
    """``y = [q, v]`` right-hand side and exact Jacobian with the same force model, the
    start ``y0`` (static equilibrium at rest), the index of the probe DOF and the start on
    all DOFs (for rotorsim).

    The Jacobian ``[[0, I], [-M^-1 K_t, -M^-1 D_t]]`` is dense whatever the size (the
    inverse of a consistent mass matrix is full), so it is given as a dense array, the
    peers' best: a sparse matrix with that many nonzeros is slower, and a ``jac_sparsity``
    would cost ``2n`` evaluations per Jacobian. ``M^-1 K`` and ``M^-1 D`` are formed once;
    a call adds the bearing tangents through the columns of ``M^-1`` at the bearing DOFs.
    """
    rotor, bearings = bench.build()
    system = assemble(rotor, bearings)
    t_end, speed = bench.t_end, bench.speed
    from rotorsim.analyses.transient.equation import rotor_problem as _problem
    from rotorsim.analyses.transient.speed_profile import ConstantSpeed
    from rotorsim.analyses.transient.start import initial_state

    profile = ConstantSpeed(speed).bind(0.0, t_end)
    problem, loads = _problem(system, profile, 0.0, rs.Excitation(unbalance=bench.unbalance))
    n = system.n_free
    dense = (lambda A: A.toarray() if sp.issparse(A) else np.asarray(A))  # noqa: E731
    M, K, C, G = (dense(m) for m in (problem.mass, problem.stiffness, problem.damping,
                                     problem.gyroscopic))
    mass_lu = spl.splu(sp.csc_matrix(M))
    D = C + speed * G
    MinvK, MinvD = mass_lu.solve(K), mass_lu.solve(D)
    nl = system.nonlinear
    assert nl is not None and problem.restoring is not None
    dofs = nl.dofs
    Minv_cols = mass_lu.solve(np.eye(n)[:, dofs])
    Ksp, Dsp = sp.csr_matrix(K), sp.csr_matrix(D)
    restoring = problem.restoring

    def rhs(t, y):
        q, v = y[:n], y[n:]
        r, _, _ = restoring(q, v, t)
        return np.concatenate([v, mass_lu.solve(loads(t) - Ksp @ q - Dsp @ v - r)])

    def jac(t, y):
        q, v = y[:n], y[n:]
        _, kt, ct = restoring(q, v, t)
        J = np.zeros((2 * n, 2 * n))
        J[:n, n:] = np.eye(n)
        J[n:, :n] = -MinvK
        J[n:, n:] = -MinvD
        J[n:, dofs] -= Minv_cols @ kt.block
        J[n:, n + dofs] -= Minv_cols @ ct.block
        return J

    q0, _ = initial_state(system, "static", loads.constant, profile, 0.0)
    full = np.zeros(system.dof_map.ndof)
    full[system.dof_map.free] = q0
    return rhs, jac, np.concatenate([q0, np.zeros(n)]), \
        system.dofs_of(bench.probe, ("uy",))[0], full


def best_of(repeat: int, run: Any) -> tuple[Any, float]:
    """``run()``'s result and its least CPU time [s] over ``repeat`` calls (the noise of a
    shared machine only ever adds time; every method, rotorsim's and solve_ivp's, is timed
    the same way)."""
    best, out = math.inf, None
    for _ in range(max(1, int(repeat))):
        clock = time.process_time()
        out = run()
        best = min(best, time.process_time() - clock)
    return out, best


def equal_accuracy(bench: BenchModel, reference_rtol: float = 1e-10,
                   quick: bool = False, peers_cache: str | None = None,
                   repeat: int = 1) -> dict[str, float]:
    """Cost of rotorsim (fixed-step average acceleration over ``bench.steps``, and the
    automatic path over ``bench.auto_rtols``) and of solve_ivp (Radau, BDF, LSODA over
    ``bench.rtols``) for the same accuracy (module docstring): the error of each run, and
    for each of :data:`ACCURACIES` the cheapest run of each method that reaches it and
    rotorsim's speed-up against the fastest solve_ivp method. Every run starts from the same
    static equilibrium (given to rotorsim as ``initial``), so no run is charged for it.

    ``repeat``: every run (rotorsim's and solve_ivp's) is timed that many times and its
    least CPU time kept (:func:`best_of`).

    ``peers_cache``: a JSON file with the scales, the reference and the solve_ivp runs of
    an earlier run on this model (written when it does not exist): the peers of
    ``rotor1000`` take most of an hour, so rotorsim's side can be rerun against them
    (their CPU times then come from another process on the same machine)."""
    rhs, jac, y0, probe, full = first_order(bench)
    n = y0.size // 2
    start = (full, np.zeros_like(full))
    t_end = bench.t_end
    times = np.linspace(0.0, t_end, 41)
    # scales of the displacements and of the velocities, as a user knows them: the motion
    # and the velocity of the probe in a fine rotorsim run
    cached = json.loads(Path(peers_cache).read_text()) \
        if peers_cache and Path(peers_cache).exists() else None
    if cached is None:
        scout = rotorsim_run(bench, t_end, min(bench.steps), times=times, initial=start,
                             velocities=True)
        scales = (float(np.ptp(scout.displacement(bench.probe, "uy"))),
                  float(np.ptp(scout.velocity(bench.probe, "uy"))))
    else:
        scales = tuple(cached["scales"])
    per_component = np.concatenate([np.full(n, scales[0]), np.full(n, scales[1])])
    ref = np.asarray(cached["reference"]) if cached is not None else solve_ivp(
        rhs, (0.0, t_end), y0, method=bench.reference, jac=jac, rtol=reference_rtol,
        atol=reference_rtol * per_component, t_eval=times).y[probe]
    motion = float(np.ptp(ref))
    runs: dict[str, list[tuple[float, float]]] = {"rotorsim": [], "rotorsim auto": [],
                                                  **{m: [] for m in IVP_METHODS}}
    out: dict[str, float] = {"probe motion [m]": motion,
                             "probe velocity scale [m/s]": scales[1]}
    settings: list[tuple[str, str, dict[str, Any]]] = [
        ("rotorsim", f"dt={dt:g}", {"dt": dt}) for dt in bench.steps]
    settings += [("rotorsim auto", f"rtol={r:g}", {"dt": None, "rtol": r})
                 for r in (bench.auto_rtols[:3] if quick else bench.auto_rtols)]
    model = bench.build()
    for label, setting, kw in settings:
        res, wall = best_of(repeat, lambda kw=kw: rotorsim_run(
            bench, t_end, times=times, initial=start, model=model, **kw))
        err = float(np.max(np.abs(res.displacement(bench.probe, "uy") - ref))) / motion
        runs[label].append((err, wall))
        out[f"{label} {setting}: error"] = err
        out[f"{label} {setting}: s"] = wall
        out[f"{label} {setting}: steps"] = float(res.stats["steps"])
        if kw.get("dt") is None:  # 1: the automatic path chose exponential collocation
            out[f"{label} {setting}: exponential"] = float(res.method == "exponential")
        decision = res.options.get("auto_reduction")
        if decision is not None:  # 1: the automatic path chose a Craig-Bampton model
            out[f"{label} {setting}: reduced"] = float(bool(decision["reduced"]))
    peer_runs = [] if cached is None else cached["runs"]
    for method in IVP_METHODS:
        for rtol in (bench.rtols[:2] if quick else bench.rtols):
            if cached is not None:
                err, wall = next((e, w) for m, r, e, w in peer_runs if m == method and r == rtol)
            else:
                sol, wall = best_of(repeat, lambda m=method, r=rtol: solve_ivp(
                    rhs, (0.0, t_end), y0, method=m, jac=jac, rtol=r,
                    atol=r * per_component, t_eval=times))
                err = float(np.max(np.abs(sol.y[probe] - ref))) / motion if sol.success \
                    else math.inf
                peer_runs.append((method, rtol, err, wall))
            runs[method].append((err, wall))
            out[f"{method} rtol={rtol:g}: error"] = err
            out[f"{method} rtol={rtol:g}: s"] = wall
    if peers_cache and cached is None:
        Path(peers_cache).write_text(json.dumps({"scales": list(scales),
                                                 "reference": ref.tolist(),
                                                 "runs": peer_runs}))
    for target in ACCURACIES:
        cost = {m: min((w for e, w in r if e <= target), default=math.inf)
                for m, r in runs.items()}
        fastest = min(IVP_METHODS, key=lambda m: cost[m])
        for method in IVP_METHODS:
            out[f"{method} cheapest at {target:g}: s"] = cost[method]
        for label in ("rotorsim", "rotorsim auto"):
            out[f"{label} cheapest at {target:g}: s"] = cost[label]
            # NaN: not reached with the settings tried (by rotorsim or by every peer)
            ratio = cost[fastest] / cost[label]
            out[f"{label} speed-up vs fastest ({fastest}) at {target:g}"] = \
                ratio if math.isfinite(ratio) and ratio > 0 else math.nan
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
                        help="5,000 steps; solve_ivp at its two loosest rtol, rotorsim's "
                             "automatic path at 1e-2..1e-4 only")
    parser.add_argument("--models", nargs="+", choices=sorted(MODELS), default=None)
    parser.add_argument("--repeat", type=int, default=3,
                        help="time every run (rotorsim's and solve_ivp's) this many times "
                             "and keep the least CPU time")
    parser.add_argument("--peers-cache", default=None,
                        help="JSON of the reference and solve_ivp runs, one model only: "
                             "read when it exists, else written (see equal_accuracy)")
    args = parser.parse_args(argv)
    n = 5_000 if args.quick else args.steps
    models = args.models or (["bench", "issue14"] if args.quick else list(MODELS))
    if args.peers_cache and len(models) != 1:
        parser.error("--peers-cache needs exactly one model")
    report = {**({"steps": steps(n)} if n > 0 else {}),
              **{f"accuracy {name}": equal_accuracy(MODELS[name], quick=args.quick,
                                                    peers_cache=args.peers_cache,
                                                    repeat=args.repeat)
                 for name in models},
              **({"memory": memory(2_000 if args.quick else 10_000)} if n > 0 else {})}
    for name, values in report.items():
        print(f"\n[{name}]")
        for key, value in values.items():
            print(f"  {key:52s} {value:.6g}")
    return report


if __name__ == "__main__":
    main()
