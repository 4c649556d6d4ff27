"""Independent beam-theory references for the validation tests.

Nothing here uses rotorsim: closed-form frequency equations and a shooting solution of the
Euler-Bernoulli / Timoshenko beam differential equations with variable section.

References
----------
- Han, Benaroya, Wei, "Dynamics of transversely vibrating beams using four engineering
  theories", J. Sound Vib. 225 (1999) 935-988: simply supported Timoshenko beam, the
  quadratic frequency equation in w^2 of :func:`simply_supported_frequency`.
- Blevins, *Formulas for Natural Frequency and Mode Shape* (1979), table 8-1: the roots
  ``beta L`` of ``cos x cosh x = 1`` (free-free) and ``= -1`` (clamped-free).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

FREE_FREE_BETA_L_BLEVINS = (4.73004074, 7.85320462, 10.9956078, 14.1371655)
"""Free-free ``beta L`` printed by Blevins (1979), table 8-1 (8-9 digits)."""
CANTILEVER_BETA_L_BLEVINS = (1.87510407, 4.69409113, 7.85475744, 10.9955407)
"""Clamped-free ``beta L`` printed by Blevins (1979), table 8-1."""


def cowper_solid(nu: float) -> float:
    """Cowper's (1966) shear coefficient of a solid circle, ``6 (1 + nu) / (7 + 6 nu)``."""
    return 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)


def cowper_hollow(nu: float, ratio: np.ndarray | float) -> np.ndarray:
    """Cowper's (1966) shear coefficient of a hollow circle, ``ratio = inner / outer``."""
    m2 = np.asarray(ratio, dtype=float) ** 2
    a = (1.0 + m2) ** 2
    return 6.0 * (1.0 + nu) * a / ((7.0 + 6.0 * nu) * a + (20.0 + 12.0 * nu) * m2)


def simply_supported_frequency(
    n: int, L: float, E: float, G: float, rho: float, A: float, I: float, kappa: float,
    shear: bool = True, rotary: bool = True,
) -> float:
    """Lowest-branch natural frequency [rad/s] of mode ``n`` of a simply supported beam.

    With ``k = n pi / L`` and modes ``w = sin(k z)``, ``psi = cos(k z)`` the Timoshenko
    equations give ``a w^4 - b w^2 + c = 0`` with ``a = rho A rho I / (kappa G A)``,
    ``b = rho A + rho I k^2 + rho A E I k^2 / (kappa G A)``, ``c = E I k^4``; dropping
    shear (``kappa G A -> inf``) and/or rotary inertia (``rho I -> 0``) gives the
    Rayleigh, shear and Euler-Bernoulli limits.
    """
    k = n * np.pi / L
    rho_i = rho * I if rotary else 0.0
    flex = 1.0 / (kappa * G * A) if shear else 0.0
    a = rho * A * rho_i * flex
    b = rho * A + rho_i * k**2 + rho * A * E * I * k**2 * flex
    c = E * I * k**4
    if a == 0.0:
        return float(np.sqrt(c / b))
    return float(np.sqrt((b - np.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)))


def _char_roots(fn: Callable[[float], float], count: int, first: int) -> np.ndarray:
    """Roots of ``fn``, one in each ``[j pi, (j + 1) pi]``, ``j = first, first + 1, ...``."""
    return np.array([brentq(fn, j * np.pi, (j + 1) * np.pi, xtol=1e-14)
                     for j in range(first, first + count)])


def free_free_beta_l(count: int) -> np.ndarray:
    """Roots ``x = beta L > 0`` of ``cos x cosh x = 1`` (Euler-Bernoulli free-free beam)."""
    return _char_roots(lambda x: np.cos(x) - 1.0 / np.cosh(x), count, first=1)


def cantilever_beta_l(count: int) -> np.ndarray:
    """Roots of ``cos x cosh x = -1`` (Euler-Bernoulli clamped-free beam)."""
    return _char_roots(lambda x: np.cos(x) + 1.0 / np.cosh(x), count, first=0)


@dataclass(frozen=True)
class VariableBeam:
    """A straight beam of circular (hollow) section whose diameters vary linearly.

    ``outer(s)``/``inner(s)`` at ``s = z / L`` interpolate ``d0 -> d1`` and
    ``di0 -> di1``. ``kappa(s)`` is Cowper's coefficient of the local section.
    """

    L: float
    d0: float
    d1: float
    E: float
    G: float
    rho: float
    di0: float = 0.0
    di1: float = 0.0
    shear: bool = True
    rotary: bool = True

    def section(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        do = self.d0 + (self.d1 - self.d0) * s
        di = self.di0 + (self.di1 - self.di0) * s
        area = np.pi / 4.0 * (do**2 - di**2)
        inertia = np.pi / 64.0 * (do**4 - di**4)
        nu = self.E / (2.0 * self.G) - 1.0
        return area, inertia, cowper_hollow(nu, di / do)


# components that an end condition holds at zero, in y = [w, psi, Q, M]
_HELD = {"clamped": (0, 1), "free": (2, 3), "pinned": (0, 3)}


def _rhs(beam: VariableBeam, omega: float):
    """Right-hand side of the scaled Timoshenko equations (s = z / L).

    ``w' = psi + Q / (kappa G A)``, ``psi' = M / (E I)``, ``Q' = -rho A w^2 w``,
    ``M' = -Q - rho I w^2 psi``; scaled with ``w/L``, ``Q L^2/(E I0)``, ``M L/(E I0)``.
    """
    L, E = beam.L, beam.E
    _, i0, _ = beam.section(np.array(0.0))

    def f(s, y):
        area, inertia, kappa = beam.section(s)
        shear = E * i0 / (kappa * beam.G * area * L**2) if beam.shear else 0.0
        rot = beam.rho * inertia * omega**2 * L**2 / (E * i0) if beam.rotary else 0.0
        trans = beam.rho * area * omega**2 * L**4 / (E * i0)
        w, psi, q, m = y
        return np.array([psi + shear * q, m * i0 / inertia, -trans * w, -q - rot * psi])

    return f


def _end_determinant(beam: VariableBeam, omega: float, ends: tuple[str, str]) -> float:
    held0, held1 = _HELD[ends[0]], _HELD[ends[1]]
    start = [i for i in range(4) if i not in held0]
    f = _rhs(beam, omega)
    cols = []
    for j in start:
        y0 = np.zeros(4)
        y0[j] = 1.0
        sol = solve_ivp(f, (0.0, 1.0), y0, method="DOP853", rtol=1e-12, atol=1e-14)
        cols.append(sol.y[list(held1), -1])
    return float(np.linalg.det(np.array(cols).T))


def shooting_frequencies(
    beam: VariableBeam, ends: tuple[str, str], count: int, omega_max: float,
    n_scan: int = 120,
) -> np.ndarray:
    """The lowest ``count`` natural frequencies [rad/s] of ``beam`` by shooting.

    Two independent solutions leave end 0 satisfying its conditions; the 2x2 determinant
    of the conditions at end 1 vanishes at a natural frequency. Sign changes on a scan of
    ``(0, omega_max]`` are refined by Brent's method.
    """
    grid = np.linspace(omega_max / n_scan, omega_max, n_scan)
    values = np.array([_end_determinant(beam, w, ends) for w in grid])
    found = []
    for a, b, fa, fb in zip(grid[:-1], grid[1:], values[:-1], values[1:], strict=True):
        if np.sign(fa) != np.sign(fb):
            found.append(brentq(lambda w: _end_determinant(beam, w, ends), a, b,
                                xtol=1e-10 * b, rtol=1e-13))
        if len(found) == count:
            break
    if len(found) < count:
        raise RuntimeError(f"found {len(found)} of {count} roots below {omega_max} rad/s")
    return np.array(found)
