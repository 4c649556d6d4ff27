"""Shooting (rotorsim.harmonic_balance.shooting): multipliers and periodic orbits from the
real trajectory, against closed forms, Hill's method on a smooth problem, and an independent
event-located integration of NLvib's unilateral-contact example (nlvib_unilateral.py),
where the checks of floquet_check must flag Hill and Hsu and fall back to shooting.
"""

from __future__ import annotations

import numpy as np
import pytest
from multiplier_matching import matched
from nlvib_unilateral import (
    OMEGA,
    ORBIT_GUESSES,
    first_harmonic,
    hb_orbit,
    problem,
    reference_monodromy,
    reference_period,
)

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.floquet import hill
from rotorsim.harmonic_balance.floquet_check import checked_floquet, run_checks
from rotorsim.harmonic_balance.liouville import LIOUVILLE_TOL
from rotorsim.harmonic_balance.monodromy import hsu
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import make_residual
from rotorsim.harmonic_balance.shooting import hb_state, shoot, shooting_multipliers
from rotorsim.harmonic_balance.solve import solve_point

# --- smooth problems ----------------------------------------------------------------

def test_multipliers_of_a_linear_gyroscopic_system_are_exp_of_its_eigenvalues():
    """Closed form: for constant ``A`` the monodromy is ``exp(A T)``; DOP853 at rtol 1e-10
    over one period (about 10 oscillations of the fast mode) is good to ~1e-9."""
    M = np.diag([2.0, 1.0])
    K = np.array([[30.0, -4.0], [-4.0, 20.0]])
    C = np.array([[0.3, 0.0], [0.0, 0.2]])
    G = np.array([[0.0, 0.5], [-0.5, 0.0]])
    pb = HBProblem(M, K, C, G, spin=2.0)
    omega = 0.9
    fl = shooting_multipliers(pb, [0.1, -0.2, 0.0, 0.3], omega)
    A = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, C + 2.0 * G)]])
    exact = np.exp(np.linalg.eigvals(A) * 2 * np.pi / omega)
    assert fl.method == "shooting"
    assert np.abs(matched(fl.multipliers, exact) - exact).max() < 1e-8
    # the integrated trace is -T tr(M^-1 (C + W G)) (G drops out: tr(M^-1 G) = 0 here)
    assert fl.stats["trace_integral"] == pytest.approx(
        -2 * np.pi / omega * np.trace(np.linalg.solve(M, C)), rel=1e-10)


def _duffing():
    def cubic(q, v, tau, w, p):
        return q**3 + 0.05 * v**3, 3 * q[:, :, None] ** 2, 0.15 * v[:, :, None] ** 2
    return HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1), nl_dofs=[0], force=cubic,
                     excitation=[[0.0], [1.0], [0.0]])


@pytest.mark.parametrize("omega", [0.8, 2.5])
def test_shooting_agrees_with_hill_on_a_smooth_duffing_oscillator(omega):
    """Duffing with cubic stiffness and damping: HB at H = 15 is converged to ~1e-10, so
    Hill's exponents and the shooting orbit must agree with shooting to that level
    (1e-7 allows for the DOP853 tolerance times the multipliers' condition)."""
    pb = _duffing()
    res = make_residual(pb, 15)
    sol = solve_point(res, omega)
    y_hb = hb_state(res, sol.x, omega)
    shot = shoot(pb, omega, y_hb)
    assert shot.iterations <= 2 and np.abs(shot.state - y_hb).max() < 1e-8
    ref = hill(res, sol.x, omega).multipliers
    assert np.abs(matched(shot.floquet.multipliers, ref) - ref).max() < 1e-7
    assert shot.liouville_error < 1e-9               # the trace along the trajectory
    # on a smooth orbit the checks pass and nothing falls back to shooting
    kept, record = checked_floquet(res, sol.x, omega, 0.0, hill(res, sol.x, omega))
    assert record.passed and record.method == "hill" and record.tangent_jumps == 0
    assert record.liouville_error < 1e-9 and kept.method == "hill"


def test_shooting_refuses_a_singular_mass_matrix_and_a_bad_state():
    pb = HBProblem(np.diag([1.0, 0.0]), np.eye(2))
    with pytest.raises(ModelError, match="nonsingular mass"):
        shooting_multipliers(pb, np.zeros(4), 1.0)
    with pytest.raises(ModelError, match="2n = 2"):
        shooting_multipliers(HBProblem(np.eye(1), np.eye(1)), [0.0, np.nan], 1.0)


# --- NLvib's unilateral contact ----------------------------------------------------

@pytest.fixture(scope="module", params=[0, 1], ids=["a1=1.222", "a1=1.310"])
def orbit(request):
    """The orbit by shooting from the guess, its HB counterpart and the reference."""
    pb = problem()
    shot = shoot(pb, OMEGA, ORBIT_GUESSES[request.param])
    res, hb = hb_orbit(shot.state)
    mu_ref = np.linalg.eigvals(reference_monodromy(shot.state, h=1e-4))
    return {"shot": shot, "res": res, "hb": hb, "mu_ref": mu_ref, "index": request.param}


def test_the_two_hb_orbits_are_those_of_the_issue(orbit):
    assert first_harmonic(orbit["hb"].x) == pytest.approx((1.222, 1.310)[orbit["index"]],
                                                          abs=5e-4)


def test_shooting_orbit_and_multipliers_match_an_event_located_integration(orbit):
    """The reference returns to the shooting state within 3e-10 (LSODA at rtol 1e-11);
    its finite-difference monodromy (h = 1e-4: truncation ~h^2, noise ~1e-11 / h) gives
    the multipliers to ~1e-7 (measured 3e-7 against shooting)."""
    shot = orbit["shot"]
    assert np.abs(reference_period(shot.state) - shot.state).max() < 1e-9
    mu_ref = orbit["mu_ref"]
    assert np.abs(matched(shot.floquet.multipliers, mu_ref) - mu_ref).max() < 1e-5
    assert shot.liouville_error < 1e-9


def test_shooting_converges_from_the_hb_solution(orbit):
    pb, res, hb = problem(), orbit["res"], orbit["hb"]
    shot = shoot(pb, OMEGA, hb_state(res, hb.x, OMEGA))
    assert shot.iterations <= 3
    assert np.abs(shot.state - orbit["shot"].state).max() < 1e-8


def test_hill_and_hsu_are_off_and_the_checks_flag_them(orbit):
    """Issue 16: the HB-orbit methods miss the multipliers by O(1) (Gibbs ripple at the
    contact). Liouville flags Hill; Hsu satisfies Liouville exactly (a product of
    exponentials) and is flagged by the tangent jumps; the fallback gives the reference."""
    res, x, mu_ref = orbit["res"], orbit["hb"].x, orbit["mu_ref"]
    h, s = hill(res, x, OMEGA), hsu(res, x, OMEGA)
    assert np.abs(matched(s.multipliers, mu_ref) - mu_ref).max() > 0.5
    assert np.abs(matched(h.multipliers, mu_ref) - mu_ref).max() > 0.1
    hill_error, jumps = run_checks(res, x, OMEGA, 0.0, h)
    hsu_error, _ = run_checks(res, x, OMEGA, 0.0, s)
    assert hill_error > LIOUVILLE_TOL and hsu_error < 1e-12 and jumps == 2
    kept, record = checked_floquet(res, x, OMEGA, 0.0, s)
    assert (record.method, record.passed, record.fallback) == ("shooting", False, "shooting")
    assert np.abs(matched(kept.multipliers, mu_ref) - mu_ref).max() < 1e-5
