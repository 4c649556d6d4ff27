"""Periodic orbits of the full rotor model by shooting, with the monodromy of the real
trajectory.

Harmonic balance gives an orbit as a truncated Fourier series and its Floquet multipliers
from tangents along that series (Hill, Hsu, or a reduced stability model). Here the orbit
is found again on the full finite-element model by time integration: Newton on the
period map, ``P(z) - z = 0`` for the state ``z = (q, v)`` on the free DOFs at phase 0,
started from the harmonic-balance state, with the exact Jacobian ``Phi - I`` of the
discrete average-acceleration map
(:func:`~rotorsim.time_integration.sensitivity_flow.average_acceleration_flow`). The
eigenvalues of ``Phi`` at the converged orbit are its Floquet multipliers: no margin on
growth over a few periods, so that the 0.1 % damped modes of a rotor, whose multipliers lie
within a few 1e-3 of the unit circle, are resolved (seed 002 section 3.5.3; Seydel 2010,
*Practical Bifurcation and Stability Analysis*, sections 7.1-7.3).

The multipliers carry the time discretisation's error, second order in the step:
:func:`shoot_full_model` repeats the last Newton step with twice the steps and reports the
change of each multiplier (``accuracy``), an upper estimate of the error of the finer one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.transient.equation import rotor_problem
from rotorsim.analyses.transient.speed_profile import ConstantSpeed
from rotorsim.assembly.system import RotorSystem
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.options import Excitation
from rotorsim.solvers.threads import one_blas_thread
from rotorsim.time_integration.local_tangent import LocalMatrix
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.sensitivity_flow import DiscreteFlow, average_acceleration_flow

FloatArray = NDArray[np.float64]
WHERE = "shoot_full_model"


@dataclass(frozen=True, eq=False)
class FullOrbit:
    """A periodic orbit of the full model found by shooting.

    Attributes
    ----------
    q, v : arrays (n,)
        State at phase 0 on the problem's unknowns [m, rad, m/s, rad/s].
    multipliers : complex array (2 n,)
        Floquet multipliers of the orbit with ``2 steps`` per period, by decreasing modulus
        (``n`` unknowns of the problem).
    vectors : complex array (2 n, 2 n)
        Their eigenvectors (columns), ``(dq, dv)``.
    coarse : complex array (2 n,)
        The multipliers with ``steps`` per period, each the one nearest to the fine one.
    residual : float
        ``|P(z) - z|`` of the last Newton iterate, relative to the orbit's scale.
    newton : int
        Newton iterations (one period each, plus the fine one).
    moved : float
        Largest change of a displacement from the start state, relative to the orbit's
        scale ``scale_q``.
    """

    q: FloatArray
    v: FloatArray
    multipliers: NDArray[np.complex128]
    vectors: NDArray[np.complex128]
    coarse: NDArray[np.complex128]
    residual: float
    newton: int
    moved: float

    @property
    def accuracy(self) -> FloatArray:
        """``|mu_fine - mu_coarse|`` of each multiplier: about three times the error of
        the fine one for a second-order scheme [-]."""
        return np.abs(self.multipliers - self.coarse)


def speed_problem(system: RotorSystem, speed: float, excitation: Excitation,
                  phi0: float = 0.0, held: NDArray[np.int64] | None = None
                  ) -> tuple[SecondOrderProblem, NDArray[np.int64]]:
    """The equation of motion at a constant ``speed`` [rad/s] with the shaft at ``phi0``
    [rad] at ``t = 0`` (the transient's own, :func:`rotorsim.transient`), without the
    free DOFs ``held`` (indices among the free DOFs: free rigid motions that no element
    restrains, held at zero as harmonic balance holds them; left in, their multipliers
    are exactly 1 in a Jordan block, ``Phi - I`` is singular and rounding splits the pair
    by ``sqrt(eps)``).

    Returns the problem on the kept free DOFs and their indices among the free DOFs."""
    profile = ConstantSpeed(float(speed), phi0=float(phi0)).bind(0.0, 1.0)
    problem, _ = rotor_problem(system, profile, 0.0, excitation)
    keep = np.setdiff1d(np.arange(problem.n), [] if held is None else held).astype(np.int64)
    if keep.size == problem.n:
        return problem, keep
    return _restricted(problem, keep), keep


def _restricted(problem: SecondOrderProblem, keep: NDArray[np.int64]) -> SecondOrderProblem:
    """``problem`` on the unknowns ``keep``, the others held at zero (the restoring force
    must not act on them)."""
    n = problem.n
    where = np.full(n, -1, dtype=np.int64)
    where[keep] = np.arange(keep.size)
    cut = np.ix_(keep, keep)

    def part(A: object) -> object:
        return None if A is None else (A.tocsr() if sp.issparse(A) else np.asarray(A))[cut]  # type: ignore[attr-defined]

    def restoring(q: FloatArray, v: FloatArray, t: float) -> Any:
        assert problem.restoring is not None
        qf, vf = np.zeros(n), np.zeros(n)
        qf[keep], vf[keep] = q, v
        out = problem.restoring(qf, vf, t)
        if out is None:
            return None
        r, kt, ct = out
        if kt is None or ct is None or not np.array_equal(kt.dofs, ct.dofs):
            raise ModelError("the restoring force must give both tangents on the same DOFs",
                             WHERE)
        dofs = where[kt.dofs]
        inside = dofs >= 0
        for block in (kt.block, ct.block):
            if not np.all(block[~inside] == 0.0) or not np.all(block[:, ~inside] == 0.0):
                raise ModelError("a nonlinear element acts on a held DOF", WHERE)
        on = np.ix_(inside, inside)
        return (np.asarray(r)[keep],
                LocalMatrix.trusted(keep.size, dofs[inside], kt.block[on]),
                LocalMatrix.trusted(keep.size, dofs[inside], ct.block[on]))

    def load(t: float) -> FloatArray:
        return problem.external(t)[keep]

    return SecondOrderProblem(
        mass=part(problem.mass), stiffness=part(problem.stiffness),
        damping=part(problem.damping),
        restoring=None if problem.restoring is None else restoring, load=load,
        gyroscopic=part(problem.gyroscopic), speed=problem.speed)


def _weighted(dz: FloatArray, n: int, scale_q: float, scale_v: float) -> float:
    return max(float(np.max(np.abs(dz[:n]))) / scale_q, float(np.max(np.abs(dz[n:]))) / scale_v)


@one_blas_thread()   # small dense and banded work per time step: no BLAS threads
def shoot_full_model(problem: SecondOrderProblem, q0: FloatArray, v0: FloatArray,
                     period: float, steps: int = 200, *, scale_q: float, scale_v: float,
                     tolerance: float = 1e-9, max_newton: int = 12, max_move: float = 0.05
                     ) -> FullOrbit:
    """Newton on the period map of ``problem`` from ``(q0, v0)`` (module docstring).

    Parameters
    ----------
    problem : SecondOrderProblem
        The rotor's equation of motion (:func:`speed_problem`), periodic with ``period``.
    q0, v0 : arrays (n_free,)
        Start state, e.g. the harmonic-balance orbit at phase 0 [m, rad, m/s, rad/s].
    period : float
        ``T`` [s].
    steps : int
        Steps per period of the Newton iterations; the multipliers are computed again
        with ``2 steps``.
    scale_q, scale_v : float
        Sizes of the orbit (e.g. its largest peak-to-peak displacement and velocity)
        [m, m/s]: the residual is measured relative to them.
    tolerance : float
        Newton stops at ``max |P(z) - z| / scale < tolerance``.
    max_newton : int
        Most Newton iterations.
    max_move : float
        Largest Newton step relative to the scales (a trust region: next to a fold,
        where ``Phi - I`` is nearly singular, a full step could land on another sheet).

    Returns
    -------
    FullOrbit

    Raises
    ------
    ConvergenceError
        Newton does not converge (the last residual is named), or a step fails.
    """
    n = problem.n
    if not (scale_q > 0 and scale_v > 0 and math.isfinite(scale_q * scale_v)):
        raise ModelError(f"scales must be finite and > 0, got {scale_q!r}, {scale_v!r}",
                         WHERE)
    z = np.concatenate([np.asarray(q0, dtype=float), np.asarray(v0, dtype=float)])
    if z.shape != (2 * n,):
        raise ModelError(f"expected ({n},) start displacements and velocities", WHERE)
    start = z.copy()
    residual = math.inf
    history: list[float] = []
    flow: DiscreteFlow | None = None
    newton = 0
    for newton in range(1, max_newton + 1):
        flow = average_acceleration_flow(problem, z[:n], z[n:], 0.0, period, steps)
        F = np.concatenate([flow.q, flow.v]) - z
        residual = _weighted(F, n, scale_q, scale_v)
        history.append(residual)
        if residual < tolerance:
            break
        if len(history) > 3 and residual > 0.5 * history[-4]:
            raise ConvergenceError(
                f"shooting makes no progress (residual {history[-4]:.3g} -> "
                f"{residual:.3g} over 3 periods): no orbit of the full model next to the "
                "start state", WHERE, iteration=newton, residual=residual)
        assert flow.monodromy is not None
        dz = np.linalg.solve(flow.monodromy - np.eye(2 * n), -F)
        if not np.all(np.isfinite(dz)):
            raise ConvergenceError("the shooting correction is not finite (a multiplier at "
                                   "1: a fold)", WHERE, iteration=newton, residual=residual)
        z += dz * min(1.0, max_move / _weighted(dz, n, scale_q, scale_v))   # stay close
    else:
        raise ConvergenceError(f"shooting did not converge in {max_newton} periods",
                               WHERE, iteration=newton, residual=residual)
    assert flow is not None and flow.monodromy is not None
    coarse = np.linalg.eigvals(flow.monodromy)
    fine = average_acceleration_flow(problem, z[:n], z[n:], 0.0, period, 2 * steps)
    assert fine.monodromy is not None
    mu, vectors = np.linalg.eig(fine.monodromy)
    order = np.argsort(-np.abs(mu), kind="stable")
    mu, vectors = mu[order], vectors[:, order]
    nearest = coarse[np.argmin(np.abs(coarse[None, :] - mu[:, None]), axis=1)]
    moved = float(np.max(np.abs(z[:n] - start[:n]))) / scale_q
    return FullOrbit(z[:n], z[n:], mu.astype(complex), vectors.astype(complex),
                     nearest.astype(complex), residual, newton + 1, moved)
