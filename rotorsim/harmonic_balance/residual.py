"""Harmonic-balance residual with its analytic Jacobian and parameter derivatives.

Public API (stable; used by continuation and bifurcation code)
--------------------------------------------------------------
``make_residual(problem, harmonics, *, samples=None, condense=True) -> HBResidual``
    The discretised problem: :class:`~.condensation.CondensedResidual` (unknowns on the
    nonlinear DOFs only) or :class:`HarmonicBalanceResidual` (all DOFs).

An :class:`HBResidual` has ``size`` unknowns ``x`` (the flattened coefficient array of its
DOFs in the harmonic-major layout of :mod:`~rotorsim.harmonic_balance.fourier`) and

* ``evaluate(x, omega, param=0.0, *, jacobian=True, d_omega=False, d_param=False,
  stats=None) -> HBEvaluation`` with ``r`` (size,), ``jacobian = dr/dx`` (size, size),
  ``d_omega = dr/domega`` and ``d_param = dr/dp`` (size,);
* ``expand(x, omega, param=0.0) -> X`` (2H + 1, n): coefficients of all DOFs;
* ``restrict(X) -> x``: the unknowns of a full coefficient array (initial guesses);
* ``with_discretization(harmonics=None, samples=None)``: the same problem on another
  ``(H, N)``.

:func:`continuation_function` wraps one into ``fun(x, lam) -> (r, dr/dx, dr/dlam)`` with
``lam`` either ``omega`` or ``p``.

The residual of harmonic ``h`` (rows ``cos``, ``sin``) is

    [K - (h w)^2 M     h w D      ] [Q_hc]            [F_hc]
    [   -h w D      K - (h w)^2 M ] [Q_hs] + F_nl,h - [F_hs] ,   D = C + W(w) G,

(seed 002 after eq 3.32, with the gyroscopic matrix inside ``D``), i.e.
``R = K X + w D nabla X + w^2 M nabla^2 X + F_nl(X) - F_ext`` in operator form. ``dR/dw``
is analytic for the linear terms, the gyroscopic speed ``W(w)`` and the velocity argument of
the force; the excitation (and an explicit ``omega`` dependence of the force) are
differentiated by central differences, and so is ``dR/dp``.

References
----------
Seed 002 section 3.5.2.1, eqs 3.30-3.36.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Literal, Protocol

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.fourier import (
    AFT,
    FloatArray,
    IntArray,
    derivative,
    derivative_matrix,
)
from rotorsim.harmonic_balance.memory import check_memory
from rotorsim.harmonic_balance.nonlinear import (
    excitation_derivatives,
    nonlinear_harmonics,
    nonlinear_param_derivative,
)
from rotorsim.harmonic_balance.problem import HBProblem, Matrix, as_dense
from rotorsim.solvers.stats import Stats


@dataclass(frozen=True, eq=False)
class HBEvaluation:
    """Residual ``r`` (m,) [N] and, when requested, ``jacobian`` (m, m), ``d_omega`` and
    ``d_param`` (m,); ``terms`` (m,) [N] is the size of the terms summed in each component
    of ``r`` (``|K| |x| + |f_nl| + |f|``, before cancellation), from which continuation
    judges the round-off floor of the residual (None: unknown)."""

    r: FloatArray
    jacobian: FloatArray | None = None
    d_omega: FloatArray | None = None
    d_param: FloatArray | None = None
    terms: FloatArray | None = None


class HBResidual(Protocol):
    """What continuation, Floquet and the Newton solve need of a discretised problem."""

    @property
    def problem(self) -> HBProblem: ...

    @property
    def harmonics(self) -> int: ...

    @property
    def samples(self) -> int: ...

    @property
    def aft(self) -> AFT: ...

    @property
    def size(self) -> int: ...

    @property
    def dofs(self) -> IntArray: ...

    def evaluate(self, x: ArrayLike, omega: float, param: float = 0.0, *,
                 jacobian: bool = True, d_omega: bool = False, d_param: bool = False,
                 stats: Stats | None = None) -> HBEvaluation: ...

    def expand(self, x: ArrayLike, omega: float, param: float = 0.0) -> FloatArray: ...

    def restrict(self, X: ArrayLike) -> FloatArray: ...

    def with_discretization(self, harmonics: int | None = None,
                            samples: int | None = None) -> HBResidual: ...


def make_residual(problem: HBProblem, harmonics: int, *, samples: int | None = None,
                  condense: bool = True) -> HBResidual:
    """Discretise ``problem`` with ``harmonics`` harmonics and ``samples`` time samples.

    Parameters
    ----------
    problem : HBProblem
    harmonics : int
        ``H >= 0``.
    samples : int, optional
        ``N >= 2H + 1`` (default ``2**ceil(log2(max(8 H, 16)))``).
    condense : bool
        Unknowns on the nonlinear DOFs only (exact Schur complement per harmonic, see
        :mod:`~rotorsim.harmonic_balance.condensation`) or on all DOFs.

    Raises
    ------
    ModelError
        For bad ``harmonics`` or ``samples``, or when the discretisation would need more
        memory than :func:`~rotorsim.harmonic_balance.memory.check_memory` allows.

    Examples
    --------
    >>> cubic = lambda q, v, tau, w, p: (q**3, 3 * q[:, :, None]**2, None)
    >>> pb = HBProblem(np.eye(2), np.eye(2), nl_dofs=[1], force=cubic)
    >>> make_residual(pb, 3).size, make_residual(pb, 3, condense=False).size
    (7, 14)
    """
    aft = AFT(harmonics, samples or 0)
    check_memory(aft.harmonics, aft.samples, problem.k, problem.n, condense=condense,
                 where="make_residual")
    if condense:
        from rotorsim.harmonic_balance.condensation import CondensedResidual

        return CondensedResidual(problem, harmonics, samples or 0)
    return HarmonicBalanceResidual(problem, harmonics, samples or 0)


@dataclass(frozen=True, eq=False)
class HarmonicBalanceResidual:
    """Harmonic balance on all ``n`` DOFs: ``size = (2H + 1) n`` unknowns.

    Meant for checking the condensed form and for small systems: the Jacobian is dense.

    Examples
    --------
    Linear oscillator ``x'' + x = cos(2 t)``: the exact solution ``-cos(2t) / 3`` has zero
    residual.

    >>> pb = HBProblem(np.eye(1), np.eye(1), excitation=[[0.0], [1.0], [0.0]])
    >>> res = HarmonicBalanceResidual(pb, 1)
    >>> ev = res.evaluate([0.0, -1.0 / 3.0, 0.0], 2.0)
    >>> bool(np.abs(ev.r).max() < 1e-15), ev.jacobian.shape
    (True, (3, 3))
    """

    problem: HBProblem
    harmonics: int
    samples: int = 0

    def __post_init__(self) -> None:
        aft = AFT(self.harmonics, self.samples)
        object.__setattr__(self, "harmonics", aft.harmonics)
        object.__setattr__(self, "samples", aft.samples)

    @cached_property
    def aft(self) -> AFT:
        """Transforms of this discretisation."""
        return AFT(self.harmonics, self.samples)

    @property
    def size(self) -> int:
        """Number of unknowns ``(2H + 1) n``."""
        return self.aft.rows * self.problem.n

    @property
    def dofs(self) -> IntArray:
        """DOFs carried by the unknowns (all)."""
        return np.arange(self.problem.n, dtype=np.int64)

    def evaluate(self, x: ArrayLike, omega: float, param: float = 0.0, *,
                 jacobian: bool = True, d_omega: bool = False, d_param: bool = False,
                 stats: Stats | None = None) -> HBEvaluation:
        """Residual and derivatives at ``x`` (size,), ``omega`` [rad/s] and ``param``."""
        pb, aft = self.problem, self.aft
        X = self.expand(x, omega, param)
        if stats is not None:
            stats.residual_evaluations += 1
        nl = nonlinear_harmonics(pb, aft, X[:, pb.nl_dofs], omega, param, jacobian=jacobian,
                                 d_omega=d_omega)
        F = pb.excitation_coefficients(aft, omega, param)
        R = linear_apply(pb, X, omega) - F
        R[:, pb.nl_dofs] += nl.force
        J = dw = dp = terms = None
        if jacobian:
            assert nl.jacobian is not None
            J = linear_jacobian(pb, self.harmonics, omega)
            terms = np.abs(J) @ np.abs(X.reshape(-1)) + np.abs(F.reshape(-1))
            idx = self._nl_index
            J[np.ix_(idx, idx)] += nl.jacobian
            size = np.abs(nl.force).sum(axis=0)     # FFT round-off spreads over harmonics
            terms[idx] += np.tile(2.0 * size, aft.rows)
        if d_omega or d_param:
            dfw, dfp = excitation_derivatives(pb, aft, omega, param, d_omega=d_omega,
                                              d_param=d_param)
            if d_omega:
                assert nl.d_omega is not None
                Rw = linear_omega_derivative(pb, X, omega) - dfw
                Rw[:, pb.nl_dofs] += nl.d_omega
                dw = Rw.reshape(-1)
            if d_param:
                Rp = -dfp
                Rp[:, pb.nl_dofs] += nonlinear_param_derivative(pb, aft, X[:, pb.nl_dofs],
                                                                omega, param)
                dp = Rp.reshape(-1)
        return HBEvaluation(R.reshape(-1), J, dw, dp, terms)

    def expand(self, x: ArrayLike, omega: float, param: float = 0.0) -> FloatArray:
        """Coefficients (2H + 1, n) of all DOFs (a reshape of ``x``)."""
        return as_unknowns(x, self.size).reshape(self.aft.rows, self.problem.n)

    def restrict(self, X: ArrayLike) -> FloatArray:
        """Unknowns (size,) of the coefficient array ``X`` (2H + 1, n)."""
        return as_coefficients(X, self.aft.rows, self.problem.n).reshape(-1).copy()

    def with_discretization(self, harmonics: int | None = None,
                            samples: int | None = None) -> HarmonicBalanceResidual:
        """Same problem with other ``H`` and/or ``N`` (``N`` defaults to the rule of
        :func:`~.fourier.default_samples` when only ``H`` changes)."""
        H = self.harmonics if harmonics is None else harmonics
        N = samples if samples is not None else (self.samples if harmonics is None else 0)
        return replace(self, harmonics=H, samples=N)

    @cached_property
    def _nl_index(self) -> IntArray:
        rows = np.arange(self.aft.rows)[:, None] * self.problem.n
        return (rows + self.problem.nl_dofs[None, :]).reshape(-1)


def linear_apply(problem: HBProblem, X: FloatArray, omega: float) -> FloatArray:
    """``K X + w D nabla X + w^2 M nabla^2 X`` (2H + 1, n) for coefficients ``X``."""
    dX = derivative(X)
    out = _times(problem.stiffness, X) + omega * _times(problem.damping_matrix(omega), dX)
    return out + omega**2 * _times(problem.mass, derivative(dX))


def linear_omega_derivative(problem: HBProblem, X: FloatArray, omega: float) -> FloatArray:
    """``d/dw`` of :func:`linear_apply` at fixed ``X``:
    ``(D + w dD/dw) nabla X + 2 w M nabla^2 X``."""
    dX = derivative(X)
    D = problem.damping_matrix(omega) + omega * problem.damping_derivative()
    return _times(D, dX) + 2.0 * omega * _times(problem.mass, derivative(dX))


def linear_jacobian(problem: HBProblem, harmonics: int, omega: float) -> FloatArray:
    """Dense ``I (x) K + w nabla (x) D + w^2 nabla^2 (x) M`` ((2H + 1) n, (2H + 1) n)."""
    nabla = derivative_matrix(harmonics)
    terms = [(np.eye(2 * harmonics + 1), problem.stiffness),
             (omega * nabla, problem.damping_matrix(omega)),
             (omega**2 * nabla @ nabla, problem.mass)]
    out = np.zeros((len(nabla) * problem.n, len(nabla) * problem.n))
    for A, B in terms:
        out += np.kron(A, as_dense(B))
    return out


def continuation_function(
    residual: HBResidual, parameter: Literal["omega", "param"] = "omega", *,
    omega: float | None = None, param: float = 0.0, stats: Stats | None = None,
    terms: bool = False,
) -> Callable[[FloatArray, float], tuple[FloatArray, ...]]:
    """``fun(x, lam) -> (r, dr/dx, dr/dlam)`` for continuation in ``omega`` or ``p``.

    Parameters
    ----------
    residual : HBResidual
    parameter : {"omega", "param"}
        Which argument ``lam`` is; the other one is held at ``omega`` or ``param``.
    omega, param : float
        The fixed value of the other argument (``omega`` is required when continuing in
        ``param``).
    stats : Stats, optional
        Counter of residual evaluations.
    terms : bool
        Return ``(r, dr/dx, dr/dlam, terms)`` with the size of the terms of ``r``
        (:class:`HBEvaluation`) when the residual knows it: continuation then judges
        convergence against the round-off floor of the actual sums
        (:data:`rotorsim.solvers.continuation_core.ROUNDOFF`).

    Examples
    --------
    >>> pb = HBProblem(np.eye(1), np.eye(1), excitation=[[0.0], [1.0], [0.0]])
    >>> fun = continuation_function(make_residual(pb, 1, condense=False))
    >>> r, J, r_lam = fun(np.array([0.0, -1.0 / 3.0, 0.0]), 2.0)
    >>> np.round(r_lam, 12).tolist()   # d/dw of (1 - w^2) Q_1c
    [0.0, 1.333333333333, 0.0]
    """
    if parameter not in ("omega", "param"):
        raise TypeError(f"unknown parameter {parameter!r}; valid: omega, param")
    if parameter == "param" and omega is None:
        raise ModelError("give the fixed omega when continuing in param",
                         "continuation_function")

    def fun(x: FloatArray, lam: float) -> tuple[FloatArray, ...]:
        if parameter == "omega":
            ev = residual.evaluate(x, lam, param, d_omega=True, stats=stats)
            r_lam = ev.d_omega
        else:
            assert omega is not None
            ev = residual.evaluate(x, omega, lam, d_param=True, stats=stats)
            r_lam = ev.d_param
        assert ev.jacobian is not None and r_lam is not None
        if terms and ev.terms is not None:
            return ev.r, ev.jacobian, r_lam, ev.terms
        return ev.r, ev.jacobian, r_lam

    return fun


def _times(A: Matrix, X: FloatArray) -> FloatArray:
    """Rows of ``X`` multiplied by ``A``: ``(A @ X.T).T``."""
    return np.asarray(A @ X.T).T


def as_unknowns(x: ArrayLike, size: int) -> FloatArray:
    arr = np.asarray(x, dtype=float).reshape(-1)
    if arr.shape != (size,):
        raise ModelError(f"expected {size} unknowns, got shape {np.shape(x)}",
                         "harmonic balance")
    return arr


def as_coefficients(X: ArrayLike, rows: int, n: int) -> FloatArray:
    arr = np.asarray(X, dtype=float)
    if arr.shape != (rows, n):
        raise ModelError(f"expected coefficients of shape ({rows}, {n}), got {arr.shape}",
                         "harmonic balance")
    return arr
