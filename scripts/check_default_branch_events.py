"""Issue 16: the events of the default model's periodic branch checked by time integration.

The default model's ``branch`` analysis is quasi-periodic (the balls move); its events
can be checked by ``rs.verify_events`` only on a periodic branch whose transient keeps
nothing the branch neglects. So the balls are held (``cage = "fixed"`` on both bearings,
as in ``models/clearance_rotor.toml``) and the analysis's branch (500-2500 rpm, H = 6,
Floquet stability, all nodes kept) is traced and checked along each event's critical
Floquet mode. docs/validation.md, case 26 addendum "the default model's branch", has the
numbers. About 20 minutes on one core: the free transients take one, shooting on the full
model the rest (its trace through the cluster of folds at 1079-1085 rpm, about 240 points
of shooting continuation, most of it).

Run: ``.venv/bin/python scripts/check_default_branch_events.py``.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402

RPM = np.pi / 30


def held_cages_model() -> rs.Model:
    """``models/default.toml`` with both bearings' balls held in place."""
    text = (ROOT / "models" / "default.toml").read_text()
    held = text.replace('radial_clearance = "5 um"', 'radial_clearance = "5 um"\ncage = "fixed"')
    assert held.count('cage = "fixed"') == 2, "the default model's bearings changed"
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "default_held.toml"
        path.write_text(held)
        return rs.load_model(path)


def main() -> None:
    model = held_cages_model()
    spec: Any = model.analyses["branch"]       # a PeriodicSpec
    res = rs.periodic(model, start=spec.start, stop=spec.stop, harmonics=spec.harmonics,
                      unbalance=list(model.loads.unbalance), nodes=None,
                      continuation=spec.continuation, stability="auto")
    assert isinstance(res, rs.PeriodicResult)    # the balls held: a periodic branch
    print(f"{len(res)} points, {res.reason}")
    for b in res.bifurcations:
        print(f"  {b.kind:16s} {b.parameter / RPM:9.2f} rpm ({b.parameter:.3f} rad/s)")
    for u in res.unresolved:
        print(f"  unresolved {u.kind} {u.parameter / RPM:.2f} rpm: {u.method}")
    print("free transients along the critical Floquet mode (measure='floquet'):")
    print(rs.verify_events(model, res, measure="floquet").summary())
    clock = time.process_time()
    checked = rs.verify_events(model, res, measure="shooting", trace=True)
    print(f"shooting on the full model, the rest traced (measure='shooting', trace=True; "
          f"{time.process_time() - clock:.0f} s CPU):")
    print(checked.summary())
    print(f"{sum(c.confirmed for c in checked.checks)} of {len(checked)} confirmed")


if __name__ == "__main__":
    main()
