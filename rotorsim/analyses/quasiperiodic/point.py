"""``rs.quasi_periodic_point``: the quasi-periodic unbalance response of a rotor on rolling
bearings whose cages turn, at one speed (issue 17, first part).

The response to unbalance (shaft frequency ``W``) and varying compliance (``Z kappa W``)
is computed on the 2-torus with both rolling-element motion and unbalance, where
``rs.periodic`` must freeze the rolling elements (``result.approximation``). Newton starts
from the static equilibrium; when it fails, the unbalance is brought in by a homotopy on
its amplitude (steps halved on failure).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.quasiperiodic.problem import (
    WHERE,
    RotorQuasiProblem,
    build_quasi_problem,
)
from rotorsim.analyses.quasiperiodic.stability import TorusStability, torus_stability
from rotorsim.analyses.system_input import nonlinear_system
from rotorsim.assembly.system import RotorSystem
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.quasi import QuasiSolution, TorusAFT, TorusHarmonics
from rotorsim.harmonic_balance.quasi import solve_quasi as solve_torus
from rotorsim.harmonic_balance.quasi.lyapunov import LyapunovEstimate, largest_lyapunov_exponent
from rotorsim.options import Excitation
from rotorsim.solvers.stats import Stats
from rotorsim.solvers.threads import one_blas_thread

FloatArray = NDArray[np.float64]
MIN_HOMOTOPY_STEP = 1.0 / 64
"""Smallest step of the unbalance homotopy before the solve is given up."""


@dataclass(frozen=True, eq=False)
class QuasiPeriodicPoint:
    """A rotor's quasi-periodic response at one speed.

    Attributes
    ----------
    speed : float
        ``W`` [rad/s] (``w1``).
    vc_frequency : float
        ``w2 = Z kappa W`` [rad/s].
    solution : QuasiSolution
        Coefficients on the active DOFs.
    rotor_problem : RotorQuasiProblem
    system : RotorSystem
    """

    speed: float
    vc_frequency: float
    solution: QuasiSolution
    rotor_problem: RotorQuasiProblem
    system: RotorSystem

    def _column(self, node: int, dof: str) -> int | None:
        free = int(self.system.dofs_of(node, (dof,))[0])
        hit = np.flatnonzero(self.rotor_problem.active == free)
        return int(hit[0]) if hit.size else None

    def amplitude(self, node: int, dof: str, k1: int, k2: int) -> float:
        """Amplitude [m or rad] of the tone ``k1 W + k2 w2`` of ``(node, dof)`` (the mean's
        magnitude for ``(0, 0)``; 0 for a held DOF)."""
        col = self._column(node, dof)
        return 0.0 if col is None else self.solution.amplitude(col, k1, k2)

    def response(self, t: FloatArray, node: int, dof: str) -> FloatArray:
        """The response of ``(node, dof)`` at times ``t`` [s] from shaft and cage angle 0."""
        col = self._column(node, dof)
        t = np.asarray(t, dtype=float)
        return np.zeros(t.shape) if col is None else self.solution.evaluate(t, [col])[:, 0]

    def stability(self, periods: int = 40, steps_per_period: int = 128) -> LyapunovEstimate:
        """The largest Lyapunov exponent of the torus (negative: stable), from its
        variational equation over ``periods`` shaft revolutions
        (:func:`~rotorsim.harmonic_balance.quasi.lyapunov.largest_lyapunov_exponent`)."""
        return largest_lyapunov_exponent(self.rotor_problem.problem, self.solution,
                                         periods=periods, steps_per_period=steps_per_period)

    def exponents(self, box: tuple[int, int] | None = None, cutoff: float | None = None,
                  first: TorusStability | None = None) -> TorusStability:
        """Characteristic exponents of the torus by the quasi-periodic Hill method on a
        Craig-Bampton model (:func:`~rotorsim.analyses.quasiperiodic.stability.
        torus_stability`): stable when ``.exponents.largest < 0`` [1/s], resolved whatever
        the damping, unlike :meth:`stability`. ``box`` fixes the stability tones (default:
        grown until converged), ``cutoff`` [rad/s] the fixed-interface modes; ``first``
        this torus's result for the box (1, 1) alone, reused."""
        sol = self.solution
        return torus_stability(self.rotor_problem.problem, sol.X, sol.aft, sol.w1, sol.w2,
                               box=box, cutoff=cutoff, first=first)

    def state(self, t: float = 0.0) -> tuple[FloatArray, FloatArray]:
        """Displacements and velocities on ALL DOFs (``6 n_nodes``) at time ``t`` [s]: the
        ``initial`` of a transient started on the torus."""
        sol = self.solution
        V = sol.aft.derivative_matrix(sol.w1, sol.w2) @ sol.X
        k = sol.aft.harmonics.k
        phase = (k[:, 0] * sol.w1 + k[:, 1] * sol.w2) * t
        q = sol.X[0] + np.cos(phase) @ sol.X[1::2] + np.sin(phase) @ sol.X[2::2]
        v = V[0] + np.cos(phase) @ V[1::2] + np.sin(phase) @ V[2::2]
        n_full = 6 * self.system.dof_map.n_nodes
        free = self.system.dof_map.free[self.rotor_problem.active]
        out_q, out_v = np.zeros(n_full), np.zeros(n_full)
        out_q[free], out_v[free] = q, v
        return out_q, out_v


@one_blas_thread()   # small dense work: the Newton iterations on the condensed unknowns
def quasi_periodic_point(model: Any, speed: float, *,
                         unbalance: Sequence[tuple[int, float, float]] = (),
                         harmonics: int | tuple[int, int] = 8, truncation: str = "diamond",
                         samples: tuple[int, int] | None = None,
                         excitation: Excitation | None = None, nonlinear: Sequence[Any] = (),
                         tol: float = 1e-9) -> QuasiPeriodicPoint:
    """The quasi-periodic response of a rotor to unbalance and rolling-element varying
    compliance at ``speed`` [rad/s].

    Parameters
    ----------
    model : Rotor or RotorSystem
        With rolling bearings whose cages turn (all of one VC order ``Z kappa``).
    unbalance : list of (node, me, angle)
        [kg m, rad], at the shaft angle 0.
    harmonics : int or (int, int)
        Diamond order ``H`` (tones ``|k1| + |k2| <= H``) or box ``(H1, H2)`` with
        ``truncation="box"`` (``k1`` counts the shaft frequency, ``k2`` the VC frequency).
    excitation : Excitation, optional
        Gravity and its direction, constant point loads (default: standard gravity along
        ``-y``); its unbalance is used when ``unbalance`` is not given.
    tol : float
        Newton tolerance relative to the largest condensed load.

    Raises
    ------
    ModelError
        Bad input, no turning cage, or bearings of different VC orders.
    ConvergenceError
        Newton fails even with the unbalance brought in by steps of 1/64.
    """
    system = system_of(model, nonlinear)
    torus = torus_of(harmonics, truncation)
    ex = excitation if excitation is not None else Excitation()
    if not unbalance and ex.unbalance:
        unbalance = tuple(ex.unbalance)
    return solve_at(system, float(speed), torus, TorusAFT(torus, samples), ex, unbalance, tol)


def solve_at(system: RotorSystem, speed: float, torus: TorusHarmonics, aft: TorusAFT,
             ex: Excitation, unbalance: Sequence[tuple[int, float, float]], tol: float,
             start: FloatArray | None = None) -> QuasiPeriodicPoint:
    """The point at ``speed`` [rad/s], Newton from ``start`` (coefficients of the nonlinear
    DOFs, e.g. the previous point of a branch) or, without it, from the static state with
    the unbalance homotopy."""
    rotor_problem = build_quasi_problem(system, float(speed), torus, unbalance=unbalance,
                                        gravity=ex.gravity, direction=ex.direction,
                                        loads=tuple(ex.loads), stats=Stats())
    w1, w2 = float(speed), rotor_problem.vc_order * float(speed)
    if start is None:
        solution = _homotopy(rotor_problem, aft, w1, w2, tol)
    else:
        solution = solve_torus(rotor_problem.problem, aft, w1, w2, start=start, tol=tol)
    return QuasiPeriodicPoint(float(speed), w2, solution, rotor_problem, system)


def _start(rp: RotorQuasiProblem, rows: int) -> FloatArray:
    nl = np.asarray(rp.problem.nl_dofs)
    start = np.zeros((rows, nl.size))
    start[0] = rp.static[rp.active][nl]
    return start


def _homotopy(rp: RotorQuasiProblem, aft: TorusAFT, w1: float, w2: float, tol: float
              ) -> QuasiSolution:
    """Newton from the static state; on failure, the periodic forcing scaled from 0 to 1."""
    P = np.asarray(rp.problem.excitation)
    start = _start(rp, aft.harmonics.rows)
    try:
        return solve_torus(rp.problem, aft, w1, w2, start=start, tol=tol)
    except ConvergenceError:
        pass
    scale, step, last = 0.0, 0.25, None
    while scale < 1.0:
        trial = min(1.0, scale + step)
        scaled = P.copy()
        scaled[1:] *= trial
        try:
            last = solve_torus(replace(rp.problem, excitation=scaled), aft, w1, w2,
                               start=start, tol=tol)
        except ConvergenceError as exc:
            step /= 2
            if step < MIN_HOMOTOPY_STEP:
                raise ConvergenceError(f"no quasi-periodic solution: the unbalance homotopy "
                                       f"stalled at {scale:.3g} of the forcing ({exc})",
                                       WHERE) from exc
            continue
        scale, step = trial, min(2 * step, 0.5)
        start = last.X[:, np.asarray(rp.problem.nl_dofs)]
    assert last is not None
    return last


def system_of(model: Any, nonlinear: Sequence[Any]) -> RotorSystem:
    """:func:`~rotorsim.analyses.system_input.nonlinear_system` with this analysis's name."""
    return nonlinear_system(model, nonlinear, WHERE)


def torus_of(harmonics: int | tuple[int, int], truncation: str) -> TorusHarmonics:
    if truncation == "diamond" and not isinstance(harmonics, tuple):
        return TorusHarmonics.diamond(harmonics)
    if truncation == "box" and isinstance(harmonics, tuple) and len(harmonics) == 2:
        return TorusHarmonics.box(*harmonics)
    raise ModelError(f"truncation {truncation!r} with harmonics {harmonics!r}: use "
                     "'diamond' with an order H or 'box' with (H1, H2)", f"{WHERE}.harmonics")
