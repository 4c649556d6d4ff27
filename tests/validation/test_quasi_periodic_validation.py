"""Quasi-periodic harmonic balance against integration in time (validation case 40, issue 17).

Shortened versions of ``scripts/quasi_validation.py`` (whose full runs give the numbers of
case 40 in ``docs/validation.md``): the rigid rotor in a 9-ball bearing whose VC order is
``Z kappa = 2 + golden ratio`` (far from low-order fractions), and ``models/default.toml``.
Reference: ``rs.transient`` (Radau IIA, balls moving with the cage), an integration that
shares with the harmonic balance only the bearing's force law; its tones are fitted by least
squares on the known frequencies ``k1 W + k2 w2``.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
import quasi_validation as qv


@pytest.mark.validation
def test_rigid_rotor_tones_agree_with_an_integration_within_one_percent() -> None:
    """1200 rad/s, box (10, 4) on a 128 x 64 grid; the integration (rtol 1e-6) starts on
    the torus, settles 15 ms (the torus's exponent is about -120 1/s) and is fitted over 50
    ms (10 revolutions) on the tones of the same box. Measured: every compared tone within
    3.3e-4 (the full run, 0.25 s at rtol 1e-8 on a larger box of tones: 2.5e-4). Asserted:
    the base tones within 2e-3 and the three largest combination tones of each direction
    (down to 0.5 % of the 1X) within 1 %, the issue's bound."""
    case = dataclasses.replace(qv.rigid_case(), rtol=1e-6)
    c = qv.compare(case, 1200.0, settle=0.015, window=0.05, fit_box=(10, 4))
    qv.print_comparison(c)
    errors = np.abs(c.errors())
    base = np.array([k in qv.BASE_TONES for *_, k, _, _ in c.rows])
    assert errors[base].max() < 2e-3
    assert errors.max() < 1e-2
    assert c.deviation < 2e-3  # the integration stays on the torus


@pytest.mark.validation
def test_default_model_stays_on_its_torus() -> None:
    """``models/default.toml`` at 1800 rpm (box (6, 2) on its default grid, 32 tones): its
    first modes have about 0.1 % damping, so the integration starts on the HB torus; over
    0.05 s (1.5 revolutions, 6 VC periods; rtol 1e-6) it stays within 1e-3 of the
    peak-to-peak of the disk's motion (measured 4.9e-4 in ux and 3.0e-4 in uy; 5.6e-5 and
    1.3e-5 with case 40's diamond 6 over 0.1 s). The tones are compared over 2 s in the
    script."""
    case = qv.default_case()
    speed = 1800.0 * np.pi / 30
    point, _ = qv.solve_point(case, speed, (6, 2), "box")
    times = np.linspace(0.0, 0.05, 1001)
    run = rs.transient(case.rotor, 0.05, speed=speed, unbalance=case.unbalance,
                       initial=point.state(0.0), rtol=1e-6,
                       output=rs.Output(nodes=[8], times=times))
    for dof in ("ux", "uy"):
        torus = point.response(run.t, 8, dof)
        deviation = np.abs(run.q[:, run.dof_labels.index(f"node 8 {dof}")] - torus).max()
        print(dof, deviation / np.ptp(torus))
        assert deviation < 1e-3 * np.ptp(torus)


@pytest.mark.validation
def test_a_perturbation_of_a_stable_torus_decays_at_its_lyapunov_exponent() -> None:
    """Rigid rotor, 2 um clearance, 1200 rad/s: two integrations from the torus, one moved
    by 1 nm; their difference decays at the rate of the torus's largest Lyapunov exponent
    (the script, over 60 ms: within the difference listed in case 40; here over 40 ms at
    rtol 1e-7: -123.7 against -124.0 1/s measured; asserted within 20 %, the spread of the
    exponent over 30-80 revolution horizons and of the slope over a few revolutions)."""
    g = qv.perturbation_growth(*qv.STABLE, duration=0.04, size=1e-9, periods=30, rtol=1e-7)
    print(g)
    assert g.exponent < 0 and g.difference_rate < 0
    assert g.difference_rate == pytest.approx(g.exponent, rel=0.2)
