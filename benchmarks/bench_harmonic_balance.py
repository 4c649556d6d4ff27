"""Harmonic-balance performance against the issue 7 target (one core).

The test system has 100 DOFs (a sparse chain of 20 nodes x 5 DOFs with gyroscopic
coupling) and two nonlinear 5-DOF "bearings" (k = 10 nonlinear DOFs, dense 5 x 5 cubic
stiffness and velocity tangents), H = 10 harmonics, N = 128 samples. Prints:

* residual + analytic Jacobian of the condensed system at a fixed omega (target: well
  under 10 ms), with ``d/domega`` as well, and the first call at a new omega (which
  factorises the 11 linear blocks);
* the same on the full system (2100 unknowns, dense Jacobian) for comparison;
* one damped-Newton solve, and Floquet multipliers by Hsu's method (N = 128 steps).

Run: ``.venv/bin/python benchmarks/bench_harmonic_balance.py [--repeat N]``. Each time is
the best of ``N`` repetitions of a timed loop, so background load inflates it least.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core, as the target says

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402

from rotorsim.harmonic_balance.monodromy import hsu  # noqa: E402
from rotorsim.harmonic_balance.problem import HBProblem  # noqa: E402
from rotorsim.harmonic_balance.residual import make_residual  # noqa: E402
from rotorsim.harmonic_balance.solve import solve_point  # noqa: E402

TARGET_MS = 10.0
NODES, DOF = 20, 5
BEARING_NODES = (3, 16)
HARMONICS = 10


def chain_problem() -> HBProblem:
    """20 nodes x 5 DOFs on a spring chain, two nonlinear supports of 5 DOFs each."""
    n = NODES * DOF
    rng = np.random.default_rng(0)
    coupling = rng.standard_normal((DOF, DOF))
    k_node = 1e6 * (coupling @ coupling.T / DOF + np.eye(DOF))
    blocks = sp.lil_matrix((n, n))
    for i in range(NODES - 1):
        a, b = slice(DOF * i, DOF * i + DOF), slice(DOF * i + DOF, DOF * i + 2 * DOF)
        blocks[a, a] += k_node
        blocks[b, b] += k_node
        blocks[a, b] -= k_node
        blocks[b, a] -= k_node
    K = blocks.tocsr() + sp.identity(n, format="csr") * 1e4
    M = sp.diags(np.full(n, 2.0)).tocsr()
    C = 1e-4 * K + 5.0 * M
    G = sp.lil_matrix((n, n))
    for i in range(NODES):
        G[DOF * i + 3, DOF * i + 4], G[DOF * i + 4, DOF * i + 3] = 0.02, -0.02
    nl = np.concatenate([np.arange(DOF * b, DOF * b + DOF) for b in BEARING_NODES])
    k3 = 1e12 * np.eye(DOF) + 2e11 * np.ones((DOF, DOF))

    def bearings(q, v, tau, w, p):
        S = len(q)
        qb, vb = q.reshape(S, 2, DOF), v.reshape(S, 2, DOF)
        lin = np.einsum("ij,sbj->sbi", k3, qb**3)
        f = lin + 1e5 * qb + 50.0 * vb**3
        dq = np.zeros((S, 2, DOF, 2, DOF))
        dv = np.zeros((S, 2, DOF, 2, DOF))
        for b in range(2):
            dq[:, b, :, b, :] = k3[None] * 3 * qb[:, b, None, :] ** 2 + 1e5 * np.eye(DOF)
            dv[:, b, :, b, :] = 150.0 * vb[:, b, :, None] ** 2 * np.eye(DOF)
        k = 2 * DOF
        return f.reshape(S, k), dq.reshape(S, k, k), dv.reshape(S, k, k)

    shape = np.zeros(n)
    shape[DOF * 10] = shape[DOF * 10 + 1] = 1e-3

    def unbalance(w, p):
        F = np.zeros((3, n))
        F[1], F[2] = w**2 * shape, w**2 * np.roll(shape, 1)
        return F

    return HBProblem(M, K, C, G.tocsr(), nl_dofs=nl, force=bearings, excitation=unbalance,
                     spin_ratio=1.0)


def best_time(fun: Callable[[], object], loops: int, repeat: int) -> float:
    """Best mean wall time of one call [s] over ``repeat`` timed loops."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(loops):
            fun()
        best = min(best, (time.perf_counter() - t0) / loops)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    pb = chain_problem()
    cond = make_residual(pb, HARMONICS)
    full = make_residual(pb, HARMONICS, condense=False)
    w = 300.0
    x = 1e-6 * np.random.default_rng(1).standard_normal(cond.size)
    cond.evaluate(x, w)
    omegas = iter(w + 1e-3 * np.arange(1, 10_000))
    X = full.restrict(cond.expand(x, w))
    rows = [
        ("condensed: residual + Jacobian", lambda: cond.evaluate(x, w), 50),
        ("condensed: + d/domega", lambda: cond.evaluate(x, w, d_omega=True), 50),
        ("condensed: residual only", lambda: cond.evaluate(x, w, jacobian=False), 50),
        ("condensed: new omega (11 factorisations)",
         lambda: cond.evaluate(x, next(omegas)), 10),
        ("full (2100 unknowns): residual + Jacobian", lambda: full.evaluate(X, w), 3),
    ]
    print(f"n = {pb.n}, k = {pb.k}, H = {HARMONICS}, N = {cond.samples}, condensed unknowns "
          f"{cond.size}, full unknowns {full.size}")
    print(f"{'operation':48s} {'ms':>9s} {'evaluations/s':>14s}")
    for name, fun, loops in rows:
        t = best_time(fun, loops, args.repeat)
        print(f"{name:48s} {1e3 * t:9.3f} {1.0 / t:14.0f}")
    t_eval = best_time(lambda: cond.evaluate(x, w), 50, args.repeat)
    verdict = "met" if 1e3 * t_eval < TARGET_MS else "MISSED"
    print(f"target: condensed residual + Jacobian < {TARGET_MS:.0f} ms -> {verdict} "
          f"({TARGET_MS / (1e3 * t_eval):.0f}x margin)")
    t0 = time.perf_counter()
    sol = solve_point(cond, w, x_scale=1e-5)
    t_solve = time.perf_counter() - t0
    print(f"solve_point from zero: {1e3 * t_solve:.1f} ms, {sol.stats['iterations']:.0f} "
          f"iterations, {sol.stats['factorizations']:.0f} factorisations")
    t_hsu = best_time(lambda: hsu(cond, sol.x, w), 1, args.repeat)
    print(f"hsu (N = {cond.samples} steps, 200 x 200 state matrices): {1e3 * t_hsu:.1f} ms")


if __name__ == "__main__":
    main()
