"""examples/seed002_periodic.py runs (fast settings) and shows what it claims: the seed's
undamped rigid rotor on a cylindrical roller bearing at 1000 rad/s is neutrally ("critically",
seed 002) stable with Hill and Hsu agreeing, its mean deflection is the static one, and the
swept studies reach their end."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import rotorsim as rs  # noqa: E402
from examples import seed002_periodic as seed  # noqa: E402


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    return seed.main(fast=True, outdir=tmp_path_factory.mktemp("seed002"))


def test_figures_are_written(out):
    assert len(out["figures"]) == 4


def test_point_at_1000_rads(out):
    p = out["point_1000"]
    assert p["order"] == pytest.approx(12 * seed.RollerBearing(**seed.BEARING).kappa)
    assert sorted(p["held"]) == [2, 5]                 # axial and torsional motion held
    # undamped: all 8 multipliers on the unit circle (seed: "critically stable")
    assert abs(p["max_modulus_hill"] - 1) < 1e-9 and abs(p["max_modulus_hsu"] - 1) < 1e-9
    assert p["hill_hsu_difference"] < 1e-3            # Hsu, N = 128 steps: O(1/N^2)
    static = rs.static(seed.seed_rotor()).displacement[1]
    assert p["mean_y"] == pytest.approx(static, rel=1e-3)   # VC shifts the mean a little
    assert p["y_harmonics"][1] < 1e-2 * abs(p["mean_y"])  # VC vibration << static sag
    assert np.all(np.diff(np.log(p["y_harmonics"][1:6])) < 0)   # harmonics decay


def test_sweeps_reach_their_end(out):
    for name, numbers in out["summaries"].items():
        assert numbers["reached"] == pytest.approx(400.0), name
    assert out["summaries"]["k1_a1mm"]["peak_ptp_y"] > 5 * out["summaries"]["k1_a01mm"][
        "peak_ptp_y"]                                   # ten times the housing motion
