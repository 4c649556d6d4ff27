"""The iteration matrix at a speed node (issue 14, part 3): merged once per step size and
equal to the term-by-term sum bit for bit, factorised banded when the band is narrow (checked
against LAPACK's dense solve), nodes placed ahead of a moving speed and at a speed that has
stopped moving."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

import rotorsim as rs
from rotorsim.analyses.transient.transient import transient
from rotorsim.errors import ConvergenceError
from rotorsim.time_integration.banded_lu import BandLayout, max_band
from rotorsim.time_integration.integrate import integrate
from rotorsim.time_integration.merged_matrices import MergedMatrices
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.problem import SecondOrderProblem, combine

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def _banded(n: int, width: int, seed: int, zeros: bool = False) -> sp.csr_matrix:
    """Random CSR matrix with ``width`` diagonals either side (stored zeros if asked)."""
    rng = np.random.default_rng(seed)
    offsets = list(range(-width, width + 1))
    diagonals = [rng.normal(size=n - abs(k)) for k in offsets]
    A = sp.diags(diagonals, offsets, shape=(n, n), format="csr")
    if zeros:
        A.data[::3] = 0.0  # stored, not eliminated: as the assembled rotor matrices have
    return A


@pytest.mark.parametrize("n", [60, 500])  # dense (below DENSE_THRESHOLD) and sparse
def test_merged_matrices_sum_as_the_term_by_term_sum_bit_for_bit(n):
    M, C, G, K = (_banded(n, w, s, zeros=True) for w, s in ((2, 1), (0, 2), (3, 3), (4, 4)))
    merged = MergedMatrices.build([M, None, C, G, K], n)
    assert merged is not None
    for node in (0.0, 123.456, -7e3):
        coefficients = [1.0, 9.0, 2.5e-5, 2.5e-5 * node, 2.5e-9]
        expected = combine([(1.0, M), (2.5e-5, C), (2.5e-5 * node, G), (2.5e-9, K)], n)
        got = merged.at(coefficients)
        if sp.issparse(expected):
            expected = sp.csc_matrix(expected)
            for part in ("indptr", "indices", "data"):
                assert np.array_equal(getattr(got, part), getattr(expected, part))
        else:
            assert np.array_equal(got, expected)


def test_banded_lu_solves_as_the_dense_lu():
    n = 500
    A = (_banded(n, 6, 7) + sp.diags(np.full(n, 0.5))).tocsc()
    A.sort_indices()
    layout = BandLayout.of(A)
    assert layout is not None and (layout.kl, layout.ku) == (6, 6)
    lu = layout.factorize(A.data, "test")
    rng = np.random.default_rng(8)
    b, B = rng.normal(size=n), rng.normal(size=(n, 3))
    dense = A.toarray()
    # both are backward stable: agreement to the condition number times eps
    tol = 1e3 * np.finfo(float).eps * np.linalg.cond(dense)
    x = np.linalg.solve(dense, b)
    assert np.max(np.abs(lu.solve(b) - x)) <= tol * np.max(np.abs(x))
    X = np.linalg.solve(dense, B)
    assert np.max(np.abs(lu.solve(B) - X)) <= tol * np.max(np.abs(X))
    assert lu.solve(b).shape == (n,) and lu.solve(B).shape == (n, 3)


def test_a_wide_band_is_left_to_the_sparse_lu_and_a_zero_pivot_is_an_error():
    n = 400
    wide = _banded(n, max_band(n), 9).tocsc()
    wide.sort_indices()
    assert BandLayout.of(wide) is None
    singular = sp.diags([np.r_[1.0, 0.0, np.ones(n - 2)]], [0], format="csc")
    layout = BandLayout.of(singular)
    assert layout is not None
    with pytest.raises(ConvergenceError, match="singular"):
        layout.factorize(singular.data, "test")


def _long_rotor() -> rs.Rotor:
    """70 shaft elements on two linear bearings: 426 DOFs, sparse, half-band 11."""
    shaft = [rs.ShaftElement(L=0.02, idl=0.0, odl=0.05, material=STEEL) for _ in range(70)]
    disk = rs.DiskElement.from_geometry(n=35, material=STEEL, width=0.04, i_d=0.05, o_d=0.3)
    bearings = [rs.BearingElement(n=n, kxx=2e7, kyy=3e7, cxx=2e3, cyy=3e3) for n in (0, 70)]
    return rs.Rotor(shaft, [disk], bearings)


def test_sparse_runup_with_banded_speed_nodes_takes_the_steps_of_a_factorisation_per_step():
    """The sparse, banded path: the samples agree with factorising at every step's speed to
    the Newton tolerance (an affine step is solved to theta^2 of its correction)."""
    rotor, t_end, dt = _long_rotor(), 0.02, 5e-5
    kw = dict(unbalance=[(35, 2e-4, 0.0)], nodes=[35], excitation=rs.Excitation(gravity=None),
              initial="zero")
    speed = rs.LinearSpeed(1000.0, 1400.0, 0.0, t_end)  # 1 rad/s per step
    nodes = transient(rotor, t_end, dt, speed=speed, **kw)
    every = transient(rotor, t_end, dt, speed=speed, method=Newmark(max_contraction=0.0),
                      **kw)
    steps = int(nodes.stats["steps"])
    assert every.stats["factorizations"] >= steps
    assert nodes.stats["factorizations"] <= 0.1 * steps
    scale = float(np.max(np.ptp(every.q, axis=0)))
    np.testing.assert_allclose(nodes.q, every.q, rtol=0, atol=1e-9 * scale)


def _jeffcott_runup(stop: float) -> SecondOrderProblem:
    """A 2-DOF Jeffcott rotor whose speed ramps 100 -> 600 rad/s until ``stop``, then
    holds (gyroscopic coupling 0.02 kg m^2 per unit speed, unbalance-like load)."""
    G = np.array([[0.0, 0.02], [-0.02, 0.0]])

    def speed(t):
        return 100.0 + 500.0 * min(t, stop) / stop

    return SecondOrderProblem(mass=np.eye(2), stiffness=np.diag([4e5, 5e5]),
                              damping=np.diag([2.0, 2.0]), gyroscopic=G, speed=speed,
                              load=lambda t: np.array([np.cos(300 * t), np.sin(300 * t)]))


def test_nodes_lie_ahead_of_a_moving_speed_and_on_a_speed_that_has_stopped():
    """While the speed moves slowly the steps share nodes (two solves per step); once it
    holds, the next factorisation is at the held speed and every later step is one exact
    solve."""
    stop, t_end, dt = 0.05, 0.1, 1e-4
    res = integrate(_jeffcott_runup(stop), Newmark(), (0.0, t_end), np.zeros(2), np.zeros(2),
                    dt=dt)
    ramp_steps = round(stop / dt)
    hold_steps = int(res.stats["steps"]) - ramp_steps
    assert res.stats["factorizations"] <= 0.1 * ramp_steps
    # two solves per ramp step at most, one per hold step after the first
    assert res.stats["iterations"] <= 2 * ramp_steps + hold_steps + 2
    every = integrate(_jeffcott_runup(stop), Newmark(max_contraction=0.0), (0.0, t_end),
                      np.zeros(2), np.zeros(2), dt=dt)
    # the Newton tolerance, 1e-10 of |q| per step, over 1000 lightly damped steps: measured
    # 4.0e-8 of the motion (1.5e-7 when the node stayed off the held speed)
    np.testing.assert_allclose(res.q, every.q, rtol=0, atol=1e-7 * np.max(np.abs(every.q)))
