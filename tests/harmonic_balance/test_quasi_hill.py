"""Stability of a torus by the quasi-periodic Hill method (issue 17, part 2), against
closed forms and an independent integration.

- A linear chain: the exponents are the eigenvalues of the constant system, the largest
  real part ``-0.03`` (round-off: asserted to 1e-9).
- A damped oscillator with a stiffness modulated at two incommensurate frequencies,
  ``y'' + 0.05 y' + (1 + eps (cos w1 t + cos w2 t)) y = 0``. Its largest Lyapunov exponent
  is measured independently by ``solve_ivp`` (DOP853, rtol 1e-10) over 600 time units,
  renormalised every 10: a slowly decaying case (``eps = 0.6``, no resonance: measured
  -0.0250 by Hill, -0.0250 +- 1e-3 by the integration), and a parametric resonance
  (``w1 = 2.05``, near twice the natural frequency, ``eps = 0.3``: Hill 0.04507,
  integration 0.0447-0.0451). Asserted: 5 % (the integration's finite horizon).
- The eigenvalue selection keeps the copy of a parametric exponent that straddles two
  tones (``Im lam = w1 / 2``), which a "largest block on the central tone" rule drops.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.quasi import QuasiProblem, TorusAFT, TorusHarmonics, solve_quasi
from rotorsim.harmonic_balance.quasi.hill import hill_exponents

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_quasi_hb import W1, W2, C, K, chain

DAMPING = 0.05


def modulated(eps: float) -> QuasiProblem:
    def force(q, v, t1, t2):  # type: ignore[no-untyped-def]
        k = eps * (np.cos(t1) + np.cos(t2))
        return k[:, None] * q, k[:, None, None], None

    return QuasiProblem(np.eye(1), DAMPING * np.eye(1), np.eye(1), nl_dofs=np.array([0]),
                        force=force)


def integrated_exponent(eps: float, w1: float, w2: float, horizon: float = 600.0) -> float:
    """Growth rate of ``|(y, y')|`` over the second half of ``horizon``, by solve_ivp."""
    def rhs(t: float, z: np.ndarray) -> np.ndarray:
        k = 1.0 + eps * (np.cos(w1 * t) + np.cos(w2 * t))
        return np.array([z[1], -DAMPING * z[1] - k * z[0]])

    z, t, logs = np.array([1.0, 0.3]), 0.0, []
    while t < horizon - 1e-9:
        sol = solve_ivp(rhs, (t, t + 10.0), z, method="DOP853", rtol=1e-10, atol=1e-12)
        z, t = sol.y[:, -1], t + 10.0
        size = float(np.linalg.norm(z))
        logs.append(np.log(size))
        z = z / size
    growth = np.cumsum(logs)
    half = len(growth) // 2
    return float((growth[-1] - growth[half - 1]) / (10.0 * (len(growth) - half)))


def test_linear_chain_exponents_are_the_eigenvalues() -> None:
    harmonics = TorusHarmonics.diamond(5)
    problem = chain(harmonics, k3=0.0)
    torus = solve_quasi(problem, TorusAFT(harmonics), W1, W2)
    ex = hill_exponents(problem, torus.X, torus.aft, W1, W2, box=(2, 1))
    exact = np.linalg.eigvals(np.block([[np.zeros((2, 2)), np.eye(2)], [-K, -C]]))
    assert ex.largest == pytest.approx(exact.real.max(), rel=1e-9)
    assert ex.stable and ex.edge_share.max() < 1e-9   # nothing modulates: no spreading


@pytest.mark.parametrize(("eps", "w1", "w2"), [(0.6, 3.1, 7.3), (0.3, 2.05, 7.3)])
def test_modulated_oscillator_against_an_integration(eps: float, w1: float, w2: float
                                                     ) -> None:
    aft = TorusAFT(TorusHarmonics.box(6, 6))
    ex = hill_exponents(modulated(eps), np.zeros((aft.harmonics.rows, 1)), aft, w1, w2,
                        box=(3, 2))
    reference = integrated_exponent(eps, w1, w2)
    print(f"eps {eps}: Hill {ex.largest:.5f}, solve_ivp {reference:.5f} 1/s")
    assert ex.largest == pytest.approx(reference, rel=0.05)
    if reference > 0:
        # the parametric exponent oscillates at half the pumping frequency (mod the tones)
        assert min(abs(ex.critical_frequency - w1 / 2), abs(ex.critical_frequency + w1 / 2 - w1)) \
            < 1e-6 * w1
        assert not ex.stable


def test_bad_boxes_are_refused() -> None:
    aft = TorusAFT(TorusHarmonics.box(2, 2))
    X = np.zeros((aft.harmonics.rows, 1))
    with pytest.raises(ModelError, match="box"):
        hill_exponents(modulated(0.1), X, aft, 3.1, 7.3, box=(0, 0))
    with pytest.raises(ModelError, match="grid"):
        hill_exponents(modulated(0.1), X, aft, 3.1, 7.3, box=(4, 1))
