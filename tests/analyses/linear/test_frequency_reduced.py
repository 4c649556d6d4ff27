"""Long unbalance sweeps of large models on a basis of direct solutions (issue 15), against
the direct solve at every point.

Tolerance: every point's relative residual ``||P^-1 r|| / ||x||`` is below 1e-9; near a
resonance the error in the response can exceed it by the dynamic amplification (up to a
few hundred for these damped rotors). Measured: 1.4e-9 of the peak on the benchmark rotor,
1.3e-7 on the 5,000-DOF machine (docs/benchmarks.md); the test allows 1e-6 of the peak.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
import rotorsim.analyses.linear.frequency_response as fr

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "benchmarks"))
from bench_model import benchmark_description, build_rotorsim, unbalance_list  # noqa: E402

PEAK_RTOL = 1e-6


def _both(monkeypatch: pytest.MonkeyPatch, system, speeds, unbalance):
    reduced = rs.unbalance_response(system, speeds, unbalance)
    monkeypatch.setattr(fr, "REDUCED_MIN_DOFS", 10**9)
    direct = rs.unbalance_response(system, speeds, unbalance)
    return reduced, direct


def test_reduced_sweep_equals_direct_on_the_benchmark_rotor(
        monkeypatch: pytest.MonkeyPatch) -> None:
    desc = benchmark_description(100)
    speeds = np.linspace(0.0, 1200.0, 120)  # includes W = 0 (zero load, zero response)
    reduced, direct = _both(monkeypatch, rs.assemble(build_rotorsim(desc)), speeds,
                            unbalance_list(desc))
    assert reduced.options["method"] == "reduced" and direct.options["method"] == "direct"
    assert reduced.stats["direct_solves"] < 30 and reduced.stats["max_residual"] <= 1e-9
    peak = np.abs(direct.response).max()
    np.testing.assert_allclose(reduced.response, direct.response, rtol=0,
                               atol=PEAK_RTOL * peak)
    assert np.all(reduced.response[0] == 0)


def test_reduced_sweep_keeps_each_spools_part(monkeypatch: pytest.MonkeyPatch) -> None:
    model = rs.load_model(ROOT / "models" / "two_spool.toml")
    system = rs.assemble(model.rotor)
    monkeypatch.setattr(fr, "REDUCED_MIN_DOFS", 100)  # the example has 270 free DOFs
    reduced, direct = _both(monkeypatch, system, np.linspace(10.0, 1500.0, 150),
                            model.loads.unbalance)
    assert reduced.options["method"] == "reduced"
    assert reduced.response.shape[2] == 2  # one column per spool
    peak = np.abs(direct.response).max(axis=(0, 1))
    np.testing.assert_allclose(np.abs(reduced.response - direct.response).max(axis=(0, 1))
                               / peak, 0.0, atol=PEAK_RTOL)
