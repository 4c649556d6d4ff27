"""What the textbook rigid rotor does where its torus is unstable, checked independently
of the variational equation (docs/validation.md, case 36 second addendum; issue 17).

For each speed: ``rs.motion_beyond`` (spectral order and the trajectory's Lyapunov exponent
from the variational equation), then an independent estimate of the largest Lyapunov
exponent from two trajectories of ``rs.transient`` alone (Benettin et al. 1980 with finite
separations): after the same settling, a copy of the state displaced by 1e-9 of the motion
in a random direction is integrated beside it, one revolution at a time, and renormalised
to that distance after each revolution. The growth rates per revolution are averaged.

Cases: the first unstable torus past the fold near 637 rad/s (the branch of
``tests/analyses/test_quasi_periodic_rotor.py``), and 1000 rad/s (a doubled torus).

Run: ``OPENBLAS_NUM_THREADS=1 python scripts/check_motion_beyond.py`` (about 3 minutes).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests" / "analyses"))

import rotorsim as rs  # noqa: E402
from test_quasi_periodic_rotor import _textbook_damped  # noqa: E402

UNBALANCE = [(0, 2e-6, 0.0)]
SETTLE, RECORD, STEPS = 80, 120, 256


def two_trajectories(system, point, ex, revolutions: int = 30, seed: int = 1) -> float:
    """Largest Lyapunov exponent [1/s] from two ``rs.transient`` trajectories."""
    w = float(point.speed)
    rev = 2 * np.pi / w
    dt = rev / STEPS
    q0, v0 = point.state(0.0)
    active = point.system.dof_map.free[point.rotor_problem.active]
    rng = np.random.default_rng(seed)
    size = float(np.abs(point.solution.X[1:]).sum(axis=0).max())
    q0[active] += 1e-3 * size * rng.uniform(-1.0, 1.0, active.size)
    kw = dict(speed=w, unbalance=UNBALANCE, excitation=ex, method="average_acceleration")
    a = rs.transient(system, SETTLE * rev, dt, initial=(q0, v0), **kw)
    free = a.dof_map.free
    delta = 1e-9 * size
    direction = rng.standard_normal(2 * free.size)
    logs = []
    for _ in range(revolutions):
        qa, va, t0 = a.final.q, a.final.v, a.final.t
        step = delta * direction / np.linalg.norm(direction)
        qb, vb = np.zeros(a.dof_map.ndof), np.zeros(a.dof_map.ndof)
        qb[free], vb[free] = qa + step[:free.size], va + w * step[free.size:]
        b = rs.transient(system, (t0, t0 + rev), dt, initial=(qb, vb), **kw)
        a = rs.transient(system, (t0, t0 + rev), dt, initial=a, **kw)
        diff = np.concatenate([b.final.q - a.final.q, (b.final.v - a.final.v) / w])
        logs.append(np.log(np.linalg.norm(diff) / delta))
        direction = diff
    return float(np.mean(logs)) / rev


def main() -> None:
    rotor, ex = _textbook_damped()
    system = rs.assemble(rotor)
    res = rs.periodic(rotor, start=600.0, stop=800.0, harmonics=8, unbalance=UNBALANCE,
                      excitation=ex, continuation=rs.ContinuationOptions(max_points=12),
                      stability=rs.StabilityOptions(beyond=0))
    (event,) = [e for e in res.events if e.kind == "loss_of_stability"]
    fold_speed = float(res.speed[event.index + 1])
    branch = rs.quasi_periodic(rotor, start=600.0, stop=800.0, step=10.0,
                               unbalance=UNBALANCE, harmonics=(8, 3), excitation=ex,
                               stability=False, max_points=12, beyond=None)
    fold_point = branch.points[event.index + 1]      # the same branch, point for point
    assert abs(fold_point.speed - fold_speed) < 1e-6 * fold_speed
    doubled = rs.quasi_periodic_point(rotor, 1000.0, unbalance=UNBALANCE, excitation=ex,
                                      harmonics=(12, 4), truncation="box")
    for label, point in (("past the fold", fold_point), ("1000 rad/s", doubled)):
        clock = time.process_time()
        motion = rs.motion_beyond(point, UNBALANCE, ex, settle=SETTLE, record=RECORD)
        reference = two_trajectories(system, point, ex)
        print(f"{label}, {point.speed:.4f} rad/s: {motion.summary()}\n"
              f"  two rs.transient trajectories: {reference:.4g} 1/s "
              f"({time.process_time() - clock:.0f} s CPU)")


if __name__ == "__main__":
    main()
