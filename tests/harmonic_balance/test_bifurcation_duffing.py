"""Duffing frequency response traced through its folds, with stability and the jump map.

``x'' + 2 zeta x' + x + gamma x^3 = F cos(omega t)`` with zeta = 0.05, gamma = 0.1, F = 0.3:
a hardening overhang between omega = 1.15 and 1.21. Single-harmonic reference (x = a cos +
b sin): ``[(1 - w^2 + k A^2)^2 + (2 zeta w)^2] A^2 = F^2`` with ``k = 3 gamma / 4``; its folds
and its cusp (the smallest F with an overhang) are roots of scalar equations below.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.optimize as so

from rotorsim.harmonic_balance.bifurcation import detect_bifurcations
from rotorsim.harmonic_balance.floquet import hill
from rotorsim.harmonic_balance.fold_tracking import extended_system, track_folds
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import continuation_function, make_residual
from rotorsim.solvers.continuation import Continuation, continue_branch

ZETA, GAMMA, FORCE = 0.05, 0.1, 0.3
KAPPA = 0.75 * GAMMA
OPTIONS = Continuation(initial_step=0.05, max_step=0.2, lam_max=3.0)


def fold_equation(u, force=FORCE):
    """Folds of the single-harmonic response in u = A^2: from G = 0 and dG/du = 0 with
    p = 1 - w^2 + k u one finds p = -F^2 / (2 k u^2), w^2 = 1 + k u - p, and this
    residual of p^2 + 2 k u p + 4 zeta^2 w^2 = 0."""
    return (force**4 / (4 * KAPPA**2 * u**4) - force**2 / u
            + 4 * ZETA**2 * (1 + KAPPA * u + force**2 / (2 * KAPPA * u**2)))


def analytic_folds():
    """(omega, amplitude) of both single-harmonic folds, sorted by omega."""
    u = np.geomspace(1e-2, 1e2, 4001)
    v = fold_equation(u)
    brackets = np.flatnonzero(np.sign(v[1:]) != np.sign(v[:-1]))
    roots = [so.brentq(fold_equation, u[i], u[i + 1], xtol=1e-15, rtol=1e-15) for i in brackets]
    return sorted((math.sqrt(1 + KAPPA * r + FORCE**2 / (2 * KAPPA * r**2)), math.sqrt(r))
                  for r in roots)


def duffing(harmonics, force=FORCE):
    cubic = lambda q, v, tau, w, p: (GAMMA * q**3, 3 * GAMMA * q[:, :, None] ** 2, None)  # noqa: E731
    problem = HBProblem(np.eye(1), np.eye(1), damping=2 * ZETA * np.eye(1), nl_dofs=[0],
                        force=cubic, excitation=lambda w, p: np.array([[0.0], [p], [0.0]]))
    return make_residual(problem, harmonics, condense=False)


def single_harmonic(x, w):
    """Closed-form balance of cos and sin for x = a cos(w t) + b sin(w t)."""
    a, b = x
    s = 1 - w * w + KAPPA * (a * a + b * b)
    r = np.array([s * a + 2 * ZETA * w * b - FORCE, s * b - 2 * ZETA * w * a])
    J = np.array([[s + 2 * KAPPA * a * a, 2 * ZETA * w + 2 * KAPPA * a * b],
                  [2 * KAPPA * a * b - 2 * ZETA * w, s + 2 * KAPPA * b * b]])
    return r, J, np.array([-2 * w * a + 2 * ZETA * b, -2 * w * b - 2 * ZETA * a])


def folds_of(residual):
    fun = continuation_function(residual, "omega", param=FORCE)
    branch = continue_branch(fun, np.zeros(residual.size), 0.3, OPTIONS)
    assert branch.status.name == "OK" and branch.lam[-1] == 3.0
    events = detect_bifurcations(fun, branch)
    assert [e.kind for e in events] == ["fold", "fold"]
    return branch, sorted(events, key=lambda e: e.lam)


@pytest.mark.validation
def test_single_harmonic_folds_match_the_analytic_ones():
    reference = analytic_folds()
    _, hb = folds_of(duffing(1))
    closed = continue_branch(single_harmonic, [0.0, 0.0], 0.3, OPTIONS)
    own = sorted(detect_bifurcations(single_harmonic, closed), key=lambda e: e.lam)
    for (w, amp), e, c in zip(reference, hb, own, strict=True):
        # the same algebraic equations solved two ways: agreement to the extended-system
        # tolerance (1e-12 on the scaled residual)
        assert abs(e.lam - w) <= 1e-10 and abs(c.lam - w) <= 1e-10
        assert math.hypot(c.x[0], c.x[1]) == pytest.approx(amp, abs=1e-9)
        assert e.method == c.method == "extended_system"


@pytest.mark.verification
def test_more_harmonics_converge_and_explain_the_single_harmonic_error():
    """Folds with H = 5 and 7 agree to 1e-8 (converged); they differ from H = 1 by about the
    first-order effect of the third harmonic A3 that H = 1 drops: the cubic term's first
    harmonic changes by (3/4) gamma A1^2 A3 / 2, i.e. d(omega)/omega ~ (3/8) gamma A1 A3 /
    omega^2. The test asserts the error is within a factor 4 of that estimate."""
    reference = analytic_folds()
    res5, res7 = duffing(5), duffing(7)
    _, folds5 = folds_of(res5)
    _, folds7 = folds_of(res7)
    for (w1, _), e5, e7 in zip(reference, folds5, folds7, strict=True):
        assert abs(e5.lam - e7.lam) <= 1e-8
        X = res7.expand(e7.x, e7.lam)
        a1, a3 = math.hypot(X[1, 0], X[2, 0]), math.hypot(X[5, 0], X[6, 0])
        estimate = 3.0 / 8.0 * GAMMA * a1 * a3 / e7.lam**2
        error = abs(e7.lam - w1) / e7.lam
        assert 0.25 * estimate <= error <= 2.0 * estimate, (error, estimate)


@pytest.mark.verification
def test_branch_between_folds_is_unstable():
    """Hill multipliers: one real multiplier is > 1 exactly between the folds (saddle
    branch); no period doubling or Neimark-Sacker point on this curve."""
    residual = duffing(3)
    fun = continuation_function(residual, "omega", param=FORCE)
    branch = continue_branch(fun, np.zeros(residual.size), 0.3, OPTIONS)

    def multipliers(x, w):
        return hill(residual, x, w).multipliers

    events = detect_bifurcations(fun, branch, multipliers=multipliers)
    assert [e.kind for e in events] == ["fold", "fold"]
    first, second = events
    largest = np.array([np.max(np.abs(multipliers(x, w))) for x, w in
                        zip(branch.x, branch.lam, strict=True)])
    middle = np.arange(len(branch))
    middle = (middle > first.index) & (middle <= second.index)
    assert np.all(largest[middle] > 1.0) and np.all(largest[~middle] < 1.0)


@pytest.mark.validation
def test_jump_map_fold_curve_ends_at_the_analytic_cusp():
    """Both folds continued in F meet at the cusp F_c below which there is no overhang;
    F_c is where the fold equation has a double root, found here by brentq on its minimum.
    The cusp is a fold of the fold curve: located by the extended system (of the extended
    system) to its tolerance."""
    def g(force):
        found = so.minimize_scalar(lambda lu: fold_equation(math.exp(lu), force),
                                   bounds=(-5, 5), method="bounded", options={"xatol": 1e-12})
        return found.fun

    f_cusp = so.brentq(g, 0.05, 0.3, xtol=1e-15)
    residual = duffing(1)

    def two(x, w, p):
        ev = residual.evaluate(x, w, p, d_omega=True, d_param=True)
        return ev.r, ev.jacobian, ev.d_omega, ev.d_param

    _, (lower, upper) = folds_of(residual)
    curve = track_folds(two, upper, FORCE, Continuation(direction=-1, lam_max=FORCE,
                                                        max_step=0.05))
    assert curve.branch.reason == "lam_max = 0.3 reached"
    assert curve.lam[0] == pytest.approx(upper.lam, abs=1e-12)
    assert curve.lam[-1] == pytest.approx(lower.lam, abs=1e-9)  # came back on the other fold
    m = residual.size

    def fold_system(z, force):
        return extended_system(two, np.ones(m), z[:m], z[m:2 * m], float(z[-1]), force)

    (cusp,) = detect_bifurcations(fold_system, curve.branch)
    assert cusp.kind == "fold" and abs(cusp.lam - f_cusp) <= 1e-9
