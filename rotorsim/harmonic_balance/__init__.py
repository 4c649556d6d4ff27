"""Rotor-agnostic harmonic balance (HB-AFT) with condensation and Floquet stability.

Workflow (seed 002 section 3.5.2)::

    problem = HBProblem(M, K, C, G, nl_dofs=..., force=..., excitation=..., spin_ratio=1.0)
    res = make_residual(problem, harmonics=10)          # condensed onto the nonlinear DOFs
    sol = solve_point(res, omega, x0)                   # damped Newton, PeriodicSolution
    fl = hill(res, sol.x, omega)                        # or hsu(...), variational(...)

The unknowns are Fourier coefficients in the harmonic-major layout
``[Q_0, Q_1c, Q_1s, ..., Q_Hc, Q_Hs]`` described in :mod:`.fourier`. Continuation code
uses ``res.evaluate(x, omega, param, d_omega=True)`` or :func:`continuation_function`.
This package never imports the rotor model (DESIGN section 1).
"""

from rotorsim.harmonic_balance.condensation import CondensedResidual
from rotorsim.harmonic_balance.floquet import FloquetResult, classify, hill
from rotorsim.harmonic_balance.fourier import AFT, default_samples
from rotorsim.harmonic_balance.monodromy import hsu, variational
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.harmonic_balance.residual import (
    HarmonicBalanceResidual,
    HBEvaluation,
    HBResidual,
    continuation_function,
    make_residual,
)
from rotorsim.harmonic_balance.solve import PeriodicSolution, sample_convergence, solve_point

__all__ = [
    "AFT",
    "CondensedResidual",
    "FloquetResult",
    "HBEvaluation",
    "HBProblem",
    "HBResidual",
    "HarmonicBalanceResidual",
    "PeriodicSolution",
    "classify",
    "continuation_function",
    "default_samples",
    "hill",
    "hsu",
    "make_residual",
    "sample_convergence",
    "solve_point",
    "variational",
]
