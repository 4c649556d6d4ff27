"""Floquet stability of a rotor's periodic responses: method choice and the stability model.

Floquet multipliers come from :mod:`rotorsim.harmonic_balance` (Hill's method or Hsu's
discrete transition matrix, seed 002 eqs 3.37-3.38). Both work on *all* DOFs of the problem
they are given: the condensed HB unknowns cannot be used alone because the Floquet exponent
enters the dynamic stiffness ``Z_h(lam + i h omega)`` of the condensed linear DOFs (a
nonlinear eigenproblem). Their cost grows as ``(2 (2H + 1) n)^3`` (Hill) or
``N (2 n)^3`` (Hsu), so for a large rotor the *stability model* is a Craig-Bampton reduction
of the linear part: the nonlinear DOFs stay physical, the linear DOFs follow the static
constraint modes ``-K_LL^-1 K_LN`` plus the fixed-interface modes of ``(K_LL, M_LL)`` below
a cutoff frequency. The periodic solution itself (HB with exact condensation) is not
reduced; only its multipliers are computed on the reduced model, which is exact for the
retained dynamics and neglects the dynamics of fixed-interface modes above the cutoff (they
respond quasi-statically). ``modes=None`` keeps the full system.

``method="auto"``: Hill on the (full or reduced) model when its Hill pencil
``2 (2H + 1) n_s`` has at most :data:`HILL_LIMIT` rows, else Hsu with ``N`` steps per period.

Every point's multipliers are checked (Liouville's formula and jumps of the force tangent,
:mod:`rotorsim.harmonic_balance.floquet_check`); where a check fails the point falls back to
shooting on the stability model, and :meth:`StabilityModel.check` records what was done.

A solution counts as stable when ``max |mu| < 1 + tol``: an undamped mode (a shaft mode
with no damping, the free rotor of seed 002) has ``|mu| = 1`` up to round-off (Hill) or
the ``O(1/N^2)`` error of Hsu's method, and counts as (neutrally) stable.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp

from rotorsim.analyses.periodic.stability_checks import projected_excitation
from rotorsim.assembly.reduction import fixed_interface_modes
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.floquet import FloquetResult, hill
from rotorsim.harmonic_balance.floquet_check import FloquetCheck, checked_floquet
from rotorsim.harmonic_balance.liouville import TraceModel
from rotorsim.harmonic_balance.memory import check_hill_memory
from rotorsim.harmonic_balance.monodromy import hsu, variational
from rotorsim.harmonic_balance.problem import HBProblem, as_dense
from rotorsim.harmonic_balance.residual import HBResidual, make_residual
from rotorsim.options.stability import METHODS
from rotorsim.solvers.linear import factorize

HILL_LIMIT = 300
"""Largest Hill pencil (rows) that ``method="auto"`` solves densely at every point."""
FULL_LIMIT = 40
"""Up to this many active DOFs the stability model is the full system by default."""
CUTOFF_FACTOR = 1.5
"""Default cutoff of the retained fixed-interface modes: ``1.5 H omega_max``."""
DEFAULT_TOL = 1e-5
"""Default tolerance on ``|mu| - 1`` below which a solution counts as stable."""


@dataclass(frozen=True, eq=False)
class StabilityModel:
    """Multipliers of branch points ``(x, omega)`` of the HB residual ``main``.

    Attributes
    ----------
    main : HBResidual
        The residual the branch was traced with.
    residual : HBResidual
        The residual Floquet works on (``main`` itself, or the condensed residual of the
        Craig-Bampton reduced problem).
    method : str
        "hill", "hsu" or "variational".
    modes : int
        Fixed-interface modes kept (-1: full system).
    tol : float
        Stability tolerance on ``|mu| - 1``.
    """

    main: HBResidual
    residual: HBResidual
    method: str
    modes: int
    tol: float
    _cache: dict[tuple[bytes, float, float], FloquetResult] = field(default_factory=dict,
                                                             init=False, repr=False)
    _checks: dict[tuple[bytes, float, float], FloquetCheck] = field(
        default_factory=dict, init=False, repr=False)

    @property
    def size(self) -> int:
        """Number of multipliers ``2 n_s``."""
        return 2 * self.residual.problem.n

    def floquet(self, x: FloatArray, omega: float, param: float = 0.0) -> FloquetResult:
        """Floquet result at a branch point (memoised: bifurcation detection asks again)."""
        key = (np.asarray(x, dtype=float).tobytes(), float(omega), float(param))
        if key not in self._cache:
            y = self._unknowns(np.asarray(x, dtype=float), omega, param)
            methods: dict[str, Callable[..., FloquetResult]] = {
                "hill": hill, "hsu": hsu, "variational": variational}
            first = methods[self.method](self.residual, y, omega, param)
            self._cache[key], self._checks[key] = checked_floquet(
                self.residual, y, omega, param, first, trace=self._trace)
        return self._cache[key]

    def check(self, x: FloatArray, omega: float, param: float = 0.0) -> FloquetCheck:
        """Liouville and tangent-jump checks of a branch point, and the method kept."""
        self.floquet(x, omega, param)
        return self._checks[(np.asarray(x, dtype=float).tobytes(), float(omega),
                             float(param))]

    @cached_property
    def _trace(self) -> TraceModel:
        return TraceModel(self.residual.problem)

    def multipliers(self, x: FloatArray, omega: float) -> FloatArray:
        """``multipliers(x, lam)`` callback of bifurcation detection, with the neutral
        multipliers (``| |mu| - 1 | <= tol``) moved to ``|mu| = 1 - tol``: undamped modes
        then never trigger period-doubling or Neimark-Sacker events, and a genuine crossing
        is located where ``|mu| = 1 + tol``."""
        mu = self.floquet(x, omega).multipliers
        size = np.abs(mu)
        neutral = np.abs(size - 1.0) <= self.tol
        return np.where(neutral, mu * ((1.0 - self.tol) / np.where(size > 0, size, 1.0)), mu)

    def _unknowns(self, x: FloatArray, omega: float, param: float) -> FloatArray:
        if self.residual is self.main:
            return x
        pb = self.main.problem
        if self.main.size == self.main.aft.rows * pb.k:        # condensed: x is Y_nl
            return x
        return self.main.expand(x, omega, param)[:, pb.nl_dofs].reshape(-1)


def stability_model(main: HBResidual, method: str, *, modes: int | str | None = "auto",
                    omega_max: float, tol: float = DEFAULT_TOL) -> StabilityModel:
    """Choose the stability model and method (module docstring).

    Parameters
    ----------
    main : HBResidual
    method : {"auto", "hill", "hsu", "variational"}
    modes : int, None or "auto"
        Fixed-interface modes kept; None: full system; "auto": full system up to
        :data:`FULL_LIMIT` active DOFs, else the modes below ``1.5 H omega_max``.
    omega_max : float
        Largest fundamental frequency of the branch [rad/s] (cutoff of "auto").
    tol : float

    Raises
    ------
    ModelError
        For bad options, or Hill's method on a pencil too large for the memory
        (:func:`~rotorsim.harmonic_balance.memory.check_hill_memory`).
    """
    check_options(method, modes, tol)
    pb = main.problem
    n_linear = pb.linear_dofs.size
    if modes == "auto":
        full, count, cutoff = pb.n <= FULL_LIMIT, 0, CUTOFF_FACTOR * main.harmonics * omega_max
    elif modes is None:
        full, count, cutoff = True, 0, None
    else:
        full, count, cutoff = int(modes) >= n_linear, int(modes), None
    if full or n_linear == 0:
        residual, kept = main, -1
    else:
        reduced, kept = craig_bampton(pb, count, cutoff)
        residual = make_residual(reduced, main.harmonics, samples=main.samples)
    rows = 2 * residual.aft.rows * residual.problem.n
    if method == "auto":
        method = "hill" if rows <= HILL_LIMIT else "hsu"
    if method == "hill":
        check_hill_memory(rows, where="periodic.stability")
    return StabilityModel(main, residual, method, kept, float(tol))


def check_options(method: str | None, modes: object, tol: float) -> None:
    """Validate the stability options up front (TypeError / ModelError naming them)."""
    if method is not None and method not in METHODS:
        raise TypeError(f"unknown stability method {method!r}; valid: {', '.join(METHODS)}"
                        " or None")
    ok_int = isinstance(modes, int | np.integer) and not isinstance(modes, bool) \
        and int(modes) >= 0
    if not (modes is None or modes == "auto" or ok_int):
        raise ModelError(f"must be None, 'auto' or an integer >= 0, got {modes!r}",
                         "periodic.stability_modes")
    if not (isinstance(tol, int | float) and math.isfinite(tol) and tol >= 0):
        raise ModelError(f"must be finite and >= 0, got {tol!r}", "periodic.stability_tol")


def craig_bampton(problem: HBProblem, modes: int, cutoff: float | None
                  ) -> tuple[HBProblem, int]:
    """Craig-Bampton reduction keeping the nonlinear DOFs physical (first ``k`` unknowns).

    ``modes`` fixed-interface modes, or (``cutoff`` given) those with natural frequency up
    to ``cutoff`` [rad/s]. Returns the reduced problem (with the excitation ``T^T f``, for
    shooting; the variational equation does not use it) and the number of modes kept.
    """
    N, L = problem.nl_dofs, problem.linear_dofs
    k = N.size
    M, K = sp.csr_matrix(problem.mass), sp.csr_matrix(problem.stiffness)
    K_LL = K[L][:, L]
    try:
        psi = -np.asarray(factorize(K_LL, where="Craig-Bampton constraint modes").solve(
            K[L][:, N].toarray()))
    except ConvergenceError as exc:
        raise ModelError("the linear part is singular with the nonlinear DOFs clamped; use "
                         "stability_modes=None", "periodic.stability_modes") from exc
    w2, phi = _fixed_interface_modes(K_LL, M[L][:, L], modes, cutoff)
    T = np.zeros((problem.n, k + w2.size))
    T[N, np.arange(k)] = 1.0
    T[np.ix_(L, np.arange(k))] = psi
    T[np.ix_(L, k + np.arange(w2.size))] = phi

    def project(A: Any) -> FloatArray | None:
        return None if A is None else T.T @ (sp.csr_matrix(A) @ T)

    reduced = HBProblem(project(M), project(K), project(problem.damping),
                        project(problem.gyroscopic), nl_dofs=np.arange(k),
                        force=problem.force, **projected_excitation(problem, T),
                        spin=problem.spin,
                        spin_ratio=problem.spin_ratio,
                        force_uses_omega=problem.force_uses_omega,
                        param_scale=problem.param_scale)
    return reduced, int(w2.size)


def _fixed_interface_modes(K_LL: Any, M_LL: Any, modes: int,
                           cutoff: float | None) -> tuple[FloatArray, FloatArray]:
    """Eigenvalues ``w^2`` and mass-normalised modes of ``K_LL phi = w^2 M_LL phi``."""
    n = K_LL.shape[0]
    if cutoff is not None:
        w2, phi = sl.eigh(as_dense(K_LL), as_dense(M_LL),
                          subset_by_value=(-np.inf, cutoff**2))
    else:  # a pair of equal frequencies is kept whole (the basis must not depend on LAPACK)
        w, phi = fixed_interface_modes(K_LL, M_LL, min(modes, n))
        w2 = w**2
    return np.asarray(w2), np.asarray(phi)
