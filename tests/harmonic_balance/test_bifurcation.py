"""Bifurcation detection and location on algebraic branches with known answers."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.optimize as so

from rotorsim.harmonic_balance.bifurcation import (
    BifurcationOptions,
    branch_test_functions,
    detect_bifurcations,
    neimark_sacker_value,
    period_doubling_value,
)
from rotorsim.harmonic_balance.fold_tracking import locate_fold, track_folds
from rotorsim.solvers.continuation import Continuation, continue_branch

FOLD = 2.0 / (3.0 * math.sqrt(3.0))  # x^3 - x + lam = 0 turns at lam = +-2 / (3 sqrt 3)


def s_curve(x, lam):
    return x**3 - x + lam, np.diag(3.0 * x**2 - 1.0), np.ones(1)


def line(x, lam):
    return x - lam, np.eye(1), -np.ones(1)


def test_s_curve_folds_to_machine_precision():
    b = continue_branch(s_curve, [-1.3], 1.0, Continuation(direction=-1, lam_min=-1.0,
                                                           max_step=0.3))
    events = detect_bifurcations(s_curve, b)
    assert [e.kind for e in events] == ["fold", "fold"]  # folds do not flip the BP test
    for e, sign in zip(events, (-1.0, 1.0), strict=True):
        # analytic fold: 3 x^2 = 1, lam = x - x^3; the brief asks for 1e-10
        assert abs(e.lam - sign * FOLD) <= 1e-10
        assert abs(e.x[0] - sign / math.sqrt(3.0)) <= 1e-8
        assert e.method == "extended_system" and e.located
        assert abs(abs(e.null_vector[0]) - 1.0) <= 1e-12
        assert e.test_values[0] * e.test_values[1] < 0
        assert b.lam[e.index] * sign <= sign * e.lam and b.lam[e.next_index] * sign <= sign * e.lam
    assert b.with_events(events).events == events


def test_circle_folds_and_coarse_location_without_polish():
    def circle(x, lam):
        return np.array([x[0] ** 2 + lam**2 - 1.0]), np.array([[2.0 * x[0]]]), np.array([2 * lam])

    b = continue_branch(circle, [1.0], 0.0, Continuation(max_step=0.4))
    events = detect_bifurcations(circle, b)
    assert [(e.kind, round(e.lam, 12)) for e in events] == [("fold", 1.0), ("fold", -1.0)]
    assert all(abs(e.x[0]) < 1e-12 for e in events)


def crossing(x, lam):
    """(x - sin lam)(lam - 0.5 - x^2) = 0: two curves crossing transversally (a branch
    point where dR/dx = dR/dlam = 0)."""
    a, b = x[0] - math.sin(lam), lam - 0.5 - x[0] ** 2
    return (np.array([a * b]), np.array([[b - 2.0 * x[0] * a]]),
            np.array([-math.cos(lam) * b + a]))


def test_branch_point_of_crossing_curves():
    x_star = so.brentq(lambda x: x - math.sin(0.5 + x * x), 0.0, 1.0, xtol=1e-15)
    lam_star = 0.5 + x_star**2
    b = continue_branch(crossing, [math.sin(-0.5)], -0.5, Continuation(max_step=0.2,
                                                                       lam_max=2.0))
    assert b.status.name == "OK" and b.lam[-1] == 2.0
    events = detect_bifurcations(crossing, b)
    assert [e.kind for e in events] == ["branch_point"]
    e = events[0]
    # det of the bordered Jacobian is ~linear in arclength there; the Illinois tolerance is
    # 1e-10 on arclength, the corrector's 1e-10 on R = O(distance^2) near the BP
    assert abs(e.lam - lam_star) <= 1e-8 and abs(e.x[0] - x_star) <= 1e-8 and e.located


def test_pitchfork_branch_point():
    def pitchfork(x, lam):
        return (np.array([x[0] * (lam - x[0] ** 2)]), np.array([[lam - 3 * x[0] ** 2]]),
                np.array([x[0]]))

    b = continue_branch(pitchfork, [0.0], -1.0, Continuation(lam_max=1.3, max_step=0.3))
    events = detect_bifurcations(pitchfork, b)
    assert [e.kind for e in events] == ["branch_point"]
    assert abs(events[0].lam) <= 1e-10 and abs(events[0].x[0]) <= 1e-12


def test_non_smooth_fold_is_located_at_the_corner():
    """lam = |x| / 2: a V-shaped branch turning by 53 deg at a corner; no smooth fold, so
    the extended system cannot converge and the test-function bracket gives the event.
    (A corner turning by 90 deg or more cannot be passed: the pseudo-arclength hyperplane
    no longer meets the outgoing branch.)"""
    def vee(x, lam):
        return (np.array([0.5 * abs(x[0]) - lam]), np.array([[0.5 if x[0] > 0 else -0.5]]),
                -np.ones(1))

    b = continue_branch(vee, [-2.0], 1.0, Continuation(direction=-1, lam_max=1.0,
                                                       initial_step=0.25, max_step=0.25))
    assert b.status.name == "OK" and b.lam[-1] == 1.0 and b.x[-1, 0] == pytest.approx(2.0)
    assert b.stats["secant_predictions"] >= 1
    events = detect_bifurcations(vee, b, options=BifurcationOptions(kinds=("fold",)))
    assert len(events) == 1 and events[0].method == "test_function"
    assert abs(events[0].lam) <= 1e-9 and abs(events[0].x[0]) <= 1e-9


def synthetic_multipliers(x, lam):
    """Multipliers along lam: a real one crosses -1 at 0.3 (period doubling), a complex
    pair crosses the unit circle at 0.6 (Neimark-Sacker), and a real pair's product crosses
    1 at 0.8 (a neutral saddle, not a bifurcation)."""
    r = math.exp(lam - 0.6)
    return np.array([-1.0 - 0.5 * (lam - 0.3), r * np.exp(1.2j), r * np.exp(-1.2j),
                     0.25 * math.exp(2.0 * (lam - 0.8)), 4.0])


def test_period_doubling_and_neimark_sacker_from_multipliers():
    b = continue_branch(line, [0.0], 0.0, Continuation(max_step=0.17, lam_max=1.0))
    values = branch_test_functions(b, synthetic_multipliers)
    assert set(values) == {"fold", "branch_point", "period_doubling", "neimark_sacker"}
    events = detect_bifurcations(line, b, multipliers=synthetic_multipliers)
    assert [e.kind for e in events] == ["period_doubling", "neimark_sacker"]
    pd, ns = events
    assert abs(pd.lam - 0.3) <= 1e-9 and abs(ns.lam - 0.6) <= 1e-9  # Illinois to 1e-10
    assert abs(min(abs(pd.multipliers + 1.0))) <= 1e-9
    assert abs(np.abs(ns.multipliers[1]) - 1.0) <= 1e-9


def test_multiplier_test_functions_signs():
    assert period_doubling_value([-0.9, 0.5]) > 0 > period_doubling_value([-1.1, 0.5])
    inside = 0.9 * np.exp(np.array([1j, -1j]))
    assert neimark_sacker_value(inside) < 0 < neimark_sacker_value(inside / 0.8)
    assert period_doubling_value([]) == 1.0
    # no overflow with many large multipliers
    assert math.isfinite(period_doubling_value(np.full(2000, -1e300)))


def test_locate_fold_directly_and_options_validation():
    f = locate_fold(s_curve, [0.6], 0.39, [1.0], tol=1e-13)
    # the extended system is regular at the fold: lam error ~ its residual (tol 1e-13)
    assert abs(f.lam - FOLD) <= 1e-13 and f.residual <= 1e-13 and f.iterations <= 8
    with pytest.raises(TypeError, match="valid"):
        BifurcationOptions(kinds=("hopf",))


def test_fold_curve_through_cusp():
    """x^3 - mu x + lam = 0 folds where 3 x^2 = mu, lam = 2 x^3: the fold curve
    lam = +-2 (mu / 3)^(3/2) meets itself at the cusp mu = 0; tracking the upper fold from
    mu = 1 passes the cusp and returns on the lower one."""
    def cusp(x, lam, mu):
        return (x**3 - mu * x + lam, np.diag(3.0 * x**2 - mu), np.ones(1), -x)

    start = locate_fold(lambda x, lam: cusp(x, lam, 1.0)[:3], [0.6], 0.4, [1.0])
    curve = track_folds(cusp, start, 1.0, Continuation(direction=-1, lam_max=1.0,
                                                       max_step=0.2))
    assert curve.branch.status.name == "OK" and curve.mu[-1] == 1.0
    assert curve.lam[0] > 0 > curve.lam[-1]
    np.testing.assert_allclose(np.abs(curve.lam), 2.0 * (curve.mu / 3.0) ** 1.5, atol=1e-9)
    np.testing.assert_allclose(3.0 * curve.x[:, 0] ** 2, curve.mu, atol=1e-9)
    assert curve.mu.min() == pytest.approx(0.0, abs=0.05)  # turned at the cusp


@pytest.mark.validation
def test_bratu_fold_converges_to_the_analytic_value():
    """-u'' = lam e^u on (0, 1), u(0) = u(1) = 0: the fold is lam* = 8 a^2 / cosh^2(a)
    maximised, lam* = 3.513830719125... (Bratu-Gelfand). The second-order finite-difference
    fold converges as h^2: the error ratio between h and h/2 is 4 to within 1 %."""
    import scipy.sparse as sp

    def bratu(n):
        h = 1.0 / (n + 1)
        lap = (sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n)) / h**2).tocsr()

        def fun(u, lam):
            e = np.exp(u)
            return lap @ u - lam * e, (lap - sp.diags(lam * e)).tocsr(), -e
        opts = Continuation(initial_step=0.3, max_step=0.5, x_scale=math.sqrt(n),
                            r_scale="auto")
        b = continue_branch(fun, np.zeros(n), 0.0, opts,  # stop on the upper branch
                            monitor=lambda s: s.tangent[-1] < 0 and s.lam < 2.0)
        return [e.lam for e in detect_bifurcations(fun, b) if e.kind == "fold"]

    a = so.brentq(lambda a: math.tanh(a) - 1.0 / a, 0.5, 2.0, xtol=1e-15)  # d/da = 0
    exact = 8.0 * a * a / math.cosh(a) ** 2
    assert exact == pytest.approx(3.513830719125, abs=1e-12)
    (coarse,), (fine,) = bratu(127), bratu(255)
    ratio = (coarse - exact) / (fine - exact)
    assert ratio == pytest.approx(4.0, rel=0.01)
    assert abs(fine - exact) < 1e-4
