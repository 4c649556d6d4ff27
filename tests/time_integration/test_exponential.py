"""Exponential collocation on the nonlinear DOFs: the phi functions, exactness on a linear
problem (closed form), observed order 4 and the accuracy asked on a forced Duffing
oscillator (against solve_ivp at tight tolerance), dense output, resume."""

from __future__ import annotations

import math
from math import factorial

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.time_integration.exponential import Exponential
from rotorsim.time_integration.exponential_modes import (
    HarmonicLoad,
    LinearModes,
    lobatto_nodes,
    phi_functions,
)
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.output import OutputSpec
from rotorsim.time_integration.problem import SecondOrderProblem

M = np.array([[2.0, 0.0], [0.0, 1.0]])
K = np.array([[300.0, -100.0], [-100.0, 100.0]])
C = 0.002 * K
W = 7.0
F = np.array([0.0, 40.0 + 0j])
"""Two masses on springs, Rayleigh damping, a harmonic load ``Re(F e^{i W t})`` on the second
and a local spring on the first (``k1 q + k3 q^3``)."""


class LocalSpring:
    """``r = k1 q0 + k3 q0^3`` on DOF 0, evaluated in batches as a rotor's bearings are."""

    def __init__(self, k1: float, k3: float) -> None:
        self.k1, self.k3 = k1, k3
        self.dofs = np.array([0])

    def batch(self, q, v, t):
        x = q[:, :1]
        r = self.k1 * x + self.k3 * x**3
        kt = (self.k1 + 3.0 * self.k3 * x**2)[:, :, None]
        return self.dofs, r, kt, np.zeros_like(kt)

    def __call__(self, q, v, t):
        _, r, kt, _ = self.batch(q[None, :], v[None, :], np.array([t]))
        full = np.zeros(2)
        full[0] = r[0, 0]
        return full, np.pad(kt[0], ((0, 1), (0, 1))), None


def problem(k1: float, k3: float) -> tuple[SecondOrderProblem, HarmonicLoad]:
    load = HarmonicLoad(np.zeros(2), F, W)
    return SecondOrderProblem(mass=M, stiffness=K, damping=C, restoring=LocalSpring(k1, k3),
                              load=load), load


def reference(k1: float, k3: float, times):
    """solve_ivp (DOP853, rtol 1e-12) of the same equations from rest."""
    minv = np.linalg.inv(M)

    def rhs(t, y):
        q, v = y[:2], y[2:]
        r = np.array([k1 * q[0] + k3 * q[0] ** 3, 0.0])
        f = (F * np.exp(1j * W * t)).real
        return np.concatenate([v, minv @ (f - K @ q - C @ v - r)])

    sol = solve_ivp(rhs, (0.0, times[-1]), np.zeros(4), method="DOP853", rtol=1e-12,
                    atol=1e-14, t_eval=times)
    return sol.y[:2].T


def test_phi_functions_match_their_integrals():
    z = np.array([0.0, 1e-3 + 2e-3j, 0.5 - 0.7j, 1.2, -3.0 + 40.0j, 2.0j, -50.0 - 0.1j])
    P = phi_functions(z, 4)
    for k in range(1, 5):
        for i, x in enumerate(z):
            def part(th, im, x=x, k=k):
                val = np.exp((1 - th) * x) * th ** (k - 1) / factorial(k - 1)
                return val.imag if im else val.real
            exact = quad(part, 0, 1, args=(0,), epsabs=1e-15)[0] + \
                1j * quad(part, 0, 1, args=(1,), epsabs=1e-15)[0]
            # phi_k(z) = int_0^1 e^{(1-th) z} th^(k-1)/(k-1)! dth (Hochbruck & Ostermann 2010)
            assert abs(P[k, i] - exact) <= 1e-12 * abs(exact)


@pytest.mark.parametrize("spread", [0.9, 3.0])  # all in the Taylor region / mixed
def test_phi_functions_match_a_long_double_reference(spread):
    # the Taylor part (powers by doubling blocks, the sums as one real product) and the
    # recurrence against the same formulas in 80-bit arithmetic (numpy longdouble): the
    # series terms are positive multiples of z^m with at most five rounded factors each and
    # the recurrence, used at |z| >= 1, loses at most k / |z| of a digit per level, so
    # 1e-14 relative is about 50 units of the last place and leaves room for any libm
    rng = np.random.default_rng(7)
    z = spread * (rng.uniform(-1, 1, 400) + 1j * rng.uniform(-1, 1, 400)) / math.sqrt(2)
    P = phi_functions(z, 4)
    zl = z.astype(np.clongdouble)
    small = np.abs(z) < 1.0
    ref = [np.exp(zl)]
    for k in range(1, 5):
        series = sum(zl ** m / factorial(m + k) for m in range(40))
        recurrence = (ref[-1] - np.longdouble(1) / factorial(k - 1)) / zl
        ref.append(np.where(small, series, recurrence))
    for k in range(5):
        assert np.max(np.abs(P[k] - ref[k]) / np.abs(ref[k])) <= 1e-14


def test_lobatto_nodes_are_the_roots_of_p_prime():
    x = lobatto_nodes(3)
    assert np.allclose(x, [0.0, (1 - 1 / math.sqrt(5)) / 2, (1 + 1 / math.sqrt(5)) / 2, 1.0],
                       atol=1e-15)


def test_linear_local_spring_is_integrated_exactly_whatever_the_step():
    # with a linear local spring rho vanishes: the steps are the exact propagator, so even
    # steps of 0.1 s (a tenth of the slowest period) reproduce solve_ivp at rtol 1e-12 to
    # its own accuracy (1e-9 of the motion)
    p, load = problem(200.0, 0.0)
    times = np.linspace(0.0, 2.0, 21)
    res = integrate(p, Exponential(load, fixed=True), (0.0, 2.0), [0.0, 0.0], [0.0, 0.0],
                    dt=0.1, output=OutputSpec(times=times))
    ref = reference(200.0, 0.0, times)
    assert np.max(np.abs(res.q - ref)) <= 1e-9 * np.ptp(ref)


def test_observed_order_is_four_on_a_forced_duffing_oscillator():
    p, load = problem(200.0, 2e4)
    T = 1.0
    ref = reference(200.0, 2e4, np.array([0.0, T]))[-1]
    errors = []
    for h in (0.04, 0.02, 0.01):
        res = integrate(p, Exponential(load, fixed=True), (0.0, T), [0.0, 0.0], [0.0, 0.0],
                        dt=h, output=OutputSpec(times=[T]))
        errors.append(float(np.max(np.abs(res.q[-1] - ref))))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # declared order s + 1 = 4: the interpolant of rho through 4 Lobatto nodes is cubic
    assert np.all(orders > 3.7), (errors, orders)


def test_error_control_meets_the_accuracy_asked_and_dense_output_agrees():
    p, load = problem(200.0, 2e4)
    times = np.linspace(0.0, 1.0, 37)
    ref = reference(200.0, 2e4, times)
    motion = float(np.max(np.abs(ref)))
    for rtol in (1e-3, 1e-5):
        res = integrate(p, Exponential(load, rtol=rtol), (0.0, 1.0), [0.0, 0.0], [0.0, 0.0],
                        dt=1e-3, output=OutputSpec(times=times))
        # rtol bounds the error relative to the motion (local errors held to 0.1 rtol)
        assert np.max(np.abs(res.q - ref)) <= rtol * motion


def test_bad_input_and_a_wrong_load_are_refused():
    p, load = problem(200.0, 0.0)
    with pytest.raises(ModelError, match="stages"):
        Exponential(load, stages=9)
    wrong = HarmonicLoad(np.ones(2), F, W)
    with pytest.raises(ModelError, match="load does not match"):
        integrate(p, Exponential(wrong), (0.0, 0.1), [0.0, 0.0], [0.0, 0.0], dt=1e-2)
    with pytest.raises(ModelError, match="batch"):
        plain = SecondOrderProblem(mass=M, stiffness=K, load=load,
                                   restoring=lambda q, v, t: (np.zeros(2), None, None))
        integrate(plain, Exponential(load), (0.0, 0.1), [0.0, 0.0], [0.0, 0.0], dt=1e-2)
    assert issubclass(ConvergenceError, Exception)


def test_a_continued_run_equals_an_uninterrupted_one():
    p, load = problem(200.0, 2e4)
    stepper = Exponential(load, rtol=1e-4)
    whole = integrate(p, stepper, (0.0, 0.6), [0.0, 0.0], [0.0, 0.0], dt=1e-3,
                      output=OutputSpec(times=[0.6]))
    first = integrate(p, stepper, (0.0, 0.3), [0.0, 0.0], [0.0, 0.0], dt=1e-3,
                      output=OutputSpec(times=[0.3]))
    second = integrate(p, stepper, (0.3, 0.6), None, None, dt=1e-3,
                       output=OutputSpec(times=[0.6]), start=first.state)
    # the modes are rebuilt from the start kept in the state: the same numbers follow,
    # except that the first run's last step was clipped onto 0.3 s
    assert np.max(np.abs(second.q[-1] - whole.q[-1])) <= 1e-4 * np.max(np.abs(whole.q))


def test_a_resumed_checkpoint_is_bitwise_identical(tmp_path):
    # the modal coordinates travel in the state's history: a resumed run does not
    # recompute them from q and v, so it repeats the uninterrupted run bit for bit
    p, load = problem(200.0, 2e4)
    stepper, times = Exponential(load, rtol=1e-5), np.linspace(0.0, 0.6, 7)
    whole = integrate(p, stepper, (0.0, 0.6), [0.0, 0.0], [0.0, 0.0], dt=1e-3,
                      output=OutputSpec(times=times))
    path = tmp_path / "run.h5"

    def stop(state):
        if state.step == 20:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        integrate(p, stepper, (0.0, 0.6), [0.0, 0.0], [0.0, 0.0], dt=1e-3,
                  output=OutputSpec(times=times), checkpoint=path, checkpoint_every=10,
                  callback=stop)
    resumed = integrate(p, stepper, (0.0, 0.6), [0.0, 0.0], [0.0, 0.0], dt=1e-3,
                        output=OutputSpec(times=times), resume=path)
    assert np.array_equal(resumed.q, whole.q)


def test_the_eigenbasis_of_a_wide_spectrum_reconstructs_displacements_and_velocities():
    # natural frequencies from 2e2 to 5e5 rad/s, as on the 150-DOF benchmark rotors: in
    # y = (q, v) the eigenvectors' velocity parts are |lambda| times their displacement
    # parts, and the basis lost 1e-11 of q and 4e-10 of v (cond 5e5 here, 5e7 on the
    # rotors, where it was refused on some BLAS builds). Diagonalised in (q, v / s) both
    # come back to about 1e-13 (1e-11 asserted: 100 times the round-off measured, far
    # below what the unscaled basis gave)
    n = 60
    rng = np.random.default_rng(3)
    Q, _ = np.linalg.qr(rng.normal(size=(n, n)))
    K = (Q * np.geomspace(2e2, 5e5, n) ** 2) @ Q.T
    K = 0.5 * (K + K.T)
    D = 1e-6 * K + 0.1 * np.eye(n)
    load = HarmonicLoad(np.zeros(n), np.zeros(n, dtype=complex), 100.0)
    modes = LinearModes.build(np.eye(n), K, D, np.array([0, 1]), np.zeros((2, 2)),
                              np.zeros((2, 2)), load, "test")
    q, v = rng.normal(size=n), 1e4 * rng.normal(size=n)
    y = (modes.V @ modes.modal(q, v)).real
    assert np.max(np.abs(y[:n] - q)) <= 1e-11 * np.max(np.abs(q))
    assert np.max(np.abs(y[n:] - v)) <= 1e-11 * np.max(np.abs(v))
