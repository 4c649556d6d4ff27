"""Floquet stability: classification, Hill's exponent selection, Hsu's convergence order,
the Mathieu equation's instability tongues and a gyroscopic rotor with a velocity-dependent
nonlinearity (Hill, Hsu and Newmark integration of the variational equations agree).

References: the damped Mathieu equation ``x'' + 2 zeta x' + (delta + eps cos t) x = 0`` is
unstable inside the tongues issuing from ``delta = (m / 2)^2``; to second order in ``eps``
the first is ``1/4 - eps/2 < delta < 1/4 + eps/2`` (period doubling, multiplier -1) and the
second ``1 - eps^2 / 12 < delta < 1 + 5 eps^2 / 12`` (multiplier +1) (A. H. Nayfeh,
D. T. Mook, *Nonlinear Oscillations*, Wiley 1979, section 5.2). Reference multipliers come
from scipy's DOP853 on the variational equation at ``rtol = 1e-12``.
"""

from __future__ import annotations

import numpy as np
import pytest
from multiplier_matching import matched
from scipy.integrate import solve_ivp

from rotorsim.harmonic_balance.floquet import classify, hill
from rotorsim.harmonic_balance.monodromy import hsu, ordered_product, variational
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import make_residual
from rotorsim.harmonic_balance.solve import solve_point


def _sorted(mu):
    mu = np.asarray(mu)
    return mu[np.lexsort((np.round(mu.imag, 9), np.round(mu.real, 9)))]


# --- classification ---------------------------------------------------------------

@pytest.mark.parametrize(("mu", "expected"), [
    ([0.5, 0.2j, -0.2j], (True, 0.5, "fold")),
    ([1.3, 0.5], (False, 1.3, "fold")),
    ([-1.1, 0.9], (False, -1.1, "period_doubling")),
    ([0.6 + 0.9j, 0.6 - 0.9j, 0.1], (False, 0.6 + 0.9j, "neimark_sacker")),
    ([0.3 + 0.4j, 0.3 - 0.4j], (True, 0.3 + 0.4j, "neimark_sacker")),
])
def test_classify_names_the_critical_multiplier(mu, expected):
    stable, crit, kind = classify(mu)
    assert (stable, kind) == (expected[0], expected[2])
    assert crit == pytest.approx(expected[1])


def test_classify_excludes_the_trivial_multiplier_of_autonomous_problems():
    assert classify([1.0 + 1e-9, 0.5])[0] is False
    assert classify([1.0 + 1e-9, 0.5], autonomous=True) == (True, 0.5, "fold")


def test_ordered_product_keeps_the_time_order():
    rng = np.random.default_rng(3)
    F = rng.standard_normal((7, 3, 3))
    expected = np.eye(3)
    for f in F:
        expected = f @ expected
    assert np.allclose(ordered_product(F), expected, rtol=1e-13, atol=1e-13)


# --- Hill's method on linear time-invariant systems --------------------------------

def gyroscopic_lti():
    M = np.diag([2.0, 2.0, 0.1, 0.1])
    K = np.array([[3e2, 0, 0, 20], [0, 3e2, -20, 0], [0, -20, 8.0, 0], [20, 0, 0, 8.0]])
    C = 0.02 * K + 0.1 * np.eye(4)
    G = np.zeros((4, 4))
    G[2, 3], G[3, 2] = 0.2, -0.2
    return M, K, C, G


def lti_exponents(M, K, D):
    A = np.block([[np.zeros((4, 4)), np.eye(4)], [-np.linalg.solve(M, K),
                                                   -np.linalg.solve(M, D)]])
    return _sorted(np.linalg.eigvals(A))


def test_hill_eigenvector_selection_returns_the_exact_lti_eigenvalues():
    """Natural frequencies 1.1, 12, 12.2 and 61 rad/s at omega = 3 rad/s, H = 4: the
    61 rad/s mode lies beyond H omega = 12 rad/s, yet its central copy is found."""
    M, K, C, G = gyroscopic_lti()
    omega, spin = 3.0, 30.0
    pb = HBProblem(M, K, C, G, spin=spin)
    exact = lti_exponents(M, K, C + spin * G)
    res = make_residual(pb, 4, condense=False)
    fe = hill(res, np.zeros(res.size), omega)
    assert _sorted(fe.exponents) == pytest.approx(exact, rel=1e-10)
    assert fe.stable
    # the imaginary-part criterion takes shifted copies (for the 61 rad/s mode the one at
    # the truncation edge, 61 - 4 omega = 49 rad/s); exact here (LTI), same multipliers
    fi = hill(res, np.zeros(res.size), omega, selection="imaginary")
    # expected: each exact frequency moved by the nearest multiple of omega, at most H = 4
    w = np.sort(np.abs(exact.imag))[::2]
    shifted = np.sort(np.abs(w - np.minimum(np.round(w / omega), 4) * omega))
    assert np.sort(np.abs(fi.exponents.imag))[::2] == pytest.approx(shifted, abs=1e-9)
    ref = fe.multipliers
    assert matched(fi.multipliers, ref) == pytest.approx(ref, abs=1e-9)
    # with H omega above every natural frequency (H = 22: 66 rad/s) all copies are central
    res = make_residual(pb, 22, condense=False)
    fi = hill(res, np.zeros(res.size), omega, selection="imaginary")
    assert np.abs(fi.exponents.imag).max() <= omega / 2 + 1e-9
    ref = fe.multipliers
    assert matched(fi.multipliers, ref) == pytest.approx(ref, abs=1e-9)


def test_negative_damping_is_a_neimark_sacker_instability():
    pb = HBProblem(np.eye(1), np.eye(1), -0.1 * np.eye(1))
    for fl in (hill(make_residual(pb, 2, condense=False), np.zeros(5), 0.7),
               hsu(make_residual(pb, 2), np.zeros(0), 0.7)):
        assert not fl.stable and fl.kind == "neimark_sacker"
        assert fl.max_modulus == pytest.approx(np.exp(0.05 * 2 * np.pi / 0.7), rel=1e-9)


# --- Mathieu equation ------------------------------------------------------------------

def mathieu(delta, eps, zeta):
    def force(q, v, tau, w, p):
        k = eps * np.cos(tau)[:, None, None]
        return k[:, :, 0] * q, k, None
    return HBProblem(np.eye(1), delta * np.eye(1), 2 * zeta * np.eye(1), nl_dofs=[0],
                     force=force)


def mathieu_reference(delta, eps, zeta):
    def rhs(t, y):
        A = np.array([[0.0, 1.0], [-(delta + eps * np.cos(t)), -2 * zeta]])
        return (A @ y.reshape(2, 2)).ravel()
    out = solve_ivp(rhs, (0, 2 * np.pi), np.eye(2).ravel(), method="DOP853", rtol=1e-12,
                    atol=1e-14)
    return np.linalg.eigvals(out.y[:, -1].reshape(2, 2))


@pytest.mark.validation
@pytest.mark.parametrize(("delta", "eps", "stable", "kind"), [
    (0.25, 0.2, False, "period_doubling"),   # inside the first tongue [0.15, 0.35]
    (1.02, 0.4, False, "fold"),              # inside the second tongue [0.987, 1.067]
    (0.60, 0.2, True, "neimark_sacker"),     # between the tongues: complex, stable
    (0.40, 0.2, True, "neimark_sacker"),
])
def test_mathieu_tongues(delta, eps, stable, kind):
    pb, zeta = mathieu(delta, eps, 0.002), 0.002
    res = make_residual(pb, 12)
    x = np.zeros(res.size)   # the trivial solution
    ref = _sorted(mathieu_reference(delta, eps, zeta))
    fh, fs = hill(res, x, 1.0), hsu(res, x, 1.0, samples=2048)
    for fl in (fh, fs):
        assert (fl.stable, fl.kind) == (stable, kind), fl.method
    assert matched(fh.multipliers, ref) == pytest.approx(ref, abs=1e-9)     # spectral in H
    assert matched(fs.multipliers, ref) == pytest.approx(ref, abs=1e-5)     # O(N^-2): 2048


@pytest.mark.parametrize(("rule", "order"), [("average", 2), ("midpoint", 2), ("left", 2)])
def test_hsu_converges_with_the_order_of_its_rule(rule, order):
    """Left-point is first order per step, second over a period (module docstring)."""
    pb = mathieu(0.6, 0.3, 0.01)
    res = make_residual(pb, 8)
    ref = _sorted(mathieu_reference(0.6, 0.3, 0.01))
    errors = [np.abs(_sorted(hsu(res, np.zeros(res.size), 1.0, samples=s,
                                 rule=rule).multipliers) - ref).max() for s in (64, 128, 256)]
    observed = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert observed == pytest.approx([order, order], abs=0.15)


def test_seed_taylor_expansion_approaches_the_exact_exponential():
    delta, eps, zeta, samples = 0.6, 0.3, 0.01, 256
    res = make_residual(mathieu(delta, eps, zeta), 8)
    exact = hsu(res, np.zeros(res.size), 1.0, samples=samples)
    h_norm = 2 * np.pi / samples * max(1 + 2 * zeta, delta + eps)   # step x |A|_1 bound
    for terms in (2, 3, 5):
        taylor = hsu(res, np.zeros(res.size), 1.0, samples=samples, expansion="taylor",
                     terms=terms)
        # sum of the local remainders (h |A|)^(terms+1) / (terms+1)! over the period
        bound = samples * h_norm ** (terms + 1) / np.prod(np.arange(1, terms + 2)) * 1.1
        error = np.abs(_sorted(taylor.multipliers) - _sorted(exact.multipliers)).max()
        assert error <= bound
        assert error > 1e-3 * bound   # the series truncation is visible: not the exp


# --- gyroscopic rotor with a velocity-dependent nonlinear damper --------------------

def rotor_with_cubic_damper():
    M, K, C, G = gyroscopic_lti()
    c3 = 0.05

    def damper(q, v, tau, w, p):
        f = c3 * v**3 + 40.0 * q**3
        dfdv = np.zeros((len(q), 2, 2))
        dfdq = np.zeros((len(q), 2, 2))
        dfdv[:, [0, 1], [0, 1]] = 3 * c3 * v**2
        dfdq[:, [0, 1], [0, 1]] = 120.0 * q**2
        return f, dfdq, dfdv

    unbalance = np.zeros((3, 4))
    unbalance[1, 0] = unbalance[2, 1] = 0.5
    return HBProblem(M, K, C, G, nl_dofs=[0, 1], force=damper, spin_ratio=1.0,
                     excitation=lambda w, p: w**2 * unbalance)


@pytest.mark.verification
def test_floquet_methods_agree_on_a_gyroscopic_rotor_with_nonlinear_damping():
    pb, omega = rotor_with_cubic_damper(), 11.0
    res = make_residual(pb, 5)
    sol = solve_point(res, omega)
    full = make_residual(pb, 5, condense=False)
    fh = hill(res, sol.x, omega)
    full_mu = hill(full, full.restrict(sol.coefficients), omega).multipliers
    assert matched(full_mu, fh.multipliers) == pytest.approx(fh.multipliers, abs=1e-12)
    fs = hsu(res, sol.x, omega, samples=2048)
    fv = variational(res, sol.x, omega, steps=800)
    # Hsu (2048 steps) and Newmark (800 steps) are second order: measured 4e-6 and 2e-5
    ref = fh.multipliers
    assert matched(fs.multipliers, ref) == pytest.approx(ref, abs=1e-4)
    assert matched(fv.multipliers, ref) == pytest.approx(ref, abs=1e-4)
    assert fh.stable and fs.stable and fv.stable
