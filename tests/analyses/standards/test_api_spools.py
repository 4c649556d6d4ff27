"""API unbalance checks of one spool of a machine of several lines (``spool=``).

Closed form: two rigid disks on their own lines, each on an isotropic spring and damper
to ground, uncoupled; line B turns 1.5 times as fast as line A. B's unbalance excites at
B's own speed, so in B's speeds its resonance is that of a single-DOF rotor: peak at
``wn_B / sqrt(1 - 2 zeta^2)`` and the half-power AF of the closed form in
test_api_unbalance.py, whatever the speed ratio. Line A is not excited at all.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.standards.api_formulas import residual_unbalance

MODELS = Path(__file__).resolve().parents[3] / "models"
RPM = math.pi / 30.0
M_A, K_A, M_B, K_B, ZETA = 80.0, 2e7, 50.0, 5e6, 0.05


def _exact_af(zeta: float) -> float:
    """Half-power AF of the single-DOF unbalance response (test_api_unbalance.py)."""
    root = 2 * zeta * math.sqrt(1 - zeta**2)
    s_peak, s_low, s_high = 1 - 2 * zeta**2, 1 - 2 * zeta**2 + root, 1 - 2 * zeta**2 - root
    return s_peak**-0.5 / (s_high**-0.5 - s_low**-0.5)


def _machine(ratio_b: float = 1.5) -> rs.Rotor:
    lines = [rs.ShaftLine("A", [], z0=0.0), rs.ShaftLine("B", [], z0=1.0, speed_ratio=ratio_b)]
    disks = [rs.DiskElement(n=0, m=M_A, Id=0.01, Ip=0.02, tag="dA"),
             rs.DiskElement(n=1, m=M_B, Id=0.01, Ip=0.02, tag="dB")]
    bearings = [rs.BearingElement(n=n, kxx=k, cxx=2 * ZETA * math.sqrt(k * m), tag=f"b{n}")
                for n, (m, k) in enumerate(((M_A, K_A), (M_B, K_B)))]
    rotor = rs.Rotor([], disks, bearings, lines=lines)
    return rotor.with_fixed([(n, d) for n in (0, 1) for d in ("uz", "rx", "ry", "rz")])


def test_spool_check_is_the_single_dof_closed_form_in_its_own_speeds():
    wn = math.sqrt(K_B / M_B)
    speeds = np.linspace(0.1, 2.5, 241) * wn          # B's own speeds
    r = rs.api_unbalance(_machine(), speeds, min_speed=1.6 * wn, mcs=2.0 * wn,
                         num_modes=1, spool="B")
    assert r.num_modes == 1 and r.unbalance_node.tolist() == [1]
    assert r.options["spool"] == "B" and r.options["speed_ratio"] == 1.5
    # the refined half-power band: same tolerances as the one-line check (1e-6)
    assert r.af[0] == pytest.approx(_exact_af(ZETA), rel=1e-6)
    assert r.peak_speed[0] == pytest.approx(wn / math.sqrt(1 - 2 * ZETA**2), rel=1e-6)
    assert r.mode_speed[0] == pytest.approx(wn, rel=2e-3)  # Campbell crossing, 41 speeds
    assert r.probe_nodes.tolist() == [1]                 # B's bearing
    u = residual_unbalance(M_B, 2.0 * wn / RPM)[0]       # W: B's mass, N: B's MCS
    assert r.unbalance_magnitude[0] == pytest.approx(u, rel=1e-14)
    assert np.all(r.major_pp[0][:, 0] == 0.0)            # line A is not excited
    assert r.margin_ok[0] and r.passed


def test_the_same_spool_alone_gives_the_same_check():
    """Uncoupled lines: B checked in the machine equals B as a rotor of its own."""
    wn = math.sqrt(K_B / M_B)
    speeds = np.linspace(0.1, 2.5, 121) * wn
    alone = rs.Rotor([], [rs.DiskElement(n=0, m=M_B, Id=0.01, Ip=0.02)], [
        rs.BearingElement(n=0, kxx=K_B, cxx=2 * ZETA * math.sqrt(K_B * M_B))])
    alone = alone.with_fixed([(0, d) for d in ("uz", "rx", "ry", "rz")])
    kw = dict(min_speed=1.6 * wn, mcs=2.0 * wn, num_modes=1)
    one = rs.api_unbalance(alone, speeds, **kw)
    spool = rs.api_unbalance(_machine(), speeds, spool="B", **kw)
    for key in ("af", "peak_speed", "half_power_low", "half_power_high", "actual_margin"):
        np.testing.assert_allclose(getattr(spool, key), getattr(one, key), rtol=1e-9)


@pytest.mark.parametrize(("spool", "ratio", "match"), [
    (None, 1.5, "name the spool"), ("C", 1.5, "C"), ("B", 0.0, "does not rotate"),
    ("B", -1.5, "turns against the reference")])
def test_spool_refusals_are_named(spool, ratio, match):
    wn = math.sqrt(K_B / M_B)
    with pytest.raises(rs.ModelError, match=match):
        rs.api_unbalance(_machine(ratio), np.linspace(0.1, 2.5, 41) * wn, min_speed=wn,
                         mcs=1.2 * wn, spool=spool)


def test_two_spool_model_file_checks_a_spool_in_the_report(tmp_path):
    """models/two_spool.toml with an ``api_unbalance`` analysis of its HP spool (1.45 times
    the reference speed): the model file, the runner and ``rotorsim report`` check the
    spool in its own speeds, with anti-nodes and probes on it, and the page lists the
    lines (coarse grid: the point is the per-spool path; the LP spool goes the same way)."""
    import tomllib
    import xml.etree.ElementTree as ET

    from rotorsim.io.model import model_from_dict
    from rotorsim.report.build import write_report

    data = tomllib.loads((MODELS / "two_spool.toml").read_text())
    data["analyses"] = {"api_hp": {
        "type": "api_unbalance", "speeds": {"start": "100 rpm", "stop": "21000 rpm",
                                            "num": 41},
        "min_speed": "9000 rpm", "mcs": "16000 rpm", "num_modes": 1, "spool": "HP"}}
    model = model_from_dict(data, source=MODELS / "two_spool.toml")
    html = write_report(model, tmp_path, plots=False)
    r = rs.load(html.parent / "report.h5")["api_hp"]
    layout = model.rotor.layout
    i = layout.index("HP")
    on_spool = range(int(layout.first_node[i]), int(layout.first_node[i]) + 9)
    assert r.options["spool"] == "HP" and r.mcs == pytest.approx(16000 * RPM)
    assert all(int(n) in on_spool for n in (*r.unbalance_node, *r.probe_nodes))
    assert np.isfinite(r.af[0]) and r.af[0] > 2.5
    text = "".join(ET.fromstring(html.read_text().split("\n", 1)[1]).itertext())
    assert "spool HP (speed ratio 1.45)" in text
    assert all(name in text for name in ("LP", "HP", "casing", "not rotating"))
    with pytest.raises(rs.ModelError, match="does not rotate"):
        rs.api_unbalance(model.rotor, np.linspace(10.0, 1500.0, 20), min_speed=500.0,
                         mcs=600.0, spool="casing")
