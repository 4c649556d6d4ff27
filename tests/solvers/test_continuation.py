"""Pseudo-arclength continuation: folds, closed branches, bounds, scaling, failures."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.solvers.continuation import Continuation, continue_branch


def circle(x, lam):
    """x^2 + lam^2 = 1: two folds (lam = +-1), a closed branch."""
    return np.array([x[0] ** 2 + lam**2 - 1.0]), np.array([[2.0 * x[0]]]), np.array([2.0 * lam])


def s_curve(x, lam):
    """x^3 - x + lam = 0: folds at lam = +-2 / (3 sqrt 3)."""
    return x**3 - x + lam, np.diag(3.0 * x**2 - 1.0), np.ones(1)


def ellipse_2d(x, lam):
    """A 2-unknown closed curve in metres-against-kilometres units: x0 = 1000 x1,
    (x1 / 2)^2 + lam^2 = 1 (x0 ~ 2000, x1 ~ 2)."""
    r = np.array([x[0] - 1000.0 * x[1], 0.25 * x[1] ** 2 + lam**2 - 1.0])
    J = np.array([[1.0, -1000.0], [0.0, 0.5 * x[1]]])
    return r, J, np.array([0.0, 2.0 * lam])


def test_circle_passes_both_folds_and_closes():
    b = continue_branch(circle, [0.9], 0.0, Continuation(initial_step=0.1, max_step=0.3))
    assert b.status == Status.OK and b.reason == "closed loop"
    # every point on the circle to the corrector tolerance (1e-10 on |R|)
    assert np.max(np.abs(b.x[:, 0] ** 2 + b.lam**2 - 1.0)) <= 1e-10
    assert b.x[0, 0] == pytest.approx(1.0, abs=1e-12)  # corrected at fixed lam = 0
    signs = np.sign(b.tangents[:, -1])
    assert np.count_nonzero(np.diff(signs)) == 2  # lam turns at both folds
    assert b.lam.max() > 0.95 and b.lam.min() < -0.95 and b.x[:, 0].min() < -0.95
    # closed: the last chord passes the start; total arclength ~ 2 pi
    assert b.arclength()[-1] == pytest.approx(2.0 * math.pi, abs=0.3)
    assert b.lam[1] > 0  # direction +1
    back = continue_branch(circle, [0.9], 0.0, Continuation(direction=-1, max_step=0.3))
    assert back.lam[1] < 0 and back.reason == "closed loop"


def test_s_curve_both_directions_end_on_bounds():
    opts = Continuation(initial_step=0.05, max_step=0.2, lam_min=-1.0, lam_max=1.0)
    down = continue_branch(s_curve, [-1.3], 1.0, opts.__class__(**{**opts.__dict__,
                                                                   "direction": -1}))
    up = continue_branch(s_curve, [1.3], -1.0, opts)
    for b, end in ((down, -1.0), (up, 1.0)):
        assert b.status == Status.OK and b.lam[-1] == end  # landed exactly on the bound
        assert np.max(np.abs(b.x[:, 0] ** 3 - b.x[:, 0] + b.lam)) <= 1e-10
        assert np.count_nonzero(np.diff(np.sign(b.tangents[:, -1]))) == 2
    # the upper/lower outer branches: x(lam = -1) > 1 going down, x(lam = 1) < -1 going up
    assert down.x[-1, 0] > 1.0 and up.x[-1, 0] < -1.0
    assert down.stats["points"] == len(down) and down.stats["factorizations"] > len(down)


def test_scaling_makes_mixed_units_trace_like_the_unit_problem():
    """With u = x1 / 2 the ellipse is the circle u^2 + lam^2 = 1 and x0 = 2000 u; the
    scales (2000 sqrt 2, 2 sqrt 2) make its scaled arclength du^2 + dlam^2, so it is traced
    at the same points as the 1-unknown circle with the same steps."""
    opts = Continuation(initial_step=0.1, max_step=0.2,
                        x_scale=(2000.0 * math.sqrt(2.0), 2.0 * math.sqrt(2.0)))
    b = continue_branch(ellipse_2d, [1800.0, 1.8], 0.0, opts)
    ref = continue_branch(circle, [0.9], 0.0, Continuation(initial_step=0.1, max_step=0.2))
    assert b.reason == ref.reason == "closed loop"
    assert len(b) == len(ref)
    np.testing.assert_allclose(b.x[:, 1] / 2.0, ref.x[:, 0], atol=1e-9)
    np.testing.assert_allclose(b.lam, ref.lam, atol=1e-9)
    auto = continue_branch(ellipse_2d, [1800.0, 1.8], 0.0,
                           Continuation(x_scale="auto", r_scale="auto", max_step=0.2))
    assert auto.reason == "closed loop" and np.all(auto.x_scale == 1800.0)
    assert np.max(np.abs(auto.x[:, 0] - 1000.0 * auto.x[:, 1])) <= 1e-10 * 2000.0


def test_step_adapts_to_curvature_and_iterations():
    """Flat parts of the S-curve take max_step; steps shrink around the folds."""
    opts = Continuation(initial_step=0.01, max_step=0.5, direction=-1, lam_min=-3.0,
                        lam_max=3.0)
    b = continue_branch(s_curve, [-1.67], 3.0, opts)
    assert b.status == Status.OK and b.lam[-1] == -3.0
    assert b.step_sizes.max() == 0.5  # grew from 0.01 on the nearly straight outer parts
    near_fold = np.abs(np.abs(b.x[:, 0]) - 1 / math.sqrt(3)) < 0.2  # folds at x = +-1/sqrt 3
    assert near_fold.sum() >= 4 and b.step_sizes[near_fold].max() < 0.15
    assert b.stats["max_iterations"] <= opts.max_iter


def test_branch_through_kink_uses_secant_and_rejects_steps():
    """x + 9 max(x, 0) = lam: slope dx/dlam jumps from 1 to 1/10 at x = 0, a corner of
    0.68 rad > max_angle; halving the step does not reduce that turn."""
    def kink(x, lam):
        on = x[0] > 0.0
        return (np.array([x[0] + 9.0 * max(x[0], 0.0) - lam]),
                np.array([[10.0 if on else 1.0]]), np.array([-1.0]))

    b = continue_branch(kink, [-1.0], -1.0, Continuation(initial_step=0.3, max_step=0.3,
                                                         lam_max=1.0))
    assert b.status == Status.OK and b.lam[-1] == 1.0
    np.testing.assert_allclose(b.x[:, 0] + 9.0 * np.maximum(b.x[:, 0], 0.0), b.lam,
                               atol=1e-12)
    assert b.stats["rejected_steps"] >= 1 and b.stats["secant_predictions"] >= 1
    assert not b.smooth.all()
    assert np.all(np.diff(b.lam) > 0)  # no fold, no back-tracking across the corner


def test_contact_law_with_infinite_curvature():
    """x + 5 max(x - 0.2, 0)^1.5 = lam (a Hertz-like contact onset at x = 0.2): C^1 with
    unbounded curvature at onset; the branch passes with all points converged."""
    def contact(x, lam):
        g = max(x[0] - 0.2, 0.0)
        return (np.array([x[0] + 5.0 * g**1.5 - lam]), np.array([[1.0 + 7.5 * math.sqrt(g)]]),
                np.array([-1.0]))

    b = continue_branch(contact, [0.0], 0.0, Continuation(initial_step=0.05, max_step=0.2,
                                                          lam_max=3.0))
    assert b.status == Status.OK and b.lam[-1] == 3.0
    gap = np.maximum(b.x[:, 0] - 0.2, 0.0)
    assert np.max(np.abs(b.x[:, 0] + 5.0 * gap**1.5 - b.lam)) <= 1e-10
    assert np.all(np.diff(b.lam) > 0)


@pytest.mark.parametrize("failure", ["raise", "nan"])
def test_branch_that_cannot_continue_keeps_its_points(failure):
    """R = x - lam, undefined beyond lam = 0.5: the branch creeps to the edge until the
    step falls below min_step, then stops with a failure status and keeps every point."""
    def edge(x, lam):
        if lam > 0.5:
            if failure == "raise":
                raise ValueError("model undefined beyond lam = 0.5")
            return np.array([math.nan]), np.eye(1), np.array([-1.0])
        return x - lam, np.eye(1), np.array([-1.0])

    opts = Continuation(initial_step=0.1, max_step=0.1, min_step=1e-6)
    b = continue_branch(edge, [0.0], 0.0, opts)
    assert b.status == Status.FAILED
    assert "min_step" in b.reason and ("undefined" in b.reason or "not finite" in b.reason)
    assert np.all(b.lam <= 0.5) and len(b) > 5
    # the last point is within about two minimal steps of the edge (scaled step along the
    # tangent (1, 1)/sqrt 2 moves lam by ds / sqrt 2)
    assert 0.5 - b.lam[-1] < 2e-6
    # R = x - lam holds to the corrector tolerance (1e-10), not to the last bit of the
    # LU solve of the bordered system
    np.testing.assert_allclose(b.x[:, 0], b.lam, rtol=0, atol=1e-10)
    assert b.stats["rejected_steps"] >= 10


def test_max_points_and_monitor_end_the_branch_with_ok():
    b = continue_branch(circle, [1.0], 0.0, Continuation(max_points=7))
    assert len(b) == 7 and b.status == Status.OK and b.reason == "max_points reached"
    seen = []
    b = continue_branch(circle, [1.0], 0.0, Continuation(),
                        monitor=lambda s: seen.append(s.point) or s.lam > 0.5)
    assert b.reason == "stopped by monitor" and b.lam[-1] > 0.5 >= b.lam[-2]
    assert seen == list(range(1, len(b)))


def test_start_on_bound_and_invalid_inputs():
    b = continue_branch(s_curve, [-1.3], 1.0, Continuation(lam_max=1.0))
    assert len(b) == 1 and b.reason == "lam_max = 1 reached"
    with pytest.raises(ModelError, match="min_step"):
        Continuation(min_step=1.0, initial_step=0.1)
    with pytest.raises(ModelError, match="direction"):
        Continuation(direction=0)
    with pytest.raises(ModelError, match="x_scale"):
        Continuation(x_scale=(1.0, -2.0))
    with pytest.raises(ModelError, match="outside"):
        continue_branch(s_curve, [0.0], 2.0, Continuation(lam_max=1.0))
    with pytest.raises(ModelError, match="2 entries"):
        continue_branch(s_curve, [0.0], 0.0, Continuation(x_scale=(1.0, 2.0)))
    with pytest.raises(ConvergenceError, match="starting point"):  # no real root at lam=1
        continue_branch(circle, [0.5], 1.5, Continuation())


def test_sparse_problem_matches_dense_one():
    """The same tridiagonal Bratu-like system as dense and as CSR gives the same branch."""
    import scipy.sparse as sp

    def make(sparse):
        n, h = 150, 1.0 / 151  # m + 1 > DENSE_THRESHOLD: SuperLU
        lap = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n)) / h**2

        def fun(u, lam):
            e = np.exp(u)
            J = lap - sp.diags(lam * e)
            return lap @ u - lam * e, (J.tocsr() if sparse else J.toarray()), -e
        return fun

    opts = Continuation(initial_step=0.5, max_step=1.0, max_points=20, x_scale=5.0)
    dense = continue_branch(make(False), np.zeros(150), 0.0, opts)
    sparse = continue_branch(make(True), np.zeros(150), 0.0, opts)
    assert len(dense) == len(sparse) == 20
    np.testing.assert_allclose(sparse.x, dense.x, atol=1e-9)
    np.testing.assert_array_equal(sparse.det_sign, dense.det_sign)
    assert np.count_nonzero(np.diff(np.sign(sparse.tangents[:, -1]))) == 1  # the Bratu fold


@pytest.mark.parametrize(("name", "value"), [("max_points", 2.5), ("max_points", 1),
                                             ("max_points", float("inf")), ("max_iter", 0),
                                             ("max_iter", True), ("max_backtracks", 1.5),
                                             ("target_iterations", "4")])
def test_integer_options_must_be_integers(name, value):
    """Issue 12: max_points = inf used to trace forever and 2.5 passed unnoticed."""
    with pytest.raises(ModelError, match=f"Continuation: {name} must be an integer"):
        Continuation(**{name: value})
