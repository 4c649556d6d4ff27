"""Quasi-periodic harmonic balance: two incommensurate base frequencies on a 2-torus
(issue 17). Rotor-agnostic, like :mod:`rotorsim.harmonic_balance` (DESIGN section 1)."""

from rotorsim.harmonic_balance.quasi.aft import TorusAFT
from rotorsim.harmonic_balance.quasi.harmonics import TorusHarmonics
from rotorsim.harmonic_balance.quasi.residual import QuasiProblem, TorusForce
from rotorsim.harmonic_balance.quasi.solve import QuasiSolution, solve_quasi

__all__ = ["QuasiProblem", "QuasiSolution", "TorusAFT", "TorusForce", "TorusHarmonics",
           "solve_quasi"]
