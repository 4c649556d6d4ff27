"""Issue 16: the period doubling of the default model's branch checked by time integration.

Traces ``models/default.toml``'s ``branch`` analysis with all nodes kept, then at the point
with the most negative Floquet multiplier (1082.76 rpm, Hsu -1.4468) integrates the full
model (``PeriodMap``, average acceleration, ``T / 400``): the HB orbit's closure after 3
periods, and 16 periods of power iteration on the period map linearised by finite
differences from a seeded random displacement of every free DOF. docs/validation.md, case
26 addendum, has the numbers (-1.405). About 3 minutes on one core.

Run: ``.venv/bin/python scripts/check_default_period_doubling.py``.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402
from rotorsim.io import analysis_runners as ar  # noqa: E402
from rotorsim.verification.period_map import PeriodMap, linearised_growth  # noqa: E402
from rotorsim.verification.periodic_events import _excitation, _system  # noqa: E402


def main() -> None:
    model = rs.load_model(ROOT / "models" / "default.toml")
    spec = dataclasses.replace(model.analyses["branch"], nodes=None)
    rotor = model.rotor.with_nonlinear(model.rolling_bearings)
    r = ar._periodic(rotor, model, spec, False, False, rs.Checkpointing())
    i = int(np.argmin(np.min(r.multipliers.real, axis=1)))
    system = _system(rotor)
    pm = PeriodMap(system, float(r.speed[i]), 2 * np.pi / float(r.fundamental[i]),
                   _excitation(r), 0.0, 400)
    q0, v0 = r.state(i, 0.0)
    qs, _ = pm.flow(q0, v0, 3)
    closure = float(np.max(np.abs(qs[-1] - q0)))
    dq = np.zeros_like(q0)
    free = system.dof_map.free
    dq[free] = np.random.default_rng(1).standard_normal(free.size) * 1e-8
    g = linearised_growth(pm, q0, v0, (dq, np.zeros_like(q0)), 16)
    mu = r.multipliers[i][np.argsort(-np.abs(r.multipliers[i]))][0]
    print(f"point {i}, {r.speed[i] * 30 / np.pi:.3f} rpm: Floquet {mu:.4f}; orbit closure "
          f"after 3 periods {closure * 1e6:.3f} um (peak-to-peak "
          f"{r.peak_to_peak[i].max() * 1e6:.0f} um); period map dominant "
          f"{np.round(g.multipliers, 4)}")


if __name__ == "__main__":
    main()
