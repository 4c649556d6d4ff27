"""Half-space influence coefficients and the complementarity solve
(rotorsim.elements.rolling.contact.influence)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.integrate import dblquad
from scipy.optimize import nnls

from rotorsim.elements.rolling.contact.influence import (
    grid_compliance,
    rectangle_influence,
    solve_contact,
)


@pytest.mark.parametrize(("dx", "dy", "a", "h"), [
    (0.3, -0.7, 1.0, 2.0), (3.0, 5.0, 1.0, 0.5), (-2.0, 0.1, 0.5, 1.0), (0.0, -4.0, 0.2, 1.0),
])
def test_love_rectangle_matches_quadrature(dx, dy, a, h):
    # independent reference: adaptive quadrature of 1/r over the rectangle (Boussinesq),
    # cut at the point so that the integrable singularity sits at a corner
    xs = sorted({-a, a, min(max(dx, -a), a)})
    ys = sorted({-h, h, min(max(dy, -h), h)})
    ref = sum(dblquad(lambda y, x: 1.0 / np.hypot(x - dx, y - dy), x0, x1, y0, y1,
                      epsabs=1e-13, epsrel=1e-12)[0]
              for x0, x1 in itertools.pairwise(xs) for y0, y1 in itertools.pairwise(ys)
              if x1 > x0 and y1 > y0)
    # 1e-9: quadrature accuracy near the 1/r singularity inside the rectangle
    assert rectangle_influence(dx, dy, a, h) == pytest.approx(ref, rel=1e-9)


def test_centre_of_a_square_closed_form():
    # Love: centre of a square of side 2a, D = 8 a asinh(1) (Johnson 1985, eq 3.25)
    assert rectangle_influence(0.0, 0.0, 1.5, 1.5) == pytest.approx(
        8 * 1.5 * np.arcsinh(1.0), rel=1e-14)


def _problem(seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    x, y = np.meshgrid(np.arange(6.0), np.arange(5.0), indexing="ij")
    c = grid_compliance(x.ravel(), y.ravel(), 0.5, 0.5, 1.0)
    return c, rng.normal(0.3, 1.0, (4, x.size))


def test_active_set_matches_scipy_nnls():
    c, d = _problem(1)
    p, iterations = solve_contact(c, d)
    low = np.linalg.cholesky(c)
    for k in range(d.shape[0]):  # min |L^T p - L^-1 d|, p >= 0 (scipy NNLS, independent)
        ref, _ = nnls(low.T, np.linalg.solve(low, d[k]))
        # 1e-9: both solve the same well-conditioned system to rounding, cond(C) ~ 10
        assert np.allclose(p[k], ref, rtol=1e-9, atol=1e-9 * ref.max())
    assert iterations < 20
    gap = np.einsum("ij,kj->ki", c, p) - d
    assert (p >= 0).all() and (gap > -1e-12).all()
    assert np.abs(p * gap).max() < 1e-12 * np.abs(d).max() * p.max()


def test_batched_equals_one_by_one_and_open_contacts_carry_nothing():
    c, d = _problem(2)
    p, _ = solve_contact(c, d)
    for k in range(d.shape[0]):
        np.testing.assert_allclose(solve_contact(c, d[k])[0], p[k], rtol=1e-12,
                                   atol=1e-14)
    assert not solve_contact(c, -np.abs(d))[0].any()


def test_nnls_fallback_when_the_active_set_has_not_settled():
    c, d = _problem(3)
    settled, _ = solve_contact(c, d)
    fallback, iterations = solve_contact(c, d, max_iter=1)  # NNLS for the unsettled ones
    assert iterations == 1
    # 1e-9: two exact solvers of the same small, well-conditioned problem
    np.testing.assert_allclose(fallback, settled, rtol=1e-9, atol=1e-9 * settled.max())
