"""Amplitude peaks along HB branches: the Duffing oscillator of the reference list.

``x'' + 0.05 x' + x + 0.1 x^3 = 0.18 cos(W t)``: the single-harmonic closed form
``a^2 [(1 - W^2 + 0.075 a^2)^2 + (0.05 W)^2] = 0.18^2`` peaks at a = 2.84162, W = 1.26663
(/work/shared/reference/README.md, "Nonlinear dynamics"); the peak is where ``da/dW = 0``
on that curve. With more harmonics the peak moves slightly; long time integration
(scipy's solve_ivp) at the located frequency confirms it.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.optimize as so
from scipy.integrate import solve_ivp

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.peaks import locate_peaks, orbit_amplitude
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import continuation_function, make_residual
from rotorsim.solvers.continuation import Continuation, continue_branch
from rotorsim.solvers.continuation_extrema import locate_extrema

C, K3, P = 0.05, 0.1, 0.18
OPTIONS = Continuation(max_step=0.2, lam_max=2.0)


def duffing(harmonics):
    cubic = lambda q, v, tau, w, p: (K3 * q**3, 3 * K3 * q[:, :, None] ** 2, None)  # noqa: E731
    return make_residual(HBProblem(np.eye(1), np.eye(1), C * np.eye(1), nl_dofs=[0],
                                   force=cubic, excitation=[[0.0], [P], [0.0]]), harmonics)


def closed_form_peak():
    """(a, W) with G(a, W) = 0 and dG/dW = 0 for the single-harmonic balance G."""
    def equations(v):
        a, w = v
        s = 1 - w * w + 0.75 * K3 * a * a
        return [a * a * (s * s + (C * w) ** 2) - P * P, -4 * w * s + 2 * C * C * w]
    return so.fsolve(equations, [2.84, 1.27], xtol=1e-14)


def peak(harmonics):
    res = duffing(harmonics)
    branch = continue_branch(continuation_function(res), np.zeros(res.size), 0.5, OPTIONS)
    assert branch.status.name == "OK"
    peaks = locate_peaks(res, branch, 0)
    assert [p.kind for p in peaks] == ["max"] and peaks[0].located
    return res, peaks[0]


@pytest.mark.validation
def test_single_harmonic_peak_equals_the_closed_form():
    a_ref, w_ref = closed_form_peak()
    assert (round(a_ref, 5), round(w_ref, 5)) == (2.84162, 1.26663)   # the reference
    _, p = peak(1)
    # the HB equations with H = 1 are the closed form's; the corrector tolerance 1e-10
    # (scaled residual) bounds the error of the point, the Illinois tolerance 1e-10
    # (scaled arclength) its place along the branch; measured 2e-13 and 1e-11
    assert abs(p.value - a_ref) < 1e-9 * a_ref
    assert abs(p.lam - w_ref) < 1e-8


@pytest.mark.validation
def test_multi_harmonic_peak_is_confirmed_by_shooting():
    res, p = peak(11)
    a1 = peak(1)[1].value
    assert 1e-3 < abs(p.value - a1) / a1 < 3e-2      # 1.25 % off the single harmonic
    w = p.lam
    X = res.expand(p.x, w)
    state = [X[0, 0] + X[1::2, 0].sum(), w * (np.arange(1, 12) * X[2::2, 0]).sum()]
    T = 2 * np.pi / w

    def period_map(z0):
        sol = solve_ivp(lambda t, z: [z[1], P * np.cos(w * t) - C * z[1] - z[0]
                                      - K3 * z[0] ** 3],
                        (0.0, T), z0, method="DOP853", rtol=1e-12, atol=1e-13,
                        dense_output=True)
        assert sol.success
        return sol

    # the peak sits next to the upper fold, where a multiplier approaches 1: a long
    # integration from the HB state converges (or drifts) too slowly to be a reference at
    # 1e-9, and whether it drifts depends on the last bits of the located frequency.
    # Shooting (Newton on the period map, finite-difference Jacobian) finds the exact
    # periodic orbit whatever its stability.
    z = np.array(state, dtype=float)
    for _ in range(8):
        g = period_map(z).y[:, -1] - z
        J = np.empty((2, 2))
        for k in range(2):
            dz = np.zeros(2)
            dz[k] = 1e-7 * max(1.0, abs(z[k]))
            J[:, k] = (period_map(z + dz).y[:, -1] - (z + dz) - g) / dz[k]
        z = z - np.linalg.solve(J, g)
        if np.max(np.abs(g)) < 1e-12:
            break
    q = period_map(z).sol(np.linspace(0.0, T, 4001))[0]
    i = int(np.argmax(np.abs(q)))
    amplitude = max(abs(q[i]), np.polyfit([-1, 0, 1], q[i - 1:i + 2], 2)[2]
                    - np.polyfit([-1, 0, 1], q[i - 1:i + 2], 2)[1] ** 2
                    / (4 * np.polyfit([-1, 0, 1], q[i - 1:i + 2], 2)[0]))
    # H = 11 truncation (H = 7 is off by 7e-8: the 9th harmonic), the ODE tolerance and
    # the sampled maximum
    assert abs(amplitude - p.value) < 1e-9 * p.value


def test_orbit_amplitude_is_the_maximum_of_the_norm():
    X = np.array([[0.1, 0.0], [1.0, 0.0], [0.0, 0.5], [0.2, 0.0], [0.0, 0.1]])
    tau = np.linspace(0, 2 * np.pi, 200001)
    q = np.stack([0.1 + np.cos(tau) + 0.2 * np.cos(2 * tau),
                  0.5 * np.sin(tau) + 0.1 * np.sin(2 * tau)], axis=1)
    dense = np.sqrt((q**2).sum(axis=1)).max()
    # the dense grid misses the maximum by O(spacing^2) = 1e-10
    assert orbit_amplitude(X) == pytest.approx(dense, abs=1e-9)
    assert orbit_amplitude(X[:, :1]) == pytest.approx(1.3, abs=1e-12)


def test_minima_and_bad_input():
    res = duffing(1)
    branch = continue_branch(continuation_function(res), np.zeros(res.size), 0.5, OPTIONS)
    # the amplitude falls monotonically from the peak over both folds: no minimum
    both = locate_peaks(res, branch, [0], kinds=("max", "min"))
    assert [p.kind for p in both] == ["max"]
    with pytest.raises(ModelError, match="dofs"):
        locate_peaks(res, branch, 3)
    with pytest.raises(TypeError, match="unknown extremum kinds"):
        locate_extrema(continuation_function(res), branch, lambda x, lam: 0.0,
                       kinds=("peak",))
