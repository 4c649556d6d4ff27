"""What makes a sign change a resolved event (``rotorsim/analyses/periodic/crossings.py``,
``refined.py``): synthetic multipliers for each rule, and the finer discretisation on a
smooth problem. The clearance rotor's events are checked in ``test_verify_events.py``
(one shared branch)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest

from rotorsim.analyses.periodic.crossings import (
    largest_real,
    missing_crossing,
    real_unstable,
    window_partners,
)
from rotorsim.analyses.periodic.refined import SamplingCheck
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import continuation_function, make_residual
from rotorsim.solvers.continuation import Continuation, continue_branch

TOL = 1e-5


@dataclass(frozen=True)
class Between:
    kind: str
    i: int
    j: int


NEUTRAL = [np.exp(0.4j), np.exp(-0.4j)]          # an undamped mode: |mu| = 1


def _rows(*largest_real_multiplier):
    """Multipliers (P, 4): a neutral pair, a damped real one, and the given real one."""
    return np.array([[*NEUTRAL, 0.3, r] for r in largest_real_multiplier], dtype=complex)


def test_real_multipliers_above_the_circle_are_counted():
    assert real_unstable([1.2, 1.0 + 1e-9, -1.3, 1.1 + 0.2j, 1.1 - 0.2j], TOL) == 1
    assert real_unstable([*NEUTRAL, 0.99], TOL) == 0
    assert largest_real([-2.0, 0.5, 1.1 + 0.2j]) == 0.5
    assert largest_real([-2.0, 1.1 + 0.2j]) == 0.0


def test_a_branch_point_needs_a_real_multiplier_crossing_next_to_it():
    # a real multiplier passes 1 + tol between points 2 and 3: resolved
    mu = _rows(0.9, 0.95, 0.99, 1.01, 1.03, 1.05)
    assert missing_crossing(Between("branch_point", 2, 3), mu, TOL) == ""
    # ... or one point away (the determinant and the multipliers need not change at the
    # same step): still resolved
    assert missing_crossing(Between("branch_point", 1, 2), mu, TOL) == ""
    # two points away: not next to it
    why = missing_crossing(Between("branch_point", 0, 1), mu, TOL)
    assert "no real Floquet multiplier crosses" in why and "0.9 at point 0" in why
    # a multiplier that stops short of 1 + tol is not a resolved crossing
    close = _rows(0.999, 1.0 + 0.5 * TOL, 1.0 + 0.9 * TOL, 1.0)
    assert "no real Floquet multiplier" in missing_crossing(Between("branch_point", 1, 2),
                                                            close, TOL)
    # only a neutral pair touching +1 (an internal resonance): not a crossing
    touch = np.array([[np.exp(1j * a), np.exp(-1j * a), 0.3] for a in
                      (0.2, 0.05, 1e-3, 0.05)])
    assert missing_crossing(Between("branch_point", 1, 2), touch, TOL) != ""
    # no multipliers at either pair: says so
    nan = np.full((4, 3), np.nan + 0j)
    assert "no Floquet multipliers" in missing_crossing(Between("branch_point", 1, 2), nan,
                                                        TOL)


def test_the_other_edge_of_a_window_with_an_artefact_edge_is_unresolved():
    # a complex pair leaves the circle between 1 and 2 and comes back between 3 and 4
    pair = [1.0005 * np.exp(0.3j), 1.0005 * np.exp(-0.3j)]
    inside = [0.9 * np.exp(0.3j), 0.9 * np.exp(-0.3j)]
    mu = np.array([inside, inside, pair, pair, inside])
    up, down = Between("neimark_sacker", 1, 2), Between("neimark_sacker", 3, 4)
    assert window_partners([up, down], {up: "too steep", down: ""}, mu, TOL) == {
        down: "the other edge of its unstable window did not survive the check"}
    assert window_partners([up, down], {up: "", down: ""}, mu, TOL) == {}
    assert window_partners([up, down], {up: "a", down: "b"}, mu, TOL) == {}


@pytest.fixture(scope="module")
def duffing():
    """A Duffing oscillator ``x'' + 0.1 x' + x + x^3 = 0.2 cos(omega t)`` traced over its
    hardening resonance at ``H = 5`` (smooth: every harmonic decays fast)."""
    cubic = lambda q, v, tau, w, p: (q**3, 3 * q[:, :, None] ** 2, None)  # noqa: E731
    pb = HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1), nl_dofs=[0], force=cubic,
                   excitation=[[0.0], [0.2], [0.0]])
    residual = make_residual(pb, 5)
    fun = continuation_function(residual, "omega", terms=True)
    x0 = np.zeros(residual.size)
    branch = continue_branch(fun, x0, 0.5, Continuation(max_step=0.2, lam_max=3.0,
                                                        max_points=300))
    return residual, branch


def test_the_finer_discretisation_with_more_harmonics_reproduces_a_smooth_branch(duffing):
    """On a smooth problem the bracket points of both folds converge with 8 instead of 5
    harmonics and twice the samples, and the finer branch turns between them too; the
    padded scales keep the branch's own scales for the harmonics it has."""
    residual, branch = duffing
    turns = np.flatnonzero(branch.tangents[:-1, -1] * branch.tangents[1:, -1] < 0)
    assert turns.size == 2
    check = SamplingCheck(residual, branch, None, harmonics=math.ceil(1.5 * 5))
    assert check.fine.harmonics == 8 and check.fine.samples == 2 * residual.samples
    scale = check.system.x_scale
    assert scale.size == 17 and np.array_equal(scale[:11], branch.x_scale)
    assert np.array_equal(scale[11:], np.resize(branch.x_scale[-2:], 6))
    for i in turns:
        assert check.confirms(Between("fold", int(i), int(i) + 1), None) == ""
        fine = check._point(int(i))
        # the first 2H + 1 coefficients agree with the branch's to the truncation error
        # of H = 5 on this orbit: its 5th harmonic is 6e-4 of the fundamental, the added
        # 7th 1e-5, and they move the first 11 coefficients by 3e-7 (measured) of the
        # largest; 1e-5 allows for the corrector's tolerance (1e-8 of the scales)
        assert np.abs(fine.x[:11] - branch.x[i]).max() < 1e-5 * np.abs(branch.x[i]).max()
    assert "8 harmonics and 2 times the samples" in check.what
