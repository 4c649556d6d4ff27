"""What the textbook rigid rotor does where its torus is unstable, checked independently
of the variational equation (docs/validation.md, case 36 second addendum; issue 17).

For each speed: ``rs.motion_beyond`` (spectral order, and the largest Lyapunov exponent
from the growth of its distance to a twin), then a repeat of the exponent with
``rs.transient`` alone, from another random start and perturbation (``two_trajectories``).
The variational estimate along the record, the method the twin replaced, is recorded in
docs/validation.md beside them.

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

from test_quasi_periodic_rotor import _textbook_damped  # noqa: E402

import rotorsim as rs  # noqa: E402

UNBALANCE = [(0, 2e-6, 0.0)]
SETTLE, RECORD, STEPS = 80, 120, 256


def two_trajectories(system, point, ex, revolutions: int = 40, seed: int = 1) -> float:
    """Largest Lyapunov exponent [1/s] from the separation of two ``rs.transient``
    trajectories: after the same settling, both restart from arrays at the same time (so
    that any difference is the perturbation's), one displaced by 1e-9 of the motion in a
    random direction; the slope of ``ln`` of their distance (displacements and velocities
    over ``W``) against time, fitted where the distance has grown 100-fold from the start
    but is still below 1e-2 of the motion (past the alignment, before saturation)."""
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
    final = a.final
    assert final is not None
    free, t0 = a.dof_map.free, final.t
    qa, va = np.zeros(a.dof_map.ndof), np.zeros(a.dof_map.ndof)
    qa[free], va[free] = final.q, final.v
    qb = qa.copy()
    qb[free] += 1e-9 * size * rng.standard_normal(free.size)
    times = t0 + rev * np.arange(revolutions + 1)
    out = rs.Output(times=times, velocities=True)
    runs = [rs.transient(system, (t0, times[-1]), dt, initial=(q, va), output=out, **kw)
            for q in (qa, qb)]
    va_run, vb_run = runs[0].v, runs[1].v
    assert va_run is not None and vb_run is not None
    d = np.sqrt(((runs[0].q - runs[1].q) ** 2).sum(axis=1)
                + ((va_run - vb_run) ** 2).sum(axis=1) / w ** 2)
    window = (d > 100 * d[0]) & (d < 1e-2 * size)
    if window.sum() < 3:                    # no growth: the slope over the whole run
        window = np.ones(d.size, dtype=bool)
    return float(np.polyfit(times[window], np.log(d[window]), 1)[0])


def main() -> None:
    rotor, ex = _textbook_damped()
    system = rs.assemble(rotor)
    branch = rs.quasi_periodic(rotor, start=600.0, stop=800.0, step=10.0,
                               unbalance=UNBALANCE, harmonics=(8, 3), excitation=ex,
                               max_points=12, beyond=None)
    stable = branch.stable
    first = int(np.flatnonzero(stable[:-1] & ~stable[1:])[0]) + 1   # first unstable torus
    fold_point = branch.points[first]
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
