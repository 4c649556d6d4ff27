"""HB residual: analytic Jacobian and parameter derivatives against central differences,
condensed against full system, sparse against dense, factorisation cache, API contracts.

Finite-difference tolerance: central differences with step ``h = 1e-6`` on unknowns of
size ~0.3 leave a truncation error ``h^2 |r'''| / 6 ~ 1e-12`` and a round-off error
``eps |r| / h ~ 1e-9`` relative to the largest entry; the analytic derivatives must agree
to 1e-7 of the largest Jacobian entry (measured 1e-10).
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.condensation import CondensedResidual
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import (
    HarmonicBalanceResidual,
    continuation_function,
    make_residual,
)
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.solvers.stats import Stats

RNG = np.random.default_rng(11)
NL = np.array([4, 1])


def coupled_force(q, v, tau, w, p):
    """Cubic springs, a velocity-dependent coupling, a parametric (tau) stiffness and an
    explicit omega dependence (force_uses_omega)."""
    a, b = q[:, 0], q[:, 1]
    va, vb = v[:, 0], v[:, 1]
    kt = 0.5 * np.cos(tau) + 0.01 * w**2
    f = np.stack([(1 + p) * a**3 + 0.2 * b**2 * va + kt * a,
                  2.0 * b**3 + 0.3 * a * b + 0.1 * vb**3 + kt * b], axis=1)
    dq = np.zeros((len(q), 2, 2))
    dv = np.zeros((len(q), 2, 2))
    dq[:, 0, 0] = 3 * (1 + p) * a**2 + kt
    dq[:, 0, 1] = 0.4 * b * va
    dq[:, 1, 0] = 0.3 * b
    dq[:, 1, 1] = 6.0 * b**2 + 0.3 * a + kt
    dv[:, 0, 0] = 0.2 * b**2
    dv[:, 1, 1] = 0.3 * vb**2
    return f, dq, dv


def smooth_problem(n=6, sparse=False, **kwargs):
    A = RNG.standard_normal((n, n))
    K = A @ A.T + n * np.eye(n)
    M = np.eye(n) + 0.1 * np.diag(RNG.random(n))
    G = RNG.standard_normal((n, n))
    G = G - G.T
    shape = np.linspace(0.2, 1.0, n)

    def excitation(w, p):
        return np.vstack([0.1 * shape, w**2 * shape, (1 + p) * shape[::-1], 0.3 * shape,
                          np.zeros(n)])

    def load(tau, w, p):
        return 0.05 * (1 + p) * np.outer(np.sin(3 * tau) ** 2, shape)

    mats = [M, K, 0.05 * K, G]
    if sparse:
        mats = [sp.csr_matrix(m) for m in mats]
    options = dict(nl_dofs=NL, force=coupled_force, excitation=excitation, load=load,
                   spin=0.3, spin_ratio=0.7, force_uses_omega=True)
    options.update(kwargs)
    return HBProblem(*mats, **options)


def central(fun, x, h=1e-6):
    return np.array([(fun(x + h * e) - fun(x - h * e)) / (2 * h) for e in np.eye(x.size)]).T


@pytest.mark.parametrize("condense", [False, True])
def test_jacobian_and_parameter_derivatives_match_central_differences(condense):
    pb = smooth_problem()
    res = make_residual(pb, 3, condense=condense)
    x, w, p = 0.3 * RNG.standard_normal(res.size), 1.3, 0.2
    ev = res.evaluate(x, w, p, d_omega=True, d_param=True)
    scale = np.abs(ev.jacobian).max()
    J = central(lambda y: res.evaluate(y, w, p, jacobian=False).r, x)
    assert np.abs(ev.jacobian - J).max() < 1e-7 * scale
    dw = central(lambda s: res.evaluate(x, s[0], p, jacobian=False).r, np.array([w]))[:, 0]
    dp = central(lambda s: res.evaluate(x, w, s[0], jacobian=False).r, np.array([p]))[:, 0]
    assert np.abs(ev.d_omega - dw).max() < 1e-7 * np.abs(dw).max()
    assert np.abs(ev.d_param - dp).max() < 1e-7 * np.abs(dp).max()


def test_omega_derivative_without_explicit_dependence_is_analytic():
    """With ``force_uses_omega=False`` no extra force call is made: a force that ignores
    omega still gets the exact derivative (through v = omega dq/dtau)."""
    calls = []

    def force(q, v, tau, w, p):
        calls.append(len(q))
        f, dq, dv = coupled_force(q, v, tau, 0.0, p)
        return f, dq, dv

    pb = smooth_problem(force=force, force_uses_omega=False)
    res = make_residual(pb, 2)
    x, w = 0.3 * RNG.standard_normal(res.size), 0.9
    ev = res.evaluate(x, w, d_omega=True)
    assert len(calls) == 1
    dw = central(lambda s: res.evaluate(x, s[0], jacobian=False).r, np.array([w]))[:, 0]
    assert np.abs(ev.d_omega - dw).max() < 1e-7 * np.abs(dw).max()


def test_condensed_and_full_systems_have_the_same_solution_and_jacobian():
    pb = smooth_problem()
    cond, full = make_residual(pb, 4), make_residual(pb, 4, condense=False)
    w, p = 1.7, 0.1
    sol_c = solve_point(cond, w, param=p, tol=1e-13)
    sol_f = solve_point(full, w, full.restrict(sol_c.coefficients) * 0.9, param=p, tol=1e-13)
    assert sol_f.coefficients == pytest.approx(sol_c.coefficients, abs=1e-12)
    assert np.abs(full.evaluate(full.restrict(sol_c.coefficients), w, p).r).max() < 1e-12
    # the condensed Jacobian is the Schur complement of the full one on the linear rows
    J = full.evaluate(full.restrict(sol_c.coefficients), w, p).jacobian
    rows = np.arange(full.aft.rows)[:, None] * pb.n
    N = (rows + pb.nl_dofs[None, :]).reshape(-1)
    L = (rows + pb.linear_dofs[None, :]).reshape(-1)
    schur = J[np.ix_(N, N)] - J[np.ix_(N, L)] @ np.linalg.solve(J[np.ix_(L, L)],
                                                               J[np.ix_(L, N)])
    assert cond.evaluate(sol_c.x, w, p).jacobian == pytest.approx(schur, abs=1e-10)


def test_sparse_matrices_and_sparse_condensation_agree_with_dense():
    """130 linear DOFs: the condensation factorises sparse (SuperLU, complex)."""
    dense = smooth_problem(n=132)
    sparse = HBProblem(*(sp.csr_matrix(getattr(dense, m)) for m in (
        "mass", "stiffness", "damping", "gyroscopic")), nl_dofs=NL, force=coupled_force,
        excitation=dense.excitation, load=dense.load, spin=0.3, spin_ratio=0.7,
        force_uses_omega=True)
    x, w = 0.1 * RNG.standard_normal(5 * 2), 2.1
    a = make_residual(dense, 2).evaluate(x, w, d_omega=True)
    b = make_residual(sparse, 2).evaluate(x, w, d_omega=True)
    for name in ("r", "jacobian", "d_omega"):
        ref = getattr(a, name)
        assert getattr(b, name) == pytest.approx(ref, abs=1e-11 * np.abs(ref).max())
    X = make_residual(sparse, 2).expand(x, w)
    full = make_residual(sparse, 2, condense=False).evaluate(X.reshape(-1), w, jacobian=False)
    assert np.abs(np.delete(full.r.reshape(5, -1), NL, axis=1)).max() < 1e-10


def test_condensation_factorises_once_per_harmonic_and_omega():
    pb = smooth_problem()
    res = CondensedResidual(pb, 5)
    stats = Stats()
    x = np.zeros(res.size)
    res.evaluate(x, 1.0, stats=stats)
    assert stats.factorizations == 6                  # H + 1 harmonics
    res.evaluate(x + 0.1, 1.0, 0.3, d_omega=True, d_param=True, stats=stats)
    assert stats.factorizations == 6
    res.evaluate(x, 1.1, stats=stats)
    res.evaluate(x, 1.0, stats=stats)                 # still cached (two omegas kept)
    assert stats.factorizations == 12
    res.evaluate(x, 1.2, stats=stats)
    res.evaluate(x, 1.1, stats=stats)
    res.evaluate(x, 1.0, stats=stats)                 # evicted
    assert stats.factorizations == 24
    assert stats.residual_evaluations == 7


def test_singular_linear_block_names_the_harmonic():
    K = np.diag([1.0, 0.0, 2.0])                      # DOF 1 free at h = 0
    pb = HBProblem(np.eye(3), K, nl_dofs=[0], force=lambda q, v, t, w, p: (
        q**3, 3 * q[:, :, None] ** 2, None))
    with pytest.raises(ConvergenceError, match="harmonic 0"):
        make_residual(pb, 2).evaluate(np.zeros(5), 1.0)
    ev = make_residual(pb, 2, condense=False).evaluate(np.zeros(15), 1.0)   # full: fine
    assert ev.r.shape == (15,)


def test_continuation_function_returns_the_requested_derivative():
    pb = smooth_problem()
    res = make_residual(pb, 2)
    x = 0.2 * RNG.standard_normal(res.size)
    r, J, r_w = continuation_function(res, "omega", param=0.4)(x, 1.5)
    ev = res.evaluate(x, 1.5, 0.4, d_omega=True, d_param=True)
    assert r == pytest.approx(ev.r) and J == pytest.approx(ev.jacobian)
    assert r_w == pytest.approx(ev.d_omega)
    _, _, r_p = continuation_function(res, "param", omega=1.5)(x, 0.4)
    assert r_p == pytest.approx(ev.d_param)
    with pytest.raises(TypeError, match="omega, param"):
        continuation_function(res, "speed")
    with pytest.raises(ModelError, match="fixed omega"):
        continuation_function(res, "param")


def test_expand_restrict_and_discretisation():
    pb = smooth_problem()
    for res in (make_residual(pb, 3), make_residual(pb, 3, condense=False)):
        x = RNG.standard_normal(res.size)
        X = res.expand(x, 1.2)
        assert X.shape == (7, 6)
        assert res.restrict(X) == pytest.approx(x)
        finer = res.with_discretization(samples=64)
        assert (finer.harmonics, finer.samples, type(finer)) == (3, 64, type(res))
        assert res.with_discretization(harmonics=5).samples == 64
    assert isinstance(make_residual(pb, 3, condense=False), HarmonicBalanceResidual)


@pytest.mark.parametrize(("options", "where"), [
    (dict(nl_dofs=[0, 0]), "nl_dofs"),
    (dict(nl_dofs=[7]), "nl_dofs"),
    (dict(force=coupled_force, nl_dofs=[]), "HBProblem.force"),
    (dict(excitation=np.ones((2, 6))), "excitation"),
    (dict(param_scale=0.0), "param_scale"),
])
def test_invalid_problems_name_the_culprit(options, where):
    base = dict(nl_dofs=NL, force=coupled_force)
    base.update(options)
    with pytest.raises(ModelError, match=where):
        HBProblem(np.eye(6), np.eye(6), **base)


def test_bad_callback_output_is_reported():
    pb = HBProblem(np.eye(2), 2 * np.eye(2), nl_dofs=[0], force=lambda q, v, t, w, p: (
        q, np.zeros((len(q), 2, 2)), None))
    with pytest.raises(ModelError, match="dfdq of shape"):
        make_residual(pb, 1).evaluate(np.zeros(3), 1.0)
    with pytest.raises(ModelError, match="expected 3 unknowns"):
        make_residual(pb, 1).evaluate(np.zeros(4), 1.0)


def test_failed_solve_raises_convergence_error_with_the_iteration():
    pb = HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1), nl_dofs=[0],
                   excitation=[[0.0], [1.0], [0.0]],
                   force=lambda q, v, t, w, p: (q**3, 3 * q[:, :, None] ** 2, None))
    with pytest.raises(ConvergenceError, match="iteration 1"):
        solve_point(make_residual(pb, 3), 1.0, max_iter=1)
    sol = solve_point(make_residual(pb, 3), 1.0)
    assert sol.stats["iterations"] >= 2 and sol.stats["residual_evaluations"] >= 3
    _, q = sol.time_response(64)
    assert q.shape == (64, 1) and sol.amplitude(0) == pytest.approx(
        0.5 * (q.max() - q.min()), rel=1e-2)


def test_sparse_damping_with_a_dense_gyroscopic_matrix():
    """``damping_matrix(omega) = C + W G`` with a sparse ``C`` and a dense ``G`` (found by
    the rs.hb work: the sum was an np.matrix, which has no ``tocsr``)."""
    import scipy.sparse as sp

    from rotorsim.harmonic_balance.problem import HBProblem as Problem

    C = 0.1 * np.eye(2)
    G = np.array([[0.0, 1.0], [-1.0, 0.0]])
    mixed = Problem(np.eye(2), np.eye(2), sp.csr_matrix(C), gyroscopic=G, spin_ratio=1.0)
    got = mixed.damping_matrix(2.0)
    assert sp.issparse(got)
    # exact: the entries are sums of two binary fractions
    assert np.array_equal(got.toarray(), C + 2.0 * G)
