"""One quasi-periodic solution at fixed base frequencies, by damped Newton on the condensed
residual (:mod:`rotorsim.harmonic_balance.quasi.residual`).

The start is the linear response (the nonlinear force left out), or given coefficients of
the nonlinear DOFs. Unknowns are scaled by the size of the start and residuals by the size
of the condensed load, so the tolerance is relative whatever the units.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.quasi.aft import TorusAFT
from rotorsim.harmonic_balance.quasi.residual import (
    QuasiProblem,
    condense,
    full_coefficients,
    residual,
)
from rotorsim.solvers.newton import Newton, ResidualProblem

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class QuasiSolution:
    """Coefficients ``X (rows, n)`` of all DOFs on the harmonic set of ``aft``, at base
    frequencies ``w1, w2`` [rad/s]; ``residual`` is the final scaled residual and
    ``iterations`` the Newton iterations."""

    X: FloatArray
    aft: TorusAFT
    w1: float
    w2: float
    residual: float
    iterations: int

    def amplitude(self, dof: int, k1: int, k2: int) -> float:
        """Amplitude of the tone ``k1 w1 + k2 w2`` of ``dof`` (``|a_0|`` for ``(0, 0)``)."""
        if (k1, k2) == (0, 0):
            return float(abs(self.X[0, dof]))
        j = self.aft.harmonics.index(k1, k2)
        return float(np.hypot(self.X[1 + 2 * j, dof], self.X[2 + 2 * j, dof]))

    def evaluate(self, t: NDArray, dofs: NDArray | list[int] | None = None,
                 theta0: tuple[float, float] = (0.0, 0.0)) -> FloatArray:
        """The response at times ``t (m,)`` [s] on ``dofs`` (all when omitted): ``(m, k)``,
        with ``theta = (w1 t, w2 t) + theta0``."""
        X = self.X if dofs is None else self.X[:, np.asarray(dofs)]
        t = np.asarray(t, dtype=float)
        k = self.aft.harmonics.k
        phase = np.outer(t, k[:, 0] * self.w1 + k[:, 1] * self.w2) + k @ np.asarray(theta0)
        return X[0] + np.cos(phase) @ X[1::2] + np.sin(phase) @ X[2::2]


def solve_quasi(problem: QuasiProblem, aft: TorusAFT, w1: float, w2: float, *,
                start: FloatArray | None = None, tol: float = 1e-10,
                max_iter: int = 60) -> QuasiSolution:
    """The quasi-periodic response at base frequencies ``(w1, w2)`` [rad/s].

    Parameters
    ----------
    problem : QuasiProblem
    aft : TorusAFT
        Harmonic set and torus grid.
    start : array (rows, d), optional
        Coefficients of the nonlinear DOFs to start from (the linear response otherwise).
    tol : float
        Largest residual component relative to the condensed load.

    Raises
    ------
    ModelError
        Frequencies not positive and finite, or a start of the wrong shape.
    ConvergenceError
        Newton does not converge (the error names the iteration and residual).
    """
    for name, w in (("w1", w1), ("w2", w2)):
        if not (np.isfinite(w) and w > 0):
            raise ModelError(f"must be positive and finite, got {w!r}", f"solve_quasi.{name}")
    tones = condense(problem, aft, float(w1), float(w2))
    rows, d = aft.harmonics.rows, int(np.size(problem.nl_dofs))
    if d == 0:
        X = full_coefficients(problem, tones, np.zeros((rows, 0)))
        return QuasiSolution(X, aft, float(w1), float(w2), 0.0, 0)
    if start is None:
        Zc = np.linalg.solve(tones.S, tones.load[..., None])[..., 0]
        start = np.empty((rows, d))
        start[0] = Zc[0].real
        start[1::2], start[2::2] = Zc[1:].real, -Zc[1:].imag
    start = np.asarray(start, dtype=float)
    if start.shape != (rows, d):
        raise ModelError(f"start has shape {start.shape}, expected {(rows, d)}",
                         "solve_quasi.start")
    x_scale = max(float(np.abs(start).max(initial=0.0)), 1e-300)
    r_scale = max(float(np.abs(tones.load).max(initial=0.0)),
                  float(np.abs(tones.S).max(initial=0.0)) * x_scale, 1e-300)

    def fun(x: FloatArray) -> tuple[FloatArray, FloatArray]:
        r, J = residual(problem, aft, tones, float(w1), float(w2), x.reshape(rows, d))
        assert J is not None
        return r, J

    def value(x: FloatArray) -> FloatArray:
        return residual(problem, aft, tones, float(w1), float(w2), x.reshape(rows, d),
                        jacobian=False)[0]

    scaled = ResidualProblem.scaled(fun, rows * d, x_scale, r_scale, residual=value)
    state = Newton(tol=tol, max_iter=max_iter, where="quasi-periodic HB", dense=True).solve(
        scaled, start.ravel())
    X = full_coefficients(problem, tones, state.x.reshape(rows, d))
    return QuasiSolution(X, aft, float(w1), float(w2), float(state.residual),
                         int(state.iteration))
