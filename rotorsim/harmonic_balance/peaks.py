"""Amplitude peaks of a harmonic-balance branch.

The amplitude of a set of DOFs at a periodic solution is the largest Euclidean norm of
their displacements over a period, ``a = max_tau |q_c(tau)|`` (one DOF: ``max |q|``; the
two lateral DOFs of a node: the largest orbit radius). :func:`orbit_amplitude` finds the
maximum on a grid of phases and polishes it by Newton's method on ``d|q|^2/dtau = 0``, so
``a`` is a smooth function of the coefficients (a sampled maximum would be piecewise and
its slope along the branch meaningless). :func:`locate_peaks` locates the extrema of ``a``
along a branch with :func:`~rotorsim.solvers.continuation_extrema.locate_extrema`.

References
----------
Seed 002 section 3.5.2.1 (Fourier series of the response). M. Krack, J. Gross, Harmonic
Balance for Nonlinear Vibration Problems, Springer 2019, section 4.4 (frequency-response
peaks).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.fourier import AFT, FloatArray, IntArray, derivative
from rotorsim.harmonic_balance.residual import HBResidual, continuation_function
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.continuation_extrema import Extremum, locate_extrema

NEWTON_STEPS = 8
"""Newton iterations on the phase of the maximum (quadratic convergence from the grid)."""


def orbit_amplitude(X: ArrayLike, grid: int = 0) -> float:
    """``max_tau |q(tau)|`` of the coefficients ``X`` (2H + 1, c) [units of ``X``].

    Parameters
    ----------
    X : array (2H + 1, c)
        Coefficients of ``c`` DOFs (layout of :mod:`~rotorsim.harmonic_balance.fourier`).
    grid : int
        Phases of the first search (default ``max(16 (2H + 1), 64)``).

    Examples
    --------
    ``q = cos(tau) + 0.5 cos(2 tau)`` has its largest ``|q|`` 1.5 at ``tau = 0``; the orbit
    ``(cos, 2 sin)`` has radius 2 at most:

    >>> round(orbit_amplitude([[0.0], [1.0], [0.0], [0.5], [0.0]]), 12)
    1.5
    >>> round(orbit_amplitude([[0.0, 0.0], [1.0, 0.0], [0.0, 2.0]]), 12)
    2.0
    """
    C = np.asarray(X, dtype=float)
    C = C.reshape(C.shape[0], -1)
    H = (C.shape[0] - 1) // 2
    count = grid or max(16 * C.shape[0], 64)
    aft = AFT(H)
    tau0 = 2.0 * np.pi * np.arange(count) / count
    size = np.sum((aft.basis(tau0) @ C) ** 2, axis=1)
    tau = float(tau0[int(np.argmax(size))])
    D1, D2 = derivative(C), derivative(C, 2)
    spacing = 2.0 * np.pi / count
    best = float(size.max())
    for _ in range(NEWTON_STEPS):
        G = aft.basis([tau])
        q, dq, ddq = (G @ C)[0], (G @ D1)[0], (G @ D2)[0]
        slope, curvature = 2.0 * q @ dq, 2.0 * (dq @ dq + q @ ddq)
        if curvature >= 0.0:
            break
        step = float(np.clip(-slope / curvature, -spacing, spacing))
        tau += step
        if abs(step) <= 1e-15 * (1.0 + abs(tau)):
            break
    G = aft.basis([tau])
    return float(np.sqrt(max(best, float(np.sum((G @ C) ** 2)))))


@dataclass(frozen=True, eq=False)
class AmplitudeMeasure:
    """``measure(x, lam)``: :func:`orbit_amplitude` of the DOFs ``columns`` (of all the
    problem's DOFs) at a point of a branch in ``omega`` or, at fixed ``omega``, in ``p``."""

    residual: HBResidual
    columns: IntArray
    parameter: Literal["omega", "param"] = "omega"
    omega: float | None = None
    param: float = 0.0

    def __call__(self, x: FloatArray, lam: float) -> float:
        if self.parameter == "omega":
            X = self.residual.expand(x, lam, self.param)
        else:
            assert self.omega is not None
            X = self.residual.expand(x, self.omega, lam)
        return orbit_amplitude(X[:, self.columns])


def locate_peaks(residual: HBResidual, branch: Branch, dofs: Sequence[int] | int, *,
                 parameter: Literal["omega", "param"] = "omega", omega: float | None = None,
                 param: float = 0.0, kinds: Sequence[str] = ("max",), tol: float = 1e-10
                 ) -> tuple[Extremum, ...]:
    """Amplitude extrema of the DOFs ``dofs`` along a branch of ``residual``.

    Parameters
    ----------
    residual : HBResidual
        The discretisation that produced ``branch``.
    branch : Branch
        From :func:`~rotorsim.solvers.continuation.continue_branch` with
        :func:`~rotorsim.harmonic_balance.residual.continuation_function`.
    dofs : int or sequence of int
        DOFs of the problem (indices among its ``n``) whose joint amplitude is measured.
    parameter, omega, param
        As for ``continuation_function``.
    kinds : sequence of {"max", "min"}
    tol : float
        Location tolerance in scaled arclength.

    Returns
    -------
    tuple of Extremum
        ``value`` the amplitude [units of the DOFs], ``lam`` the parameter.

    Examples
    --------
    Single-harmonic Duffing ``x'' + 0.05 x' + x + 0.1 x^3 = 0.18 cos(omega t)``: the peak
    of the closed form is ``a = 2.8416`` at ``omega = 1.2666``.

    >>> from rotorsim.harmonic_balance.problem import HBProblem
    >>> from rotorsim.harmonic_balance.residual import make_residual
    >>> from rotorsim.solvers.continuation import Continuation, continue_branch
    >>> cubic = lambda q, v, tau, w, p: (0.1 * q**3, 0.3 * q[:, :, None]**2, None)
    >>> res = make_residual(HBProblem(np.eye(1), np.eye(1), 0.05 * np.eye(1), nl_dofs=[0],
    ...                     force=cubic, excitation=[[0.0], [0.18], [0.0]]), 1)
    >>> fun = continuation_function(res)
    >>> b = continue_branch(fun, np.zeros(3), 0.5, Continuation(max_step=0.2, lam_max=2.0))
    >>> [(p.kind, round(p.value, 4), round(p.lam, 4)) for p in locate_peaks(res, b, 0)]
    [('max', 2.8416, 1.2666)]
    """
    columns = np.atleast_1d(np.asarray(dofs, dtype=np.int64))
    n = residual.problem.n
    if columns.size == 0 or columns.min() < 0 or columns.max() >= n:
        raise ModelError(f"dofs must be indices in [0, {n}), got {columns.tolist()}",
                         "locate_peaks")
    fun = continuation_function(residual, parameter, omega=omega, param=param)
    measure = AmplitudeMeasure(residual, columns, parameter, omega, param)
    return locate_extrema(fun, branch, measure, kinds=kinds, tol=tol)
