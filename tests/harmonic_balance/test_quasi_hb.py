"""Quasi-periodic harmonic balance on a 2-torus (issue 17, first part: the rotor-agnostic
core), against finite differences, closed forms and an independent time integration.

The model: two masses in a chain with Rayleigh damping and a cubic spring to ground on the
first (a 2-DOF Duffing chain), forced at ``w1`` on the first mass and at the incommensurate
``w2 = 0.9 phi w1`` (``phi`` the golden ratio) on the second. Its response is a torus with
combination tones ``k1 w1 + k2 w2``; a cubic force creates only those of odd order
``|k1| + |k2|``.

Reference: ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-11) started on the HB torus at
``t = 0`` and run over 60 s (about 11 periods of ``w1`` and 17 of ``w2``, two decay times of
the slowest mode): a torus that solves the equations stays the response, and the tones the
integration shows are fitted by least squares over that window.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.quasi import (
    QuasiProblem,
    TorusAFT,
    TorusHarmonics,
    solve_quasi,
)
from rotorsim.harmonic_balance.quasi.residual import condense, residual

M = np.eye(2)
K = np.array([[2.0, -1.0], [-1.0, 2.0]])
C = 0.04 * K + 0.02 * M
K3, F1, F2 = 0.5, 0.12, 0.1
W1 = 1.1
W2 = 0.9 * (1 + np.sqrt(5)) / 2 * W1


def cubic(q, v, theta1, theta2):
    f = np.zeros_like(q)
    f[:, 0] = K3 * q[:, 0] ** 3
    dfdq = np.zeros((q.shape[0], 1, 1))
    dfdq[:, 0, 0] = 3 * K3 * q[:, 0] ** 2
    return f, dfdq, None


def chain(harmonics: TorusHarmonics, k3: float = K3) -> QuasiProblem:
    P = np.zeros((harmonics.rows, 2))
    P[1 + 2 * harmonics.index(1, 0), 0] = F1
    P[1 + 2 * harmonics.index(0, 1), 1] = F2
    return QuasiProblem(M, C, K, nl_dofs=np.array([0]), force=cubic if k3 else None,
                        excitation=P)


def test_harmonic_sets() -> None:
    box = TorusHarmonics.box(2, 1)
    assert box.size == (5 * 3 - 1) // 2
    assert all(k[0] > 0 or (k[0] == 0 and k[1] > 0) for k in box.k)
    diamond = TorusHarmonics.diamond(3)
    assert diamond.size == (2 * 3 * 4 + 1 - 1) // 2   # 2 h (h + 1) + 1 points, mean left out
    assert np.all(np.abs(diamond.k).sum(axis=1) <= 3)
    np.testing.assert_allclose(diamond.frequencies(1.0, 10.0),
                               diamond.k[:, 0] + 10.0 * diamond.k[:, 1])


def test_aft_round_trip_and_exact_jacobian() -> None:
    """Coefficients -> samples -> coefficients is the identity on the retained tones, and the
    analytic Jacobian is the derivative of the discrete map (checked by central differences,
    whose error here is ~1e-9)."""
    aft = TorusAFT(TorusHarmonics.diamond(3))
    rng = np.random.default_rng(0)
    X = 0.3 * rng.standard_normal((aft.harmonics.rows, 2))
    np.testing.assert_allclose(aft.to_coefficients(aft.to_samples(X)), X, atol=1e-14)

    def force(X):
        q = aft.to_samples(X.reshape(-1, 2))
        f = np.stack([q[:, 0] ** 3 + q[:, 0] * q[:, 1], np.sin(q[:, 1])], axis=1)
        Kt = np.zeros((q.shape[0], 2, 2))
        Kt[:, 0, 0], Kt[:, 0, 1] = 3 * q[:, 0] ** 2 + q[:, 1], q[:, 0]
        Kt[:, 1, 1] = np.cos(q[:, 1])
        return aft.to_coefficients(f).ravel(), aft.jacobian(Kt)

    _, J = force(X.ravel())
    h = 1e-5
    fd = np.stack([(force(X.ravel() + h * e)[0] - force(X.ravel() - h * e)[0]) / (2 * h)
                   for e in np.eye(X.size)], axis=1)
    np.testing.assert_allclose(J, fd, atol=1e-8 * np.abs(J).max())


def test_linear_tones_are_the_exact_harmonic_responses() -> None:
    """Without the cubic spring each forcing tone is answered by ``Z(Omega)^-1 p`` and every
    other tone is zero."""
    h = TorusHarmonics.diamond(3)
    sol = solve_quasi(chain(h, k3=0.0), TorusAFT(h), W1, W2)
    for (k1, k2), dof, force in (((1, 0), 0, F1), ((0, 1), 1, F2)):
        w = k1 * W1 + k2 * W2
        p = np.zeros(2)
        p[dof] = force
        x = np.linalg.solve(K - w**2 * M + 1j * w * C, p)
        j = h.index(k1, k2)
        np.testing.assert_allclose(sol.X[1 + 2 * j] - 1j * sol.X[2 + 2 * j], x, rtol=1e-12)
    others = [h.index(*k) for k in h.k if tuple(k) not in ((1, 0), (0, 1))]
    assert np.abs(sol.X[1 + 2 * np.array(others)]).max() == 0.0


@pytest.fixture(scope="module")
def torus():
    h = TorusHarmonics.diamond(7)
    return solve_quasi(chain(h), TorusAFT(h), W1, W2)


def test_the_torus_is_the_response_of_a_time_integration(torus) -> None:
    """Started on the HB torus, an independent integration stays on it (measured 2.1e-7 of
    the motion over 60 s; 1e-5 asserted, above the HB truncation at diamond order 7 and the
    integrator's 1e-11), and the tones it shows are the HB ones (measured to 8 digits; 1e-5
    relative asserted for the base tones, 1e-4 for the combination tone ``2 w1 - w2``, 2 %
    of the ``w2`` tone)."""
    sol = torus
    q0 = sol.evaluate(np.array([0.0]))[0]
    V = sol.aft.derivative_matrix(W1, W2) @ sol.X
    v0 = V[0] + V[1::2].sum(axis=0)  # the velocity at theta = 0: its cosine coefficients

    def rhs(t, y):
        q, v = y[:2], y[2:]
        f = np.array([F1 * np.cos(W1 * t), F2 * np.cos(W2 * t)]) - C @ v - K @ q
        f[0] -= K3 * q[0] ** 3
        return np.concatenate([v, f])

    t = np.linspace(0.0, 60.0, 6001)
    run = solve_ivp(rhs, (0.0, 60.0), np.concatenate([q0, v0]), method="DOP853",
                    rtol=1e-11, atol=1e-13, t_eval=t)
    assert run.success
    x = run.y[0]
    hb = sol.evaluate(t, [0])[:, 0]
    deviation = np.abs(x - hb).max() / np.abs(hb).max()
    print(f"deviation from the torus over 60 s: {deviation:.2e} of the motion")
    assert deviation < 1e-5
    k = sol.aft.harmonics.k
    phase = np.outer(t, k[:, 0] * W1 + k[:, 1] * W2)
    basis = np.hstack([np.ones((t.size, 1)), np.cos(phase), np.sin(phase)])
    coef = np.linalg.lstsq(basis, x, rcond=None)[0]
    n_h = k.shape[0]
    for tone, rtol in (((1, 0), 1e-5), ((0, 1), 1e-5), ((2, -1), 1e-4)):
        j = sol.aft.harmonics.index(*tone)
        fitted = np.hypot(coef[1 + j], coef[1 + n_h + j])
        print(f"tone {tone}: HB {sol.amplitude(0, *tone):.8f}, integration {fitted:.8f}")
        assert fitted == pytest.approx(sol.amplitude(0, *tone), rel=rtol), tone
    assert sol.amplitude(0, 2, -1) > 1e-2 * sol.amplitude(0, 0, 1)  # a real combination tone
    assert sol.amplitude(0, 1, 1) < 1e-12                             # even order: none


def test_amplitudes_converge_with_the_harmonic_set(torus) -> None:
    """The combination tone ``2 w1 - w2`` converges as the diamond grows."""
    values = []
    for order in (3, 5):
        h = TorusHarmonics.diamond(order)
        values.append(solve_quasi(chain(h), TorusAFT(h), W1, W2).amplitude(0, 2, -1))
    values.append(torus.amplitude(0, 2, -1))
    errors = np.abs(np.array(values[:2]) - values[2])
    assert errors[1] < errors[0]
    assert errors[1] < 1e-3 * values[2]


def test_condensed_jacobian_matches_finite_differences() -> None:
    h = TorusHarmonics.box(3, 2)
    aft, problem = TorusAFT(h), chain(h)
    tones = condense(problem, aft, W1, W2)
    Y = 0.2 * np.random.default_rng(2).standard_normal((h.rows, 1))
    _, J = residual(problem, aft, tones, W1, W2, Y)
    step = 1e-6

    def at(y):
        return residual(problem, aft, tones, W1, W2, y.reshape(Y.shape))[0]

    fd = np.stack([(at(Y.ravel() + step * e) - at(Y.ravel() - step * e)) / (2 * step)
                   for e in np.eye(Y.size)], axis=1)
    np.testing.assert_allclose(J, fd, atol=1e-7 * np.abs(J).max())


@pytest.mark.parametrize("kwargs, message", [
    ({"w1": 0.0}, "w1"), ({"w2": -1.0}, "w2"), ({"w1": float("nan")}, "w1"),
])
def test_bad_frequencies_are_refused(kwargs, message) -> None:
    h = TorusHarmonics.diamond(2)
    args = {"w1": W1, "w2": W2, **kwargs}
    with pytest.raises(ModelError, match=message):
        solve_quasi(chain(h), TorusAFT(h), args["w1"], args["w2"])


def test_bad_grid_and_excitation_are_refused() -> None:
    h = TorusHarmonics.diamond(3)
    with pytest.raises(ModelError, match="exceed twice"):
        TorusAFT(h, samples=(6, 16))
    problem = QuasiProblem(M, C, K, nl_dofs=np.array([0]), force=cubic,
                           excitation=np.zeros((3, 2)))
    with pytest.raises(ModelError, match="excitation has shape"):
        solve_quasi(problem, TorusAFT(h), W1, W2)
    with pytest.raises(ModelError, match="h1 and h2"):
        TorusHarmonics.box(0, 0)


def test_public_api_gives_the_same_torus(torus) -> None:
    """``rs.hb.solve_quasi`` on an ``rs.hb.System`` with a cubic spring element gives the
    torus of the core solver (the same equations; Newton to 1e-10 of the load)."""
    import rotorsim as rs

    chain_system = rs.hb.System(M, K, damping=C, elements=[rs.hb.CubicSpring(0, k3=K3)])
    sol = rs.hb.solve_quasi(chain_system, W1, W2, harmonics=7, forcing=[
        rs.hb.ToneForcing(0, F1, (1, 0)), rs.hb.ToneForcing(1, F2, (0, 1))])
    np.testing.assert_allclose(sol.X, torus.X, atol=1e-9 * np.abs(torus.X).max())
    with pytest.raises(ModelError, match="not in the harmonic set"):
        rs.hb.solve_quasi(chain_system, W1, W2, harmonics=3,
                          forcing=[rs.hb.ToneForcing(0, F1, (4, 0))])
    with pytest.raises(ModelError, match="diamond"):
        rs.hb.solve_quasi(chain_system, W1, W2, harmonics=3, truncation="circle")
