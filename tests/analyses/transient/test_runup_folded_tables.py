"""Run-ups on bearings tabulated over speed with the tables folded into the speed node's
matrix (issue 14, parts 3 and 4): the contraction estimate bounds the tables' contraction,
the frozen map is the frozen iteration's operator, a slow run-up takes the steps of a
factorisation per step with one solve per step, and resumes bit for bit."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from test_runup_speed_nodes import NO_GRAVITY, _refactorised, _rotor, _scale
from transient_interrupt import resumed_run

import rotorsim as rs
from rotorsim.analyses.transient.transient import transient
from rotorsim.analyses.transient.variable_bearings import SpeedDependentBearings
from rotorsim.solvers.linear import factorize
from rotorsim.time_integration.folded_tables import FoldedTables
from rotorsim.time_integration.merged_matrices import MergedMatrices
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.speed_nodes import FOLDED, FactorCache

GRID = np.array([100.0, 200.0, 400.0])


def _tables(rng: np.random.Generator) -> SpeedDependentBearings:
    """Tables on DOFs 1 and 2 of 6 (stiffness [N/m] and damping [N s/m], three points)."""
    K = np.stack([np.diag([1e7, 2e7]) * f for f in (1.0, 1.5, 2.5)])
    C = np.stack([np.array([[3e4, 1e3], [-1e3, 4e4]]) * f for f in (1.0, 0.7, 0.5)])
    K += rng.normal(scale=1e5, size=K.shape)
    return SpeedDependentBearings(6, np.array([1, 2]), GRID, K, C)


def test_tables_are_interpolated_from_their_segment_slopes_and_held_outside():
    """Against ``np.interp`` entry by entry (linear between points, held outside): equal to
    round-off of the entries (the slope form rounds differently from the weighted mean)."""
    terms = _tables(np.random.default_rng(1))
    for w in (50.0, 100.0, 150.0, 200.0, 333.3, 400.0, 900.0):
        K, C = terms(w)
        for got, table in ((K, terms.stiffness), (C, terms.damping)):
            expected = np.array([[np.interp(w, GRID, table[:, i, j]) for j in range(2)]
                                 for i in range(2)])
            np.testing.assert_allclose(got, expected, rtol=1e-14, atol=1e-14 * abs(table).max())
    assert [terms.segment(w) for w in (50.0, 100.0, 150.0, 400.0, 900.0)] == [0, 1, 1, 3, 3]
    assert not np.any(terms.slopes[[0, -1]])


def _frozen_node(seed: int) -> tuple[SecondOrderProblem, FactorCache, float, float]:
    """A 6-DOF problem with gyroscopic coupling and tables, its iteration matrix factorised
    at the node 250 rad/s with the tables folded in, and the weights c_K, c_C."""
    rng = np.random.default_rng(seed)
    terms = _tables(rng)
    n = 6
    K = sp.diags([np.full(n - 1, -1e7), np.full(n, 2.5e7), np.full(n - 1, -1e7)],
                 [-1, 0, 1]).toarray()
    G = np.zeros((n, n))
    G[3, 4], G[4, 3] = 0.02, -0.02
    problem = SecondOrderProblem(mass=np.diag(rng.uniform(0.5, 2.0, n)), stiffness=K,
                                 damping=np.eye(n), gyroscopic=G, speed=lambda t: 250.0,
                                 speed_terms=terms)
    h = 5e-5
    c_K, c_C = 0.25 * h * h, 0.5 * h
    tables = FoldedTables.at_node(terms, 250.0, c_K, c_C)
    S0 = problem.mass + c_C * (problem.damping + 250.0 * G) + c_K * K
    S0[np.ix_(terms.dofs, terms.dofs)] += tables.block
    lu = factorize(S0)
    cache = FactorCache(h, 250.0, FOLDED, lu, tables=tables.with_rates(lu))
    return problem, cache, c_K, c_C


def _iteration_matrix(problem: SecondOrderProblem, w: float, c_K: float,
                      c_C: float) -> np.ndarray:
    terms = problem.speed_terms
    assert terms is not None
    S = problem.mass + c_C * (problem.damping + w * problem.gyroscopic) \
        + c_K * problem.stiffness
    K, C = terms(w)
    S[np.ix_(terms.dofs, terms.dofs)] += c_C * C + c_K * K
    return S


@pytest.mark.parametrize("seed", [2, 3])
def test_the_contraction_estimate_bounds_the_tables_and_the_frozen_map_is_the_iteration(seed):
    """On the node's segment: the spectral radius of ``S_0^-1 P D P^T`` (the tables' part of
    the frozen iteration) is at most ``rate |W - W_0|`` (a norm bounds it; measured 0.97 and
    0.99 of it), and ``(W - W_0) R`` equals ``S_0^-1 (S(W) - S_0)`` to round-off (cond(S_0)
    about 2, measured 1.5e-14 relative; 1e-12 allows for any LAPACK kernel). Off the segment
    there is no map."""
    problem, cache, c_K, c_C = _frozen_node(seed)
    tables = cache.tables
    assert tables is not None and tables.segment == 2
    S0 = _iteration_matrix(problem, 250.0, c_K, c_C)
    for w in (201.0, 260.0, 399.0):
        dS = _iteration_matrix(problem, w, c_K, c_C) - S0
        table_part = dS - c_C * (w - 250.0) * problem.gyroscopic
        rho = max(abs(np.linalg.eigvals(np.linalg.solve(S0, table_part))))
        assert 0.0 < rho <= tables.rate(w) * abs(w - 250.0) * (1.0 + 1e-12)
        mapped = cache.frozen_map(problem, 1.0, c_C, w)
        assert mapped is not None
        cols, R = mapped
        full = np.zeros((6, 6))
        full[:, cols] = R
        expected = np.linalg.solve(S0, dS)
        np.testing.assert_allclose((w - 250.0) * full, expected, rtol=0,
                                   atol=1e-12 * abs(expected).max())
    assert cache.frozen_map(problem, 1.0, c_C, 199.0) is None


def test_a_narrow_band_of_dense_matrices_is_factorised_banded_with_the_tables_block():
    """Dense input above the dense threshold with a narrow band: the banded LU of the sum
    plus a block on scattered DOFs (nonzero where the pattern says) solves as LAPACK's dense
    solve of the same matrix (both backward stable: 1e-11 relative, cond about 10)."""
    n, rng = 200, np.random.default_rng(4)
    A = (sp.diags([rng.normal(size=n - abs(k)) for k in range(-3, 4)], range(-3, 4))
         + sp.diags(np.full(n, 8.0))).toarray()
    dofs = np.array([4, 5, 150, 151])
    pattern = np.kron(np.eye(2, dtype=bool), np.ones((2, 2), dtype=bool))
    merged = MergedMatrices.build([A, None], n, (dofs, pattern))
    assert merged is not None and merged.band is not None
    block = rng.normal(size=(4, 4)) * pattern
    lu = merged.factorize([2.0, 0.0], "test", block=block)
    total = 2.0 * A
    total[np.ix_(dofs, dofs)] += block
    b = rng.normal(size=n)
    x = np.linalg.solve(total, b)
    np.testing.assert_allclose(lu.solve(b), x, rtol=0, atol=1e-11 * abs(x).max())


def _slow_runup() -> tuple[rs.Rotor, dict]:
    """The tabulated rotor through its table point at 500 rad/s at 0.05 rad/s per step:
    nodes serve tens of steps, so the tables are folded into them."""
    kw = dict(speed=rs.LinearSpeed(470.0, 520.0, 0.0, 0.05), unbalance=[(3, 2e-4, 0.0)],
              excitation=NO_GRAVITY, initial="zero", nodes=[3])
    return _rotor(), kw


def test_slow_runup_folds_the_tables_and_takes_the_steps_of_a_factorisation_per_step():
    """Folded nodes: a factorisation per 50 or so steps, one solve per step (the second
    correction is a product with the frozen map) and never fewer than two corrections
    off the node; the samples agree with factorising at every step to the Newton
    tolerance (an affine step is solved to theta^2 of its correction: measured 2.4e-11)."""
    rotor, kw = _slow_runup()
    nodes = transient(rotor, 0.05, 5e-5, **kw)
    every = transient(rotor, 0.05, 5e-5, method=_refactorised(), **kw)
    steps = int(nodes.stats["steps"])
    assert every.stats["factorizations"] >= steps
    assert nodes.stats["factorizations"] <= 0.05 * steps
    # exact low-rank updates would take two solves per step
    assert nodes.stats["solves"] <= 1.1 * steps
    assert nodes.stats["iterations_per_step"] >= 1.95
    np.testing.assert_allclose(nodes.q, every.q, rtol=0, atol=1e-9 * _scale(every))


def test_resume_of_a_folded_runup_equals_the_uninterrupted_run(tmp_path, monkeypatch):
    """The checkpoint's factor key says the tables were folded, so the resumed run rebuilds
    the same node the same way: bit-identical samples."""
    rotor, kw = _slow_runup()
    full = transient(rotor, 0.02, 5e-5, **kw)
    resumed = resumed_run(monkeypatch, tmp_path / "run.h5", 230, 75, rotor, 0.02, 5e-5, **kw)
    np.testing.assert_array_equal(resumed.q, full.q)
