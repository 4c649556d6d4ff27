"""API unbalance response analysis: the half-power amplification factor of a single-DOF
rotor against its closed form, the separation margins and clearance ratios worked by hand
from the result's own peak data, and the errors on bad input.

Closed form. A disk of mass m on an isotropic spring k and damper c, unbalance ``me``:
the orbit is a forward circle of radius ``(me/m) r^2 / |1 - r^2 + 2 i zeta r|``, ``r = W /
wn``. With ``s = 1 / r^2`` the squared radius is ``(me/m)^2 / ((s - 1)^2 + 4 zeta^2 s)``:
its peak is at ``s_p = 1 - 2 zeta^2`` and it falls to half the peak value at ``s_+-
= (1 - 2 zeta^2) +- 2 zeta sqrt(1 - zeta^2)``. So ``AF = r_p / (r_high - r_low)`` with
``r = s^-1/2``, which tends to ``1 / (2 zeta)`` as zeta -> 0 (relative gap ~ 4 zeta^2).
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


def _sdof(m: float, k: float, zeta: float) -> rs.Rotor:
    c = 2 * zeta * math.sqrt(k * m)
    disk = rs.DiskElement(n=0, m=m, Id=0.01, Ip=0.02)
    rotor = rs.Rotor([], [disk], [rs.BearingElement(n=0, kxx=k, cxx=c)])
    return rotor.with_fixed([(0, d) for d in ("uz", "rx", "ry", "rz")])


def _exact_af(zeta: float) -> float:
    root = 2 * zeta * math.sqrt(1 - zeta**2)
    s_peak, s_low, s_high = 1 - 2 * zeta**2, 1 - 2 * zeta**2 + root, 1 - 2 * zeta**2 - root
    return s_peak**-0.5 / (s_high**-0.5 - s_low**-0.5)


@pytest.mark.validation
@pytest.mark.parametrize("zeta", [0.005, 0.02, 0.05, 0.1, 0.2])
def test_half_power_af_of_a_single_dof_rotor(zeta):
    """The refined half-power points are exact to rtol 1e-10 in speed, so the AF (a
    difference of two speeds ~ 1/AF apart) carries ~1e-10 AF^2 <= 1e-5 relative error at
    AF = 100; 1e-6 is met for AF <= 30 and 2e-5 allowed for zeta = 0.005."""
    m, k = 50.0, 5e6
    wn = math.sqrt(k / m)
    rotor = _sdof(m, k, zeta)
    speeds = np.linspace(0.1, 2.5, 241) * wn
    result = rs.api_unbalance(rotor, speeds, min_speed=1.6 * wn, mcs=2.0 * wn, num_modes=1)
    assert result.num_modes == 1 and result.unbalance_node.tolist() == [0]
    tol = 2e-5 if zeta < 0.01 else 1e-6
    assert result.af[0] == pytest.approx(_exact_af(zeta), rel=tol)
    assert result.peak_speed[0] == pytest.approx(wn / math.sqrt(1 - 2 * zeta**2), rel=1e-6)
    # light-damping limit 1/(2 zeta): expanding the closed form, the relative gap is
    # 4 zeta^2 + O(zeta^4) for unbalance forcing (2 zeta^2 under a constant force)
    assert abs(2 * zeta * result.af[0] - 1) < 4.5 * zeta**2
    # the unbalance is 6350 W/N with W the rotor mass and N the MCS in rpm
    u = residual_unbalance(m, 2.0 * wn / RPM)[0]
    assert result.unbalance_magnitude[0] == pytest.approx(u, rel=1e-14)
    # peak orbit (peak to peak) = 2 (U/m) r_p^2 / (2 zeta sqrt(1 - zeta^2)) * |...|: the
    # closed-form peak radius is (U/m) / (2 zeta sqrt(1 - zeta^2))
    assert result.peak_pp[0] == pytest.approx(2 * (u / m) / (2 * zeta * math.sqrt(
        1 - zeta**2)), rel=1e-8)


def test_compressor_margins_and_clearances_by_hand():
    """Every number of the compressor's API table recomputed by hand from the result's
    peak speeds, AF and responses: API 617 7th ed. 2.6.2.10 and 2.6.2.11."""
    model = rs.load_model(MODELS / "compressor.toml")
    r = rs.run_analysis(model, "api_unbalance")
    mn, mc = r.min_speed, r.mcs
    bending = int(np.nanargmax(r.af))
    assert 5000 < r.peak_speed[bending] / RPM < 6500        # first bending, ~5740 rpm
    af = r.af[bending]
    assert af > 2.5 and r.peak_speed[bending] < mn
    # below the operating range: SM = min(17 (1 - 1/(AF - 1.5)), 16) % of the min speed
    assert r.required_margin[bending] == pytest.approx(
        min(17 * (1 - 1 / (af - 1.5)), 16) / 100, rel=1e-14)
    assert r.actual_margin[bending] == pytest.approx((mn - r.peak_speed[bending]) / mn,
                                                     rel=1e-14)
    assert r.margin_ok[bending] == (r.actual_margin[bending] >= r.required_margin[bending])
    # AF = Nc / (N2 - N1) from the stored half-power speeds
    assert af == pytest.approx(r.peak_speed[bending] / (
        r.half_power_high[bending] - r.half_power_low[bending]), rel=1e-14)
    # scale factor and clearance ratio: Scc = Av1 / A1 in [0.5, 6], A1 the largest probe
    # response in the operating range; ratio = Scc * max response / clearance
    av1 = 25.4e-6  # MCS 10 500 rpm < 12 000 rpm: the cap
    assert r.vibration_limit == av1
    inside = (r.speeds >= mn) & (r.speeds <= mc)
    a1 = r.major_pp[bending][inside][:, r.probe_nodes].max()
    scc = min(max(av1 / a1, 0.5), 6.0)
    assert r.scale_factor[bending] == pytest.approx(scc, rel=1e-14)
    seal = r.clearance_tags.index("eye seal 1")
    node = r.clearance_nodes[seal]
    assert r.clearance_ratio[bending, seal] == pytest.approx(
        scc * r.major_pp[bending][:, node].max() / 0.4e-3, rel=1e-12)
    assert r.clearance_ok[bending, seal] == (r.clearance_ratio[bending, seal] < 0.75)
    assert r.passed == bool(r.margin_ok.all() and r.clearance_ok.all())


def test_first_bending_mode_is_unbalanced_at_midspan():
    """One plane at the anti-node of the first bending mode (node 12, the middle of the
    bearing span), two out-of-phase planes for the rigid conical mode."""
    model = rs.load_model(MODELS / "compressor.toml")
    r = rs.run_analysis(model, "api_unbalance", fast=True)
    bending = int(np.nanargmax(r.af))
    planes = r.unbalance_node[r.unbalance_mode == bending]
    assert planes.tolist() == [12]
    assert r.response_node[bending] == 12


@pytest.mark.parametrize(("change", "match"), [
    (dict(mcs=3.0 * 316.2), "MCS outside the analysed range"),
    (dict(min_speed=0.05 * 316.2), "MCS outside the analysed range"),
    (dict(min_speed=2.0 * 316.2, mcs=1.8 * 316.2), "exceeds mcs"),
    (dict(factor=-1.0), "factor"), (dict(plane_mass=0.0), "plane_mass"),
    (dict(speeds=[1.0, 0.5, 2.0]), "increasing"), (dict(probes=[5]), "node 5")])
def test_bad_input_raises_model_error(change, match):
    args = dict(rotor=_sdof(50.0, 5e6, 0.05), speeds=np.linspace(0.1, 2.5, 50) * 316.2,
                min_speed=1.6 * 316.2, mcs=2.0 * 316.2)
    args.update(change)
    with pytest.raises(rs.ModelError, match=match):
        rs.api_unbalance(**args)


def test_bad_clearance():
    with pytest.raises(rs.ModelError, match="clearance"):
        rs.Clearance(node=0, clearance=-1e-4)


def test_half_power_band_narrower_than_the_grid():
    """A resonance sharper than the speed grid (zeta = 0.01, samples 0.05 wn apart: both
    neighbours of the peak sample lie below the half-power level) is still measured
    exactly, the band bracketed between the refined peak and the samples (constant-force
    SDOF; exact AF from the closed form in the docstring of ``half_power``)."""
    from rotorsim.analyses.standards.half_power import half_power

    zeta = 0.01
    amp = lambda r: 1 / np.sqrt((1 - r**2) ** 2 + (2 * zeta * r) ** 2)  # noqa: E731
    w = np.arange(0.5, 1.5, 0.05) + 0.0123
    index = int(np.argmax(amp(w)))
    assert amp(w[index - 1]) < amp(w[index]) / math.sqrt(2) * 0.8
    hp = half_power(w, amp(w), index, lambda r: float(amp(r)))
    root = 2 * zeta * math.sqrt(1 - zeta**2)
    exact = math.sqrt(1 - 2 * zeta**2) / (math.sqrt(1 - 2 * zeta**2 + root)
                                          - math.sqrt(1 - 2 * zeta**2 - root))
    assert hp.af == pytest.approx(exact, rel=1e-6)
