"""The checks of a Floquet result (liouville.py, tangent_switches.py, floquet_check.py) and
their use by the periodic analyses' stability model.

References: Liouville's formula ``det Phi(T) = exp(int trace A dt)`` (closed form for the
trace of ``x'' + (0.1 + 0.15 x'^2) x' + x + x^3 = cos(omega t)``: ``-(0.1 + 0.15 v^2)``
averaged over the orbit); the jump test on functions with known jumps and onsets.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from multiplier_matching import matched
from nlvib_unilateral import OMEGA, ORBIT_GUESSES, hb_orbit, problem

from rotorsim.analyses.periodic.stability import stability_model
from rotorsim.harmonic_balance.floquet import hill
from rotorsim.harmonic_balance.liouville import LIOUVILLE_TOL, TraceModel, liouville_error
from rotorsim.harmonic_balance.monodromy import hsu
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import make_residual
from rotorsim.harmonic_balance.shooting import shoot
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.harmonic_balance.tangent_switches import PHASE_TOL, find_jumps

GRID = 2 * np.pi * np.arange(64) / 64


# --- jumps ---------------------------------------------------------------------------

def test_jumps_are_found_and_located():
    """A step of 3 on [0.7, 2.9) plus a smooth part: both edges to PHASE_TOL."""
    def tangent(t):
        t = np.mod(t, 2 * np.pi)
        return (3.0 * ((t >= 0.7) & (t < 2.9)) + np.cos(t))[:, None]
    jumps = find_jumps(tangent, GRID)
    assert jumps.count == 2
    assert np.abs(jumps.phases - [0.7, 2.9]).max() < 2 * PHASE_TOL


@pytest.mark.parametrize("power", [1.0, 0.5, 1.0 / 9.0])
def test_continuous_contact_onsets_are_not_jumps(power):
    """A tangent ``max(sin t - 0.3, 0)^p``: linear (p = 1), Hertz point contact (1/2),
    line contact with load exponent 10/9 (1/9): continuous, so no jump."""
    def tangent(t):
        return (1e8 * np.maximum(np.sin(t) - 0.3, 0.0) ** power)[:, None]
    assert find_jumps(tangent, GRID).count == 0


# --- Liouville -------------------------------------------------------------------------

def _damped_duffing():
    def force(q, v, tau, w, p):
        return q**3 + 0.05 * v**3, 3 * q[:, :, None] ** 2, 0.15 * v[:, :, None] ** 2
    return HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1), nl_dofs=[0], force=force,
                     excitation=[[0.0], [1.0], [0.0]])


def test_the_trace_integral_and_the_liouville_error_of_hill_and_hsu():
    pb, omega = _damped_duffing(), 0.8
    res = make_residual(pb, 15)
    x = solve_point(res, omega).x
    X = res.expand(x, omega)
    tau = 2 * np.pi * np.arange(512) / 512       # velocity from the series, by hand
    h = np.arange(1, 16)
    v = omega * (-np.sin(np.outer(tau, h)) @ (h * X[1::2, 0])
                 + np.cos(np.outer(tau, h)) @ (h * X[2::2, 0]))
    closed = -2 * np.pi / omega * (0.1 + 0.15 * np.mean(v**2))
    Ct = 0.15 * v[:, None, None] ** 2
    assert TraceModel(pb).integral(omega, Ct) == pytest.approx(closed, rel=1e-12)
    assert liouville_error(hill(res, x, omega), closed) < 1e-9   # converged HB: spectral
    assert liouville_error(hsu(res, x, omega), closed) < 1e-6    # trapezoid on N = 64
    fl = hill(res, x, omega)
    off = dataclasses.replace(fl, exponents=fl.exponents + 1e-3)  # 2 pi 1e-3 / 0.8 each
    assert liouville_error(off, closed) == pytest.approx(2 * np.pi * 1e-3 / omega, rel=1e-6)
    assert liouville_error(off, closed) > LIOUVILLE_TOL


def test_the_liouville_check_does_not_apply_where_it_means_nothing():
    fl = hill(make_residual(HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1)), 2,
                            condense=False), np.zeros(5), 1.0)
    assert math.isnan(TraceModel(HBProblem(np.diag([1.0, 0.0]), np.eye(2))).integral(1.0))
    assert math.isnan(liouville_error(fl, math.nan))
    assert math.isnan(liouville_error(fl, -0.2 * np.pi, size=4))   # incomplete selection
    tiny = dataclasses.replace(fl, method="hsu", multipliers=np.array([1e-30, 0.5]))
    assert math.isnan(liouville_error(tiny, -0.2 * np.pi))         # lost to round-off


# --- the periodic analyses' stability model ----------------------------------------------

@pytest.mark.parametrize("method", ["hsu", "hill"])
def test_the_stability_model_falls_back_to_shooting_and_records_it(method):
    res, hb = hb_orbit(shoot(problem(), OMEGA, ORBIT_GUESSES[1]).state)
    model = stability_model(res, method, modes=None, omega_max=OMEGA)
    fl = model.floquet(hb.x, OMEGA)
    record = model.check(hb.x, OMEGA)
    assert fl.method == "shooting" and record.method == "shooting"
    assert not record.passed and record.tangent_jumps == 2
    assert record.fallback_liouville_error < 1e-9
    assert fl.critical.real == pytest.approx(-1.18332, abs=1e-4)   # test_shooting.py


def test_shooting_on_a_complete_craig_bampton_model_equals_shooting_on_the_full_one():
    """The reduced model carries the excitation ``T^T f`` (for shooting); with all
    fixed-interface modes kept the basis is complete, so the orbit and its multipliers are
    those of the full model (a change of coordinates) up to the shooting tolerance."""
    from rotorsim.analyses.periodic.stability import craig_bampton
    from rotorsim.harmonic_balance.shooting import hb_state

    full = problem()
    M3, K3 = np.eye(3), np.array([[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 2.0]])
    exc = np.zeros((3, 3))
    exc[1, 1] = 0.1
    pb = HBProblem(M3, K3, 0.03 * K3, nl_dofs=[0], force=full.force, excitation=exc)
    res = make_residual(pb, 21, samples=1024)
    sol = solve_point(res, 0.4)
    assert sol.time_response()[1][:, 0].max() > 1.0                 # in contact
    reduced, kept = craig_bampton(pb, 2, None)
    assert kept == 2
    red_res = make_residual(reduced, 21, samples=1024)
    shot_full = shoot(pb, 0.4, hb_state(res, sol.x, 0.4))
    shot_red = shoot(reduced, 0.4, hb_state(red_res, sol.x, 0.4))
    mu = shot_full.floquet.multipliers
    # two DOP853 runs at rtol 1e-10 in other coordinates: 2e-8 of max |mu| = 4.41 measured
    assert np.abs(matched(shot_red.floquet.multipliers, mu) - mu).max() \
        < 1e-7 * np.abs(mu).max()
    assert shot_red.state[0] == pytest.approx(shot_full.state[0], abs=1e-9)  # q_1 physical
