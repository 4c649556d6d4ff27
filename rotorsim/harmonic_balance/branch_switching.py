"""Branch switching of harmonic-balance branches: period doubling and branch points.

Period doubling. A periodic solution of fundamental ``omega`` is also a solution of the
same problem written with the fundamental ``omega / 2`` (:func:`subharmonic_problem`): its
harmonic ``h`` becomes harmonic ``2h`` (:func:`spread_harmonics`) and the odd harmonics
of ``omega / 2`` are zero. The tangents along such a solution have period ``T``, so the
Jacobian of the doubled residual does not couple even and odd harmonics: it is
block-diagonal (even block: the period-1 Jacobian; odd block: the variational problem in
the space of ``2T``-periodic, ``T``-antiperiodic functions). A Floquet multiplier ``-1``
is a ``T``-antiperiodic solution of the variational equation, i.e. a null vector of the
odd block; in the doubled formulation period doubling is a pitchfork, the symmetry being
the time shift by ``T`` (odd harmonics change sign). :func:`period_doubling_direction`
takes the right singular vector of the (scaled) odd block with the smallest singular
value, and :func:`switch_period_doubling` jumps along it and continues the period-2 branch
(:func:`~rotorsim.solvers.continuation_switch.continue_from`).

The doubled problem keeps the physics: the spin is ``W = spin + 2 spin_ratio (omega / 2)``
and the force, load and excitation callbacks see the phase ``2 tau`` and the frequency
``2 (omega / 2)`` of the original problem, so shaft and rolling-element angles are those of
the period-1 problem.

Branch points. :func:`switch_branch_point` continues the second branch through a simple
branch point (null space of ``[dR/dx, dR/domega]``, see
:mod:`rotorsim.solvers.continuation_switch`).

References
----------
R. Seydel, Practical Bifurcation and Stability Analysis, Springer 2010, section 7.6
(period doubling as a pitchfork of the doubled-period problem). Y. A. Kuznetsov, Elements
of Applied Bifurcation Theory, 3rd ed., Springer 2004, section 10.3.2. A. Lazarus,
O. Thomas, C. R. Mecanique 338 (2010) 510-517 (Floquet in the harmonic basis).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.fourier import FloatArray, harmonic_numbers, whole
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import (
    HBResidual,
    as_unknowns,
    continuation_function,
    make_residual,
)
from rotorsim.harmonic_balance.solve import solve_point
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.continuation_stepper import Continuation
from rotorsim.solvers.continuation_switch import Jump, continue_from

WHERE = "branch switching"
REFINE_STEPS = 12
"""Secant iterations placing a period doubling on the odd block's singularity."""


def spread_harmonics(X: ArrayLike, factor: int, harmonics: int) -> FloatArray:
    """Coefficients of the same signal over the fundamental ``omega / factor``.

    Row ``h`` (harmonic ``h``) of ``X`` (2H + 1, ...) becomes harmonic ``factor h`` of the
    result (2 harmonics + 1, ...); harmonics above ``harmonics`` are dropped.

    Examples
    --------
    >>> spread_harmonics([[1.0], [2.0], [3.0]], 2, 2).ravel().tolist()
    [1.0, 0.0, 0.0, 2.0, 3.0]
    """
    X = np.asarray(X, dtype=float)
    out = np.zeros((2 * harmonics + 1, *X.shape[1:]))
    out[0] = X[0]
    h = np.arange(1, (X.shape[0] - 1) // 2 + 1)
    keep = factor * h <= harmonics
    out[2 * factor * h[keep] - 1] = X[2 * h[keep] - 1]
    out[2 * factor * h[keep]] = X[2 * h[keep]]
    return out


def subharmonic_problem(problem: HBProblem, factor: int = 2) -> HBProblem:
    """``problem`` written with the fundamental ``omega / factor``.

    The callbacks of the result take the doubled problem's phase and frequency and call
    those of ``problem`` with ``factor`` times them; the excitation coefficients move from
    harmonic ``h`` to ``factor h``; ``spin_ratio`` is multiplied by ``factor``.

    Examples
    --------
    >>> pb = HBProblem(np.eye(1), np.eye(1), excitation=[[0.0], [1.0], [0.0]],
    ...                spin_ratio=1.0)
    >>> half = subharmonic_problem(pb)
    >>> half.spin_speed(1.0), half.excitation(1.0, 0.0).ravel().tolist()
    (2.0, [0.0, 0.0, 0.0, 1.0, 0.0])
    """
    if not whole(factor, 2):
        raise ModelError(f"factor must be an integer >= 2, got {factor!r}",
                         "subharmonic_problem")
    f = int(factor)
    force, load, excitation = problem.force, problem.load, problem.excitation
    return dataclasses.replace(
        problem,
        force=None if force is None else _ScaledPhase(force, f),
        load=None if load is None else _ScaledPhase(load, f),
        excitation=None if excitation is None else _SpreadExcitation(excitation, f),
        spin_ratio=f * problem.spin_ratio)


@dataclass(frozen=True)
class _ScaledPhase:
    """``callback(x..., tau, omega, p)`` called with ``factor tau`` and ``factor omega``."""

    callback: Any
    factor: int

    def __call__(self, *args: Any) -> Any:
        *states, tau, omega, param = args
        return self.callback(*states, self.factor * tau, self.factor * omega, param)


@dataclass(frozen=True)
class _SpreadExcitation:
    """Excitation coefficients of ``factor omega`` moved to harmonics ``factor h``."""

    excitation: Any
    factor: int

    def __call__(self, omega: float, param: float) -> FloatArray:
        coeff = self.excitation
        if callable(coeff):
            coeff = np.asarray(coeff(self.factor * omega, param), dtype=float)
        rows = np.shape(coeff)[0]
        return spread_harmonics(coeff, self.factor, self.factor * ((rows - 1) // 2))


@dataclass(frozen=True, eq=False)
class PeriodDoubling:
    """A period-doubling point written in the doubled basis.

    Attributes
    ----------
    residual : HBResidual
        The doubled problem (fundamental ``omega / 2``).
    x : array (residual.size,)
        The period-1 solution at the point, in the doubled unknowns.
    omega : float
        Fundamental of the doubled problem, half that of the period-1 branch [rad/s].
    param : float
    direction : array (residual.size,)
        Unit null vector of the odd block (odd harmonics only), physical units.
    singular_values : array (2,)
        Smallest and second smallest singular values of the scaled odd block, smallest
        last: the first small against the second says the point is a simple period
        doubling.
    """

    residual: HBResidual
    x: FloatArray
    omega: float
    param: float
    direction: FloatArray
    singular_values: FloatArray


def odd_rows(residual: HBResidual) -> FloatArray:
    """Boolean mask (residual.size,) of the unknowns of odd harmonics."""
    per = residual.size // residual.aft.rows
    return np.repeat(harmonic_numbers(residual.harmonics) % 2 == 1, per)


def period_doubling_point(residual: HBResidual, x: ArrayLike, omega: float,
                          param: float = 0.0, *,
                          parameter: Literal["omega", "param"] = "omega",
                          harmonics: int | None = None, samples: int | None = None,
                          condense: bool | None = None, x_scale: ArrayLike | float = 1.0,
                          refine: bool = True) -> PeriodDoubling:
    """The period-doubling point ``(x, omega)`` of ``residual`` in the doubled basis.

    Parameters
    ----------
    residual : HBResidual
        The period-1 discretisation (``H`` harmonics, ``N`` samples).
    x : array (residual.size,)
        The period-1 solution at (or next to) the period doubling.
    omega : float
        Its fundamental [rad/s].
    param : float
    parameter : {"omega", "param"}
        The parameter along which ``refine`` moves.
    harmonics, samples : int, optional
        Of the doubled problem (default ``2H`` and ``2N``: the same harmonics and time
        resolution as the period-1 problem, plus the odd ones).
    condense : bool, optional
        Condensed unknowns (default: as ``residual``).
    x_scale : float or array (residual.size,)
        Scale of the period-1 unknowns (per unknown); the odd block is scaled with it,
        harmonic by harmonic.
    refine : bool
        Move the point along the period-1 branch (Newton solves at fixed parameter) to
        where the odd block is singular, by the secant method on its smallest singular
        value signed by its determinant: the period doubling of this discretisation,
        which a Floquet method locates only to its own accuracy (Hsu's method, the
        ``1 + tol`` threshold).
    """
    H2 = 2 * residual.harmonics if harmonics is None else int(harmonics)
    N2 = 2 * residual.samples if samples is None else int(samples)
    full = residual.dofs.size == residual.problem.n and residual.problem.k < residual.problem.n
    keep = not full if condense is None else bool(condense)
    doubled = make_residual(subharmonic_problem(residual.problem), H2, samples=N2,
                            condense=keep and residual.problem.k > 0)
    per = residual.size // residual.aft.rows
    if doubled.size // doubled.aft.rows != per:
        raise ModelError("condense must match the period-1 residual's unknowns", WHERE)
    scale = np.broadcast_to(np.asarray(x_scale, dtype=float), (residual.size,))
    block = _OddBlock(residual, doubled, scale.reshape(residual.aft.rows, per).max(axis=0))
    x1 = as_unknowns(x, residual.size)
    lam = float(omega) if parameter == "omega" else float(param)
    if refine:
        x1, lam = block.refined(x1, lam, parameter, omega, param, scale)
    w, p = (lam, param) if parameter == "omega" else (omega, lam)
    _, s, vt = np.linalg.svd(block.matrix(x1, w, p))
    phi = np.zeros(doubled.size)
    phi[block.odd] = vt[-1] * block.xs
    phi /= np.linalg.norm(phi)
    phi *= 1.0 if phi[np.argmax(np.abs(phi))] > 0 else -1.0
    return PeriodDoubling(doubled, block.spread(x1), w / 2.0, float(p), phi, s[-2:])


@dataclass(frozen=True, eq=False)
class _OddBlock:
    """The scaled odd-harmonic block of the doubled Jacobian at period-1 points."""

    residual: HBResidual
    doubled: HBResidual
    per_dof: FloatArray

    @property
    def odd(self) -> Any:
        return odd_rows(self.doubled)

    @property
    def xs(self) -> FloatArray:
        return np.tile(self.per_dof, self.doubled.aft.rows)[self.odd]

    def spread(self, x1: FloatArray) -> FloatArray:
        X = x1.reshape(self.residual.aft.rows, -1)
        return spread_harmonics(X, 2, self.doubled.harmonics).reshape(-1)

    def matrix(self, x1: FloatArray, omega: float, param: float) -> FloatArray:
        """Odd block at the period-1 point ``x1``, columns scaled, rows normalised."""
        ev = self.doubled.evaluate(self.spread(x1), omega / 2.0, param)
        assert ev.jacobian is not None
        J = ev.jacobian[np.ix_(self.odd, self.odd)] * self.xs[None, :]
        rows = np.max(np.abs(J), axis=1)
        return J / np.where(rows > 0, rows, 1.0)[:, None]

    def test(self, x1: FloatArray, omega: float, param: float) -> float:
        """Smallest singular value signed by the determinant (zero at the doubling)."""
        J = self.matrix(x1, omega, param)
        sign, _ = np.linalg.slogdet(J)
        return float(sign * np.linalg.svd(J, compute_uv=False)[-1])

    def refined(self, x1: FloatArray, lam: float, parameter: str, omega: float,
                param: float, scale: FloatArray) -> tuple[FloatArray, float]:
        """Secant iteration on :meth:`test` along the period-1 branch; the start when it
        fails or leaves a neighbourhood of 1e-2 relative."""
        def point(value: float, guess: FloatArray) -> tuple[FloatArray, float]:
            w, p = (value, param) if parameter == "omega" else (omega, value)
            sol = solve_point(self.residual, w, guess, param=p, x_scale=scale)
            return sol.x, self.test(sol.x, w, p)

        try:
            xa, ga = point(lam, x1)
            width = 1e-6 * max(abs(lam), 1.0)
            b = lam + width
            xb, gb = point(b, xa)
            a = lam
            for _ in range(REFINE_STEPS):
                if gb == ga or abs(b - a) <= 1e-13 * max(abs(b), 1.0):
                    break
                c = b - gb * (b - a) / (gb - ga)
                if abs(c - lam) > 1e-2 * max(abs(lam), 1.0):
                    return x1, lam
                a, xa, ga = b, xb, gb
                b = c
                xb, gb = point(b, xa)
        except ConvergenceError:
            return x1, lam
        return xb, b


def switch_period_doubling(residual: HBResidual, x: ArrayLike, omega: float,
                           options: Continuation, *, param: float = 0.0,
                           parameter: Literal["omega", "param"] = "omega",
                           harmonics: int | None = None, samples: int | None = None,
                           x_scale: ArrayLike | float = 1.0, step: float | None = None,
                           sign: int = 1, **driver: Any
                           ) -> tuple[Branch, PeriodDoubling, Jump]:
    """Continue the period-2 branch born at a period doubling.

    Parameters
    ----------
    residual, x, omega, param
        The period-1 problem and its solution at the located period doubling
        (e.g. a :class:`~rotorsim.harmonic_balance.bifurcation.BifurcationEvent`'s ``x``
        and ``lam``).
    options : Continuation
        Of the period-2 branch, whose parameter is the doubled problem's: its fundamental
        ``omega / 2`` (``parameter="omega"``: bounds and ``lam_scale`` in it) or ``p`` at
        the fixed fundamental ``omega / 2``.
    parameter : {"omega", "param"}
    harmonics, samples, x_scale
        See :func:`period_doubling_point`; ``x_scale`` scales the jump too when
        ``options.x_scale`` is 1.
    step : float, optional
        Scaled length of the jump along the odd null vector (default
        ``options.initial_step``).
    sign : {1, -1}
        Which way along it (both give the same orbit shifted by one period ``T``).
    **driver
        Passed to :func:`~rotorsim.solvers.continuation.continue_branch`.

    Returns
    -------
    (Branch, PeriodDoubling, Jump)
        The period-2 branch (continued in the doubled problem's parameter, unknowns of
        ``doubling.residual``), the period doubling in the doubled basis and the jump.

    Examples
    --------
    See ``tests/harmonic_balance/test_branch_switching.py`` (a Duffing oscillator with a
    static preload, whose period-1 response near twice its natural frequency doubles).
    """
    pd = period_doubling_point(residual, x, omega, param, parameter=parameter,
                               harmonics=harmonics, samples=samples, x_scale=x_scale)
    fun = continuation_function(pd.residual, parameter, omega=pd.omega, param=param,
                                terms=True)
    lam = pd.omega if parameter == "omega" else float(param)
    if options.x_scale == Continuation().x_scale:
        per = residual.size // residual.aft.rows
        per_dof = np.broadcast_to(np.asarray(x_scale, dtype=float), (residual.size,))
        per_dof = per_dof.reshape(residual.aft.rows, per).max(axis=0)
        options = dataclasses.replace(
            options, x_scale=tuple(float(v) for v in np.tile(per_dof, pd.residual.aft.rows)))
    direction = np.append(pd.direction, 0.0)
    branch, start = continue_from(fun, pd.x, lam, direction, options, step=step, sign=sign,
                                  **driver)
    return branch, pd, start


def switch_branch_point(residual: HBResidual, x: ArrayLike, lam: float, along: ArrayLike,
                        options: Continuation, *, omega: float | None = None,
                        param: float = 0.0,
                        parameter: Literal["omega", "param"] = "omega",
                        step: float | None = None, sign: int = 1, **driver: Any
                        ) -> tuple[Branch, Jump]:
    """Continue the second branch through a simple branch point of an HB branch.

    Parameters
    ----------
    residual : HBResidual
    x : array (residual.size,)
        Unknowns at the located branch point.
    lam : float
        Its parameter (``omega``, or ``p`` with ``parameter="param"`` at fixed ``omega``).
    along : array (residual.size + 1,)
        Tangent or chord ``(dx, dlam)`` of the known branch at the point (physical units).
    options : Continuation
        Of the new branch (same parameter).
    step, sign, **driver
        As for :func:`~rotorsim.solvers.continuation_switch.continue_from`.
    """
    fun = continuation_function(residual, parameter, omega=omega, param=param, terms=True)
    return continue_from(fun, x, lam, None, options, along=along, step=step, sign=sign,
                         **driver)
