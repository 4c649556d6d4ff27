"""The automatic transient path: the error-controlled Radau IIA stepper set up for a rotor.

``rs.transient(rotor, t_end, rtol=1e-5)`` (or ``method="auto"``) asks for the response to
``rtol`` of the motion. The stepper (:class:`~rotorsim.time_integration.radau.Radau`, order
5) then needs to know what "the motion" is:

* the unknowns are grouped by kind, translations [m] and rotations [rad], each group with
  one scale (:mod:`~rotorsim.time_integration.motion_scale`);
* the scale of a group is the largest motion ``|q - q(t0)|`` reached so far, but never less
  than an a-priori estimate: the amplitude of the linear response to the unbalance at the
  starting speed (or the final one when the run starts at rest), linearised about the start
  state. Without the estimate the scale would start at zero and the first steps would
  resolve the onset of the motion to ``rtol`` of itself.

The estimate is only a floor of the scale: it does not limit the motion, and a response
that grows larger (a resonance in a run-up) raises the scale as it goes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp

from rotorsim.analyses.transient.loads import TransientLoads
from rotorsim.analyses.transient.speed_profile import BoundSpeed
from rotorsim.assembly.reduction import ReducedBasis
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import factorize
from rotorsim.time_integration.exponential import Exponential
from rotorsim.time_integration.local_tangent import LocalMatrix
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.radau import Radau

DEFAULT_RTOL = 1e-4
"""Accuracy of ``method="auto"`` when no ``rtol`` is given."""


def dof_weights(system: RotorSystem, n: int, basis: ReducedBasis | None = None
                ) -> tuple[float, ...] | None:
    """Weight of every unknown in the error measure: 1 for translations, the longest shaft
    element [m] for rotations. For a reduced problem (``q = T x`` on ``basis``) the
    boundary coordinates keep the weights of their DOFs (they are those DOFs; the interior
    follows them statically), and the weight of any other coordinate ``j`` is the largest
    weighted physical displacement of its column, ``max_i w_i |T_ij|``, so that a weighted
    error of ``e`` in it moves no point of the rotor by more than ``e``. None when ``n``
    matches neither."""
    free = np.asarray(system.dof_map.free)
    lengths = np.diff(np.asarray(system.nodes_pos, dtype=float))
    length = float(np.max(lengths, initial=0.0)) or 1.0
    w = np.where(free % DOFS_PER_NODE >= 3, length, 1.0)
    if basis is not None and basis.T.shape == (free.size, n):
        b = basis.boundary.size
        rest = np.max(np.abs(basis.T[:, b:]) * w[:, None], axis=0)
        w = np.concatenate([w[basis.boundary], np.where(rest > 0.0, rest, 1.0)])
    elif free.size != n:
        return None
    return tuple(float(x) for x in w)


def check_rtol(rtol: float) -> float:
    """``rtol`` as a float, or ModelError naming ``transient.rtol``."""
    if not (isinstance(rtol, int | float) and 1e-10 <= rtol <= 0.1):
        raise ModelError(f"rtol must be a number in [1e-10, 0.1], got {rtol!r}",
                         "transient.rtol")
    return float(rtol)


def auto_stepper(system: RotorSystem, problem: SecondOrderProblem, loads: TransientLoads,
                 profile: BoundSpeed, t0: float, t_end: float, q0: FloatArray,
                 rtol: float, basis: ReducedBasis | None = None,
                 motion: float | None = None) -> Radau:
    """The Radau stepper at ``rtol`` with the weights and motion floor of ``system``
    (:func:`dof_weights`; for a reduced problem, ``basis`` T and the floor ``motion``
    estimated on the full model)."""
    rtol = check_rtol(rtol)
    weights = dof_weights(system, problem.n, basis)
    floor = motion
    if weights is not None and floor is None and basis is None:
        floor = motion_floor(problem, loads, profile, t0, t_end, q0, weights)
    return Radau(rtol=rtol, weights=weights, motion=floor)


def motion_floor(problem: SecondOrderProblem, loads: TransientLoads, profile: BoundSpeed,
                 t0: float, t_end: float, q0: FloatArray, weights: tuple[float, ...],
                 tangents: tuple[Any, Any] | None = None) -> float | None:
    """The largest weighted amplitude of :func:`unbalance_amplitude` (None without)."""
    amp = unbalance_amplitude(problem, loads, profile, t0, t_end, q0, tangents)
    return None if amp is None else float(np.max(np.asarray(weights) * amp))


def unbalance_amplitude(problem: SecondOrderProblem, loads: TransientLoads,
                        profile: BoundSpeed, t0: float, t_end: float, q0: FloatArray,
                        tangents: tuple[Any, Any] | None = None) -> FloatArray | None:
    """Amplitude (n,) of the linear unbalance response about ``q0`` at the starting speed
    (the final one when the run starts at rest); None without unbalance or speed.
    ``tangents``: :func:`start_tangents` when the caller has them."""
    if loads.unbalance is None:
        return None
    speed = profile.speed(t0) or profile.speed(t_end)
    if speed <= 0.0:
        return None
    n = problem.n
    stiff, damp = start_tangents(problem, q0, t0) if tangents is None else tangents
    D: Any = problem.damping_at(speed)
    terms = [(1.0, problem.stiffness), (-speed * speed, problem.mass), (1.0, stiff),
             (1j * speed, D), (1j * speed, damp)]
    present = [(c, M) for c, M in terms if M is not None]
    if all(sp.issparse(M) or isinstance(M, LocalMatrix) for _, M in present):
        A = sum((c * (M.tocsr() if isinstance(M, LocalMatrix) else sp.csr_matrix(M))
                 for c, M in present), sp.csr_matrix((n, n), dtype=complex))
    else:  # a problem small enough to hold dense matrices: sum densely (converting them
        # to sparse cost 0.8 ms at n = 150, four times the factorisation)
        A = np.zeros((n, n), dtype=complex)
        for c, M in present:
            if isinstance(M, LocalMatrix):  # the bearing tangents: on their DOFs only
                A[np.ix_(M.dofs, M.dofs)] += c * M.block
            else:
                A += c * (M.toarray() if sp.issparse(M) else np.asarray(M))
    try:
        ratio = 1.0 if loads.unbalance_ratio is None else loads.unbalance_ratio
        x = factorize(A, where="transient: motion estimate").solve(  # each spool's r W
            (ratio * speed) ** 2 * loads.unbalance)
    except ConvergenceError:  # exactly at a resonance of the linearised rotor
        return None
    amp = np.abs(np.asarray(x))
    return amp if np.all(np.isfinite(amp)) else None


def start_tangents(problem: SecondOrderProblem, q0: FloatArray, t0: float
                   ) -> tuple[Any, Any]:
    """Tangents of the restoring force at the start (None without one; a
    :class:`~rotorsim.time_integration.local_tangent.LocalMatrix` as the force gives it)."""
    if problem.restoring is None:
        return None, None
    out = problem.restoring(q0, np.zeros_like(q0), t0)
    if out is None:
        return None, None
    return out[1], out[2]


@dataclass(frozen=True)
class AutoPath:
    """What the automatic path integrates: the problem (reduced or not), its basis and
    reduction report (None when full), the stepper and the reduction decision."""

    problem: SecondOrderProblem
    basis: ReducedBasis | None
    report: dict[str, Any] | None
    stepper: Radau | Exponential
    decision: dict[str, Any] | None
    fallback: Radau | None = None
    """The Radau stepper to use when ``stepper`` (exponential) cannot represent the
    linear part (:class:`~rotorsim.time_integration.exponential_modes.IllConditionedModes`
    at its start)."""


def auto_path(system: RotorSystem, problems: tuple[SecondOrderProblem, SecondOrderProblem],
              loads: TransientLoads, profile: BoundSpeed, span: tuple[float, float],
              q0: FloatArray, rtol: float, basis: ReducedBasis | None, basis_speed: float,
              may_reduce: bool, method: str | None = None) -> AutoPath:
    """The stepper at ``rtol`` and, when ``may_reduce`` and no ``basis`` is given, the
    reduction chosen by :func:`~.auto_reduction.auto_reduction`.

    ``problems`` is the full problem and the one to integrate (reduced on ``basis`` when a
    reduction was given); ``q0`` is the start on the free DOFs (on ``basis`` for a
    continued reduced run). The motion floor comes from the full model either way.
    ``method``: the method of the run being continued (a given basis is then integrated by
    it; otherwise by exponential collocation where it applies)."""
    from rotorsim.analyses.transient.auto_exponential import exponential_stepper
    from rotorsim.analyses.transient.auto_reduction import auto_reduction
    from rotorsim.analyses.transient.exponential_reduction import exponential_reduction

    rtol = check_rtol(rtol)
    t0, t_end = span
    problem, given = problems
    weights = dof_weights(system, problem.n)
    # the bearings' tangents at the start, shared by the motion estimate and the reduction
    start = start_tangents(problem, q0, t0) if q0.size == problem.n else None
    floor = None if weights is None or start is None else motion_floor(
        problem, loads, profile, t0, t_end, q0, weights, start)
    if basis is not None:  # reduction given: weights through the basis
        radau = auto_stepper(system, given, loads, profile, t0, t_end, q0, rtol, basis,
                             floor)
        fast = None if method not in (None, "exponential") else exponential_stepper(
            given, loads, profile, span, rtol, radau.weights, floor, basis.T, weights)
        if fast is not None:
            return AutoPath(given, basis, None, fast, None, radau)
        return AutoPath(given, basis, None, radau, None)
    top = max(abs(profile.speed(t0)), abs(profile.speed(t_end)))
    reduced, new_basis, decision = auto_reduction(
        system, problem, loads, (basis_speed, top), t_end - t0, rtol, floor, weights,
        may_reduce)
    if new_basis is None:
        radau = Radau(rtol=rtol, weights=weights, motion=floor)
        fast = exponential_stepper(problem, loads, profile, span, rtol, weights, floor)
        if fast is None:
            return AutoPath(problem, None, None, radau, decision)
        if may_reduce:
            small, new_basis, chosen = exponential_reduction(
                system, problem, loads, top, rtol, floor, weights,
                tangent=None if start is None else start[0],
                phase=profile.angle(t0), duration=t_end - t0)
            fast_small = None if new_basis is None else exponential_stepper(
                small, loads, profile, span, rtol, dof_weights(system, small.n, new_basis),
                floor, new_basis.T, weights)
            if fast_small is not None and new_basis is not None:
                report = {k: v for k, v in chosen.items()
                          if k not in ("reduced", "reason", "tried")}
                return AutoPath(small, new_basis, report, fast_small,
                                {**chosen, "for": "exponential"},
                                auto_stepper(system, small, loads, profile, t0, t_end, q0,
                                             rtol, new_basis, floor))
            if new_basis is not None:  # (the reduced loads failed the harmonic check)
                chosen = {**chosen, "reduced": False,
                          "reason": "the reduced problem's loads are not harmonic"}
            decision = {**decision, "exponential": chosen}
        return AutoPath(problem, None, None, fast, decision, radau)
    report = {k: v for k, v in decision.items() if k not in ("reduced", "reason", "tried")}
    stepper = auto_stepper(system, reduced, loads, profile, t0, t_end, q0, rtol,
                           new_basis, floor)
    return AutoPath(reduced, new_basis, report, stepper, decision)
