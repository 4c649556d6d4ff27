"""The critical-speed-vs-preload example runs and shows Hertz stiffening."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import critical_speed_vs_preload as example  # noqa: E402


def test_critical_speed_rises_with_load_and_preload(tmp_path):
    out = example.run(tmp_path, fast=True)
    speed_by_load, k_by_load = out["by_load"].T
    assert np.all(np.diff(speed_by_load) > 0) and np.all(np.diff(k_by_load) > 0)
    speed_by_clearance, k_by_clearance = out["by_clearance"].T  # clearance decreasing
    assert np.all(np.diff(k_by_clearance) >= -1e-9 * k_by_clearance.max())
    assert k_by_clearance[-1] > 2 * k_by_clearance[0]  # -5 um preload vs +10 um clearance
    assert speed_by_clearance[-1] > speed_by_clearance[0]
    assert (tmp_path / "critical_speed_vs_preload.png").stat().st_size > 5000
