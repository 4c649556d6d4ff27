"""Radau IIA (order 5) with step control: observed order against closed forms, the accuracy
asked is met, the low-rank (LocalMatrix) path equals the general one, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorsim.errors import ModelError
from rotorsim.time_integration.hermite import quintic_hermite
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.local_tangent import LocalMatrix
from rotorsim.time_integration.motion_scale import MotionScale
from rotorsim.time_integration.output import OutputSpec
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.radau import RK_MATRIX, Radau

M_, C_, K_, W_ = 1.0, 0.4, 100.0, 7.0
"""Damped oscillator ``q'' + 0.4 q' + 100 q = cos(7 t)`` from rest."""


def oscillator_exact(t):
    """Closed form of the oscillator from ``q = v = 0``: steady response plus the damped
    free vibration that cancels it at ``t = 0``."""
    X = 1.0 / (K_ - M_ * W_**2 + 1j * C_ * W_)
    wn = math.sqrt(K_ / M_)
    zeta = C_ / (2.0 * math.sqrt(K_ * M_))
    wd = wn * math.sqrt(1.0 - zeta**2)
    A = -X.real
    B = (-(1j * W_ * X).real + zeta * wn * A) / wd
    steady = (X * np.exp(1j * W_ * t)).real
    return steady + np.exp(-zeta * wn * t) * (A * np.cos(wd * t) + B * np.sin(wd * t))


def oscillator():
    return SecondOrderProblem(mass=np.eye(1) * M_, stiffness=np.eye(1) * K_,
                              damping=np.eye(1) * C_,
                              load=lambda t: np.array([math.cos(W_ * t)]))


def run(problem, rtol, times, q0=(0.0,), v0=(0.0,), **options):
    return integrate(problem, Radau(rtol=rtol, **options), (0.0, float(times[-1])), q0, v0,
                     dt=1e-2, output=OutputSpec(times=times))


def test_coefficients_are_radau_iia():
    # order conditions B(5) and C(3): sum b_i c_i^(k-1) = 1/k, sum_j a_ij c_j^(k-1) = c_i^k/k
    c = RK_MATRIX.sum(axis=1)
    b = RK_MATRIX[-1]
    assert np.allclose(c, [(4 - math.sqrt(6)) / 10, (4 + math.sqrt(6)) / 10, 1.0], atol=1e-15)
    for k in range(1, 6):
        assert b @ c ** (k - 1) == pytest.approx(1.0 / k, abs=1e-14)
    for k in range(1, 4):
        assert np.allclose(RK_MATRIX @ c ** (k - 1), c**k / k, atol=1e-14)


@pytest.mark.validation
def test_observed_order_on_damped_oscillator_is_five():
    # error against the closed form versus the number of steps over rtol 1e-4 ... 1e-8:
    # error ~ steps^-p with p = 5 for Radau IIA (Hairer & Wanner IV.5); 4.5 allows for the
    # step-control pattern, which changes with rtol
    times = np.linspace(0.0, 3.0, 31)
    exact = oscillator_exact(times)
    steps, errors = [], []
    for rtol in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8):
        res = run(oscillator(), rtol, times)
        errors.append(np.max(np.abs(res.q[:, 0] - exact)) / np.ptp(exact))
        steps.append(res.stats["steps"])
        assert errors[-1] <= rtol  # the accuracy asked, relative to the motion
    slope = -np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert 4.5 <= slope <= 6.0


@pytest.mark.validation
def test_jeffcott_rotor_forward_whirl_matches_closed_form():
    # Jeffcott rotor q = (x, y), gyroscopic-free, unbalance m e W^2 (cos, sin): the steady
    # orbit radius is m e W^2 / |k - m W^2 + i c W|; start on the steady orbit
    m, c, k, me, W = 2.0, 8.0, 2.0e4, 1e-3, 60.0
    X = me * W**2 / (k - m * W**2 + 1j * c * W)
    p = SecondOrderProblem(mass=m * np.eye(2), stiffness=k * np.eye(2), damping=c * np.eye(2),
                           load=lambda t: me * W**2 * np.array([math.cos(W * t),
                                                                math.sin(W * t)]))
    times = np.linspace(0.0, 0.5, 51)
    z0, dz0 = X, 1j * W * X
    res = integrate(p, Radau(rtol=1e-6), (0.0, 0.5), [z0.real, z0.imag],
                    [dz0.real, dz0.imag], dt=1e-3, output=OutputSpec(times=times))
    exact = X * np.exp(1j * W * times)
    err = np.max(np.abs(res.q[:, 0] + 1j * res.q[:, 1] - exact)) / abs(X)
    assert err <= 1e-6


def duffing(local):
    """Two-DOF Duffing chain; the cubic spring's tangent as a LocalMatrix or dense."""
    def restoring(q, v, t):
        r = np.array([0.0, 4e3 * q[1] ** 3])
        kt = np.array([[0.0, 0.0], [0.0, 1.2e4 * q[1] ** 2]])
        if local:
            return r, LocalMatrix(2, np.array([1]), kt[1:, 1:]), None
        return r, kt, None

    K = np.array([[200.0, -100.0], [-100.0, 100.0]])
    return SecondOrderProblem(np.eye(2), K, 0.2 * np.eye(2), restoring=restoring,
                              load=lambda t: np.array([3.0 * math.cos(9.0 * t), 0.0]))


@pytest.mark.validation
def test_duffing_against_solve_ivp_reference():
    # independent reference: solve_ivp LSODA at rtol 1e-12 on the first-order form
    p = duffing(local=True)
    times = np.linspace(0.0, 4.0, 81)

    def rhs(t, y):
        q, v = y[:2], y[2:]
        return np.concatenate([v, -p.forces(q, v, t).net])

    ref = solve_ivp(rhs, (0.0, 4.0), np.zeros(4), method="LSODA", rtol=1e-12, atol=1e-14,
                    t_eval=times).y[:2].T
    motion = np.max(np.abs(ref))
    for rtol in (1e-3, 1e-6):
        res = run(p, rtol, times, q0=(0.0, 0.0), v0=(0.0, 0.0))
        assert np.max(np.abs(res.q - ref)) / motion <= rtol


@pytest.mark.verification
def test_local_tangent_path_equals_dense_tangent_path():
    # the Woodbury update on the nonlinear DOFs solves the same Newton systems as the
    # full tangent: equal to the Newton tolerance, far below the error asked
    times = np.linspace(0.0, 2.0, 21)
    a = run(duffing(local=True), 1e-6, times, q0=(0.0, 0.0), v0=(0.0, 0.0))
    b = run(duffing(local=False), 1e-6, times, q0=(0.0, 0.0), v0=(0.0, 0.0))
    assert np.max(np.abs(a.q - b.q)) <= 1e-3 * 1e-6 * np.max(np.abs(b.q))


def test_factorisations_are_reused_at_constant_speed():
    res = run(oscillator(), 1e-6, np.linspace(0.0, 3.0, 4))
    # two shifts per step size on the ladder, a few sizes in all, not one per step
    assert res.stats["factorizations"] <= res.stats["steps"] / 3


def test_quintic_hermite_reproduces_quintics():
    coeffs = np.array([0.3, -1.0, 2.0, 0.5, -0.7, 0.2])

    def poly(t, d=0):
        c = np.polynomial.polynomial.polyder(coeffs, d) if d else coeffs
        return np.polynomial.polynomial.polyval(t, c)

    from rotorsim.time_integration.base import State

    def state(t):
        return State(t, np.array([poly(t)]), np.array([poly(t, 1)]),
                     np.array([poly(t, 2)]), np.zeros(1))

    t = np.linspace(0.4, 1.7, 7)
    q, v = quintic_hermite(state(0.4), state(1.7), t, np.arange(1))
    assert np.allclose(q[:, 0], poly(t), atol=1e-12)
    assert np.allclose(v[:, 0], poly(t, 1), atol=1e-11)


def test_motion_scale_ignores_the_static_offset():
    # rtol is relative to the motion |q - q0|, not to the sag q0 itself
    s = MotionScale.of(None, np.array([1e-3, 0.0]))
    assert s.scale(np.array([2e-6, 1e-6])) == 2e-6
    assert s.scale(np.zeros(2)) == pytest.approx(1e-11)  # floor: 1e-8 of the offset


@pytest.mark.parametrize("options, culprit", [
    ({"rtol": 0.0}, "rtol"), ({"rtol": 1.5}, "rtol"), ({"max_newton": 1}, "max_newton"),
    ({"max_growth": 0.5}, "max_growth")])
def test_bad_options_are_refused(options, culprit):
    with pytest.raises(ModelError, match=culprit):
        Radau(**options)


def test_wrong_number_of_weights_is_refused():
    with pytest.raises(ModelError, match="weights"):
        run(oscillator(), 1e-4, np.linspace(0, 1, 3), weights=(1.0, 1.0))


def test_exhausted_rejections_raise_and_name_the_time():
    """With one retry allowed (the least accepted), a first step far too long for rtol
    1e-12 is rejected twice and the run stops with a ConvergenceError naming the step size
    and the time (the retry logic shared with exponential collocation,
    ``time_integration/base.py``)."""
    from rotorsim.errors import ConvergenceError

    with pytest.raises(ConvergenceError, match=r"step size .* after 1 rejections at t = 0 s"):
        integrate(oscillator(), Radau(rtol=1e-12, max_rejections=1), (0.0, 1.0), [1.0],
                  [0.0], dt=0.5)
