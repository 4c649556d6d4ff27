"""The examples run (fast settings) and their numbers agree with independent checks."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import showcase  # noqa: E402


def test_showcase_runs_and_writes_every_figure(tmp_path):
    out = showcase.run(tmp_path, fast=True)
    for name in out["figures"]:
        assert (tmp_path / name).stat().st_size > 5000
    assert (tmp_path / "summary.txt").read_text().startswith("rotorsim")
    # damped critical speeds from the Campbell grid sit close to the undamped exact ones
    crit, exact = out["critical_speeds"], out["exact"]
    lateral = exact.speed[exact.kind == "lateral"]
    first = crit.speed[crit.whirl == "forward"][0]
    assert np.min(np.abs(lateral - first)) / first < 0.02
    # the unbalance peak is near the first forward critical speed
    peak_speed, _ = out["unbalance"].peak(4 if len(lateral) else 0, "ux")
    assert abs(peak_speed - first) / first < 0.05
