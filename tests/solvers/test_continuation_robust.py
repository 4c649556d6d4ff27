"""Continuation that passes non-smooth resonances: stalled correctors accepted within
``stall_tol``, steps that grow with the solution (``relative_step``), and the local
parametrisation tried when the predictor's normal plane misses the branch."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.errors import ModelError
from rotorsim.solvers.continuation import Continuation, continue_branch
from rotorsim.solvers.continuation_core import CorrectorOptions, ScaledSystem, correct
from rotorsim.solvers.stats import Stats


def slow_newton(x, lam):
    """``R = x - lam`` with a Jacobian 10x too large: Newton converges linearly (0.9 per
    iteration), as it does where a contact-onset sample makes the residual non-Lipschitz."""
    return x - lam, np.eye(1) * 10.0, -np.ones(1)


def test_a_stalled_corrector_is_accepted_within_stall_tol_and_flagged():
    system = ScaledSystem(slow_newton, np.ones(1), np.ones(1), 1.0)
    border = np.array([0.0, 1.0])                      # lam fixed at 0.5
    y0 = np.array([1.5, 0.5])
    strict = correct(system, y0, border, 0.5, CorrectorOptions(tol=1e-12, max_iter=10),
                     Stats())
    assert not strict.converged                        # 0.9**10 of 1.0 is far from 1e-12
    miss = abs(float(strict.y[0]) - 0.5)
    assert miss == pytest.approx(0.9 ** 10, rel=1e-12)
    loose = correct(system, y0, border, 0.5,
                    CorrectorOptions(tol=1e-12, max_iter=10, stall_tol=0.5), Stats())
    assert loose.converged and loose.relaxed           # accepted, and says so
    # a stall above stall_tol is still a failure
    tight = correct(system, y0, border, 0.5,
                    CorrectorOptions(tol=1e-12, max_iter=10, stall_tol=0.1), Stats())
    assert not tight.converged


def test_relaxed_points_are_counted_on_the_branch():
    opts = Continuation(max_step=0.05, lam_min=0.0, lam_max=1.0, tol=1e-12, max_iter=4,
                        stall_tol=1e-1)
    branch = continue_branch(slow_newton, [0.0], 0.0, opts)
    assert branch.reason == "lam_max = 1 reached"
    assert branch.stats["relaxed_points"] >= 1
    # every point still sits on x = lam within the stall tolerance
    assert np.all(np.abs(branch.x[:, 0] - branch.lam) <= 1e-1)


def test_stall_tol_below_tol_is_refused():
    with pytest.raises(ModelError, match="stall_tol"):
        Continuation(tol=1e-8, stall_tol=1e-9)


def growing(x, lam):
    """A response that grows a hundredfold along the branch: ``x = lam^2`` (x_scale 1)."""
    return x - lam ** 2, np.eye(1), -2.0 * lam * np.ones(1)


def test_relative_steps_follow_a_growing_response():
    """With ``relative_step`` the largest step is ``max_step * max(1, |x / x_scale|)``: a
    branch from x = 1 to x = 100 takes about log(100) / max_step points instead of about
    100 / max_step."""
    common = {"max_step": 0.1, "initial_step": 0.1, "lam_min": 1.0, "lam_max": 10.0,
              "max_points": 5000, "max_angle": 1.0}
    fixed = continue_branch(growing, [1.0], 1.0, Continuation(**common))
    relative = continue_branch(growing, [1.0], 1.0, Continuation(relative_step=True,
                                                                 **common))
    assert fixed.reason == relative.reason == "lam_max = 10 reached"
    assert len(fixed) > 900                     # the arclength is about 99 in x
    assert len(relative) < 0.1 * len(fixed)
    # the steps are capped relative to the solution: ds <= max_step * max(1, x)
    ds = relative.step_sizes[1:]
    cap = 0.1 * np.maximum(1.0, relative.x[:-1, 0])
    assert np.all(ds <= cap * (1 + 1e-12))
    # both trace the same curve
    assert np.allclose(relative.x[:, 0], relative.lam ** 2, rtol=1e-9)


def corner(x, lam):
    """``x = |lam - 0.5|``: a V-shaped branch whose tangent jumps at ``lam = 0.5``."""
    return x - abs(lam - 0.5), np.eye(1), -np.sign(lam - 0.5) * np.ones(1)


def test_a_corner_is_passed():
    branch = continue_branch(corner, [0.5], 0.0, Continuation(max_step=0.05, lam_min=0.0,
                                                              lam_max=1.0))
    assert branch.reason == "lam_max = 1 reached"
    assert np.allclose(branch.x[:, 0], np.abs(branch.lam - 0.5), atol=1e-10)
    assert not branch.smooth.all()              # the corner is marked
    assert math.isclose(float(branch.lam[-1]), 1.0)
