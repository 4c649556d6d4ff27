"""Issue 16: a block (subspace) iteration on the period map next to the clearance rotor's
axial pitchforks (353.12-353.73 rad/s).

Traces ``models/clearance_rotor.toml`` from 300 to 360 rad/s (``H = 8``, all nodes), then
at each requested speed iterates ``PERIODS`` periods of the full model's period map
(``PeriodMap``, average acceleration, ``T / 200``), linearised at the HB state by finite
differences, on a block of 4 vectors (the rigid translations ``uz``, ``ux``, ``uy`` and
``verify_events``' own perturbation, or random ones with ``--random``), in the energy norm
``q^T (K + W^2 M) q + v^T M v`` over all free DOFs but the torsion. Prints the moduli of the
Ritz values every 4 periods. docs/validation.md, case 26 addendum "a block iteration on
the axial pitchforks", has the numbers. About 15 s of CPU per speed plus the branch.

Run: ``.venv/bin/python scripts/check_axial_pitchfork_block.py [--random] 353.43 352.6 354.3``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402
from rotorsim.verification.period_map import PeriodMap  # noqa: E402
from rotorsim.verification.periodic_events import (  # noqa: E402
    _excitation,
    _perturbation,
    _system,
)

BLOCK = 4
PERIODS = 24


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("speeds", nargs="+", type=float, help="speeds [rad/s]")
    parser.add_argument("--random", action="store_true", help="random start vectors")
    args = parser.parse_args()
    model = rs.load_model(ROOT / "models" / "clearance_rotor.toml")
    branch = rs.periodic(model, start=300.0, stop=360.0, harmonics=8,
                         unbalance=[(10, 1e-4, 0.0)], nodes=None)
    assert isinstance(branch, rs.PeriodicResult)    # fixed cages: a periodic problem
    system = _system(model)
    for speed in args.speeds:
        block_iteration(branch, system, int(np.argmin(np.abs(branch.parameter - speed))),
                        args.random)


def block_iteration(branch: rs.PeriodicResult, system: rs.RotorSystem, i: int,
                    random: bool) -> None:
    """Ritz values of the linearised period map at branch point ``i`` (module docstring)."""
    free, ndof = system.dof_map.free, system.dof_map.ndof
    keep = free[free % 6 != 5]                     # every free DOF but the torsion
    pos = np.searchsorted(free, keep)
    W = float(branch.speed[i])
    m = system.matrices(W)
    M = m.M.toarray()[np.ix_(pos, pos)]
    G = np.linalg.cholesky(m.K.toarray()[np.ix_(pos, pos)] + W**2 * M)
    L = np.linalg.cholesky(M)
    n = keep.size

    def weigh(dq: np.ndarray, dv: np.ndarray) -> np.ndarray:
        return np.concatenate([G.T @ dq[keep], L.T @ dv[keep]])

    def unweigh(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        dq, dv = np.zeros(ndof), np.zeros(ndof)
        dq[keep], dv[keep] = np.linalg.solve(G.T, y[:n]), np.linalg.solve(L.T, y[n:])
        return dq, dv

    rng = np.random.default_rng(1)
    if random:
        starts = list(rng.standard_normal((BLOCK, 2 * n)))
    else:
        starts = []
        for component in (2, 0, 1):                # rigid translations uz, ux, uy
            dq = np.zeros(ndof)
            dq[component::6] = 1.0
            starts.append(weigh(dq, np.zeros(ndof)))
        starts.append(weigh(*_perturbation(branch, i, 1e-3)))
    pm = PeriodMap(system, W, 2 * np.pi / W, _excitation(branch),
                   float(branch.options["shaft_angle"]), 200)
    q0, v0 = branch.state(i)
    qb, vb = pm.flow(q0, v0, 1)
    step = 1e-6 * float(np.linalg.norm(weigh(q0, v0)))
    Q = np.linalg.qr(np.array(starts).T)[0]
    for k in range(PERIODS):
        Y = np.empty_like(Q)
        for c in range(BLOCK):
            dq, dv = unweigh(Q[:, c])
            qp, vp = pm.flow(q0 + step * dq, v0 + step * dv, 1)
            Y[:, c] = weigh(qp[1] - qb[1], vp[1] - vb[1]) / step
        ritz = np.linalg.eigvals(Q.T @ Y)
        Q = np.linalg.qr(Y)[0]
        if k % 4 == 3:
            print(f"{W:.3f} rad/s, {k + 1} periods: |Ritz| "
                  f"{np.round(np.sort(np.abs(ritz))[::-1], 4)}", flush=True)
    print(f"{W:.3f} rad/s (point {i}): Floquet max |mu| "
          f"{float(np.abs(branch.multipliers[i][0])):.4f}")


if __name__ == "__main__":
    main()
