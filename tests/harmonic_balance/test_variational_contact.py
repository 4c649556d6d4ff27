"""Regression of issue 16: ``variational`` on a contacting orbit.

Before the fix the Newmark integration of the variational equation sampled the tangent of
NLvib's unilateral spring only at its fixed steps, so the contact duration was rounded to
a whole number of steps: the two orbits at omega = 0.75 (a1 = 1.222 and 1.310), whose
contacts both lasted 39 of 1000 steps, got the identical multipliers {-2.1529, 0.7424 +-
0.2732i, -0.3492}, and the error fell only like 1/steps, erratically.

Reference: the HB tangent is piecewise constant (``k_t = 100`` while ``q_1(tau) >= 1``),
so the exact monodromy of the variational equation along the HB orbit is the ordered
product of ``expm(A_on dt)`` and ``expm(A_off dt)`` between the phases where the HB series
crosses the gap, found here by brentq on a fine grid. The multipliers differ from the real
trajectory's (test_shooting.py): this checks the integrator, not the HB orbit.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import scipy.linalg as sl
from multiplier_matching import matched
from nlvib_unilateral import (
    GAP,
    OMEGA,
    ORBIT_GUESSES,
    STIFFNESS,
    D,
    K,
    hb_orbit,
    problem,
)
from scipy.optimize import brentq

from rotorsim.harmonic_balance.fourier import AFT
from rotorsim.harmonic_balance.monodromy import variational
from rotorsim.harmonic_balance.shooting import shoot


def _exact_multipliers(res, x) -> np.ndarray:
    X = res.expand(x, OMEGA)
    aft = AFT(res.harmonics)

    def gap(tau):
        return float((aft.basis(np.atleast_1d(tau)) @ X[:, 0])[0] - GAP)

    grid = np.linspace(0.0, 2 * np.pi, 20001)
    g = aft.basis(grid) @ X[:, 0] - GAP
    roots = [brentq(gap, grid[i], grid[i + 1], xtol=1e-14)
             for i in np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))]
    edges = np.concatenate(([0.0], roots, [2 * np.pi]))
    Phi = np.eye(4)
    for a, b in itertools.pairwise(edges):
        k = K.copy()
        k[0, 0] += STIFFNESS * (gap(0.5 * (a + b)) >= 0)
        A = np.block([[np.zeros((2, 2)), np.eye(2)], [-k, -D]])
        Phi = sl.expm(A * (b - a) / OMEGA) @ Phi
    return np.linalg.eigvals(Phi)


@pytest.fixture(scope="module")
def orbits():
    out = []
    for guess in ORBIT_GUESSES:
        res, hb = hb_orbit(shoot(problem(), OMEGA, guess).state)
        out.append((res, hb.x, _exact_multipliers(res, hb.x)))
    return out


def test_variational_tells_the_two_contacting_orbits_apart(orbits):
    (r0, x0, _), (r1, x1, _) = orbits
    mu0 = variational(r0, x0, OMEGA).multipliers
    mu1 = variational(r1, x1, OMEGA).multipliers
    assert abs(abs(mu0[0]) - abs(mu1[0])) > 0.3        # reference: 1.93 and 2.50


def test_variational_converges_at_second_order_to_the_exact_monodromy(orbits):
    """Newmark (average acceleration) is second order once the steps meet the contact
    switches: the error at 1000 steps (~2e-2 on multipliers of size 2) falls by about 4
    per halving of the step (at least 3 asserted)."""
    for res, x, exact in orbits:
        errors = [np.abs(matched(variational(res, x, OMEGA, steps=s).multipliers, exact)
                         - exact).max() for s in (1000, 2000)]
        assert errors[0] < 3e-2 and errors[0] / errors[1] > 3.0
