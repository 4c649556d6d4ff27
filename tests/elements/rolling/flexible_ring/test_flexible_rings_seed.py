"""examples/seed001_flexible_rings.py: seed 001 section 3.1 and 3.3 (fast settings)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[4]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import seed001_flexible_rings as seed  # noqa: E402


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    out_dir = tmp_path_factory.mktemp("seed001")
    return seed.main(fast=True, outdir=out_dir), out_dir


def test_example_runs_and_writes_its_figures(result):
    out, out_dir = result
    assert out["figures"] == ["fig5_roller_loads.png", "fig8_misalignment.png"]
    for name in out["figures"]:
        assert (out_dir / name).stat().st_size > 10000
    for d in out["distributions"].values():
        for model in ("rigid", "flexible"):
            q = d[model]["inner_load"]
            assert q.shape == (24,) and q.argmax() == seed.MOST_LOADED - 1
    # seed 001 section 3.1 target: one static solve of the seed case in < 50 ms
    assert out["solve_time"] < 0.5  # generous here (shared CI machines); see benchmarks
    assert "ratio" in seed._report(out)
    # the 2D ring FE of rotorsim.verification enters the comparison whenever it exists
    assert out["fe_available"] == (importlib.util.find_spec("rotorsim.verification.ring_fe")
                                   is not None)


@pytest.mark.validation
def test_preload_rigid_rings_carry_about_2_5_times_the_flexible_ring_loads(result):
    """Seed 001 section 3.1: with g = -40 um rigid rings give contact forces "2.5 higher"
    than flexible rings (printed to two digits: accepted range [2.45, 2.55]). The purely
    structural effect (no roller centrifugal force) is compared: the seed does not give
    the roller mass that its eq 18 needs at speed."""
    assert 2.45 <= result[0]["numbers"]["preload_ratio_at_rest"] <= 2.55


@pytest.mark.validation
def test_preload_rigid_rings_carry_about_2_5_times_the_ring_fe_loads(result):
    """The same seed figure at 12000 rpm against the 2D ring FE (the counterpart of the
    seed's NX Nastran model, which the seed finds "very close" to its flexible rings)."""
    pytest.importorskip("rotorsim.verification.ring_fe")
    assert 2.45 <= result[0]["numbers"]["preload_rigid_fe_ratio"] <= 2.55


def test_regression_preload_ratio_at_speed(result):
    """Regression value, not a reference: at 12000 rpm the simplified ring model gives
    rigid / flexible = 2.630803 (5 % above the seed's 2.5; the roller mass of eq 18 is
    not in the seed, docs/flexible_rings.md). Useful because the at-rest ratio above does
    not see the rollers' centrifugal force: this pins its coupling with the ring
    flexibility. Tolerance 1e-6 relative: the equilibria are solved to a residual of
    1e-10 of the load, so round-off and BLAS differences stay below 1e-8, while any
    change of the model moves the ratio by far more."""
    assert result[0]["numbers"]["preload_ratio"] == pytest.approx(2.630803, rel=1e-6)


@pytest.mark.validation
def test_positive_clearance_flexibility_matters_less(result):
    """Seed 001 section 3.1 (Fig. 5b): with g = +10 um the rings' flexibility matters less
    than with preload."""
    num = result[0]["numbers"]
    assert 1.0 < num["clearance_ratio"] < num["preload_ratio"]


@pytest.mark.validation
def test_positive_clearance_the_fe_shows_more_flexibility_than_the_ring_model(result):
    """Seed 001 section 3.1 (Fig. 5b): at g = +10 um the reference FE gives a larger
    reduction than the simplified ring model ("performs worse if the bearing operates with
    positive clearance"); with preload the simplified model is the closer one."""
    pytest.importorskip("rotorsim.verification.ring_fe")
    num = result[0]["numbers"]
    assert num["clearance_fe_max"] < num["clearance_flexible_max"] < num["clearance_rigid_max"]
    assert abs(num["clearance_fe_max_error"]) > abs(num["preload_fe_max_error"])


@pytest.mark.validation
def test_misalignment_leaves_the_radial_forces_and_balances_the_roller(result):
    """Seed 001 section 3.3: M_y = 13.7 N m "does not change the distribution of the radial
    forces" but the load along the roller. To first order a tilt shifts load between the
    slices and leaves the roller sum unchanged; the second-order change of
    ``sum (1 + e x)^n`` is ``n (n-1)/2 e^2 <x^2>`` ~ 5e-4 for the measured ``e`` ~ 0.17,
    hence the bound 1e-3."""
    mis = result[0]["misalignment"]
    assert mis["load_change"] < 1e-3
    s = mis["positions"]
    inner, outer = mis["inner_slices"], mis["outer_slices"]
    assert np.all(np.diff(inner) > 0) and np.all(np.diff(outer) > 0)  # tilted by M_y > 0
    # roller equilibrium (eq 20, second row): equal contact moments about its centre
    assert abs(inner @ s - outer @ s) <= 1e-9 * abs(inner @ s)
    # and the outer contact carries the inner load plus the centrifugal force (eq 20, row 1)
    fc = seed.seed_bearing(-40e-6).mass * (0.5 * (1 - 6.5 / 75) * seed.SPEED) ** 2 * 75e-3
    assert outer.sum() - inner.sum() == pytest.approx(fc, rel=1e-3)
