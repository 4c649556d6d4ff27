"""The API 617 formulas against hand-worked numbers: Q_A in its SI and US forms (and the
factor 1000 of the printed SI form), the residual unbalance in both unit systems, the
required separation margins and the Level I screening rules."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.standards.api_formulas import (
    KLBF_PER_IN,
    anticipated_cross_coupling_us,
    csr_limit,
    residual_unbalance_us,
    vibration_limit,
)

RPM = math.pi / 30.0
HP = 745.69987158227  # W per mechanical horsepower (550 ft lbf/s)
INCH = 0.0254


def test_q_a_matches_the_published_ross_example():
    """ROSS's ``api_report`` doctest: two impellers, D = 0.35 m, H = 0.08 m, 10 kW each,
    density ratios 1.11 and 1.14, 1000 rpm: Q_A = 23022.32142857143 N/m with C = 9.55.
    rotorsim uses the exact torque P / Omega (C = 60 / 2 pi = 9.5493), so the two differ by
    exactly the rounding of C: compared to 1e-12 (both are a few flops)."""
    q = rs.anticipated_cross_coupling([10e3, 10e3], 1000 * RPM, [0.35, 0.35], [0.08, 0.08],
                                      [1.11, 1.14])
    assert q.sum() / 23022.32142857143 == pytest.approx((60 / (2 * math.pi)) / 9.55,
                                                         rel=1e-12)


def test_q_a_hand_worked_in_us_units_and_the_printed_si_form():
    """A stage of 1000 hp at 10 000 rpm, D = 12 in, H = 0.5 in, density ratio 1.2.

    By hand (US form): Q_A = 3 * 63 * 1000 * 1.2 / (12 * 0.5 * 10000) = 3.78 klbf/in.
    SI (consistent): the same stage converted gives 3.78 klbf/in * 63.025/63, the torque
    constant 63 025 lbf in per hp/rpm (= 6600 * 60 / 2 pi) against API's rounded 63.
    The printed SI form (C = 9.55, P in kW, D and H in mm, "kN/mm") gives a number 1000
    times (times 9.55 / 9.5493) smaller than the consistent value in kN/mm."""
    us = anticipated_cross_coupling_us(1000, 10000, 12, 0.5, 1.2)[0]
    assert us == pytest.approx(3.78, rel=1e-14)
    si = rs.anticipated_cross_coupling(1000 * HP, 10000 * RPM, 12 * INCH, 0.5 * INCH, 1.2)[0]
    torque_constant = 6600 * 60 / (2 * math.pi) / 1000  # klbf in per hp/rpm
    assert si / (us * KLBF_PER_IN) == pytest.approx(torque_constant / 63.0, rel=1e-12)
    printed_si = 3 * 9.55 * (1000 * HP / 1e3) * 1.2 / (12 * 25.4 * 0.5 * 25.4 * 10000)
    assert (si * 1e-6) / printed_si == pytest.approx(1000 * (60 / (2 * math.pi)) / 9.55,
                                                     rel=1e-12)


def test_turbine_stages_ignore_the_density_ratio():
    q = rs.anticipated_cross_coupling(1e6, 1000.0, 0.5, 0.05, 1.5, machine="turbine")
    assert q[0] == pytest.approx(1.5 * 1e6 / (1000 * 0.5 * 0.05), rel=1e-14)


def test_residual_unbalance_si_and_us_forms_agree():
    """100 lb at 10 000 rpm: 4 W/N = 0.04 oz in = 0.04 * 28.349523125 g * 25.4 mm =
    28.8031 g mm; 6350 W/N with W = 45.359237 kg gives 28.8031 g mm: API's 6350 is
    4 oz in/lb in g mm/kg (6350.03) rounded, so they agree to 5e-6."""
    us = residual_unbalance_us(100.0, 10000.0)[0]
    assert us == pytest.approx(0.04, rel=1e-14)
    si = rs.residual_unbalance(45.359237, 10000.0)[0]
    assert si / (us * 28.349523125e-3 * 25.4e-3) == pytest.approx(1.0, abs=5e-6)


@pytest.mark.parametrize(("af", "below", "percent"), [
    (2.0, True, 0.0), (2.49, False, 0.0),        # critically damped: no margin
    (2.5, True, 0.0), (2.5, False, 10.0),        # 17 (1 - 1/1) = 0
    (3.5, True, 8.5), (3.5, False, 18.5),        # 17 (1 - 1/2) = 8.5
    (6.5, True, 13.6), (6.5, False, 23.6),       # 17 (1 - 1/5) = 13.6
    (30.0, True, 16.0), (30.0, False, 26.0),     # the caps
])
def test_required_separation_margins_by_hand(af, below, percent):
    """API 617 7th ed. 2.6.2.10, worked by hand in the comments (exact in binary to
    1e-12)."""
    assert rs.required_separation_margin([af], [below])[0] * 100 == pytest.approx(
        percent, abs=1e-12)


def test_screening_rules():
    assert rs.level1_screening(1.5, 0.5, 1.0, 5.0)[0]            # Q0/QA < 2
    assert rs.level1_screening(20.0, 0.05, 1.0, 5.0)[0]          # log dec < 0.1
    assert not rs.level1_screening(5.0, 0.5, 2.4, 10.0)[0]       # Region A
    assert rs.level1_screening(5.0, 0.5, 2.6, 10.0)[0]           # Region B
    assert not rs.level1_screening(12.0, 0.5, 3.0, 100.0)[0]     # Q0/QA >= 10
    assert rs.level1_screening(5.0, 0.5, 1.0, 70.0)[0]           # above 60 kg/m^3: B
    assert not rs.level1_screening(1.5, 0.5, 1.0, 5.0, machine="turbine")[0]
    # the boundary: 2.5 to 16.53 kg/m^3, linear to 2.0 at 60 kg/m^3 (midpoint 2.25)
    assert csr_limit(16.53) == 2.5 and csr_limit(60.0) == 2.0
    assert csr_limit((16.53 + 60) / 2) == pytest.approx(2.25, abs=1e-12)


def test_vibration_limit():
    """Av1 = 25.4 sqrt(12000 / N) um, at most 25.4 um: at 10 500 rpm the root exceeds 1,
    so the cap holds; at 48 000 rpm it is 12.7 um."""
    assert vibration_limit(10500.0) == 25.4e-6
    assert vibration_limit(48000.0) == pytest.approx(12.7e-6, rel=1e-14)


@pytest.mark.parametrize("bad", [
    dict(power=-1.0), dict(speed=0.0), dict(diameter=math.nan), dict(flow_height=0.0),
    dict(density_ratio=-1.2), dict(machine="pump")])
def test_bad_machine_data_is_refused(bad):
    args = dict(power=1e5, speed=1000.0, diameter=0.3, flow_height=0.02, density_ratio=1.1,
                machine="compressor")
    args.update(bad)
    with pytest.raises(rs.ModelError):
        rs.anticipated_cross_coupling(**args)


def test_margins_vectorised():
    out = rs.required_separation_margin(np.array([3.5, 3.5]), np.array([True, False]))
    assert out.tolist() == pytest.approx([0.085, 0.185], abs=1e-15)
