"""examples/seed000_load_cases.py runs (fast settings) and reproduces what it claims."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import seed000_load_cases as seed  # noqa: E402


def test_seed000_example_runs_and_writes_its_figures(tmp_path):
    out = seed.main(fast=True, out=tmp_path)
    assert len(out["figures"]) == 5
    for name in out["figures"]:
        assert (tmp_path / name).stat().st_size > 10000
    # the three methods agree on every load case (scaled displacement, relative)
    assert max(out["agreement"].values()) < 1e-8
    assert abs(out["case_v_40deg"]["x_mm"] - 2.2916) <= 5e-5  # seed 000 section 4
    assert "physical range" in out["case_v_40deg"]["default_range_error"]
    for case, s in out["sweeps"].items():
        assert s["displacement"].shape == (len(seed.contact_angles(case, True)), 5)
        assert np.all(np.isfinite(s["stiffness"]))
    assert out["sweeps"]["vi"]["held"] == [("z",)]
    assert out["sweeps"]["iv"]["held"][-1] == ("x", "y")  # thrust bearing at 90 deg
    vi = out["case_vi"]
    assert vi.displacement.shape == (12, 5) and np.all(vi.max_element_load > 0)
    assert "case (v) at 40 deg: x = 2.2916 mm" in seed._report(out)
