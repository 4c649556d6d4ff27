"""The automatic path's choice of a Craig-Bampton reduction, with its a-priori checks.

``rs.transient(rotor, t_end, rtol=r)`` may integrate a Craig-Bampton model
(:mod:`rotorsim.assembly.reduction`, :mod:`~.reduction`) instead of the full one: the
bearing DOFs stay physical, the interior is held by the constraint modes, the static
responses to the run's loads and the lowest fixed-interface modes. The choice is made
before the first step:

1. **Eligible runs only.** A model with nonlinear bearing DOFs (the boundary), an unbalance
   (it sets both the motion and the error estimate below), no speed-dependent linear
   bearings, base excitation, user force function or torque drive, and more than
   :data:`MIN_FREE` free DOFs. Below that size the full model is stepped with dense
   inverses and a step costs no more than a reduced one, while the reduction adds its
   set-up and a truncation error (measured on the ``bench`` and ``issue14`` rotors of
   ``benchmarks/bench_transient.py``: 2 to 9 times more steps at rtol 1e-3, no run faster).
2. **Modes from the accuracy asked.** For ``k`` in :data:`MODE_COUNTS` the a-priori
   truncation error is the interior static response to the unbalance (at the top speed)
   outside the ``k`` kept modes, ``r = S - Phi Phi^T M_ii S`` with ``S = K_ii^-1 f_i``:
   what an unbalance switched on at ``t0`` leaves ringing in the dropped modes (each mode
   ``j`` takes ``phi_j phi_j^T f / w_j^2`` of it; the forced, quasi-static part is exact,
   since ``S`` is in the basis). Its largest weighted value must stay below
   :data:`RINGING_SHARE` of ``rtol`` times the a-priori motion (the unbalance response of
   the full linearised model). On the benchmark rotors the estimate bounds the error found
   by a tight full-model reference with a margin of 2 to 4.
3. **Frequency check.** The lowest natural frequencies of the full and reduced models with
   the bearings' nominal tangent (:func:`~rotorsim.assembly.reduction.accuracy`) agree to
   ``rtol``.
4. **Size.** The reduced model stays below :data:`MAX_FRACTION` of the full one.

The first ``k`` that passes is used; when none does, the full model is integrated. The
decision, with the estimates, is reported in ``result.options["auto_reduction"]``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sp

from rotorsim.analyses.transient.loads import RestoringForce, TransientLoads
from rotorsim.analyses.transient.reduction import reduce_problem
from rotorsim.assembly.reduction import CLUSTER_RTOL, ReducedBasis, fixed_interface_modes
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray
from rotorsim.solvers.linear import factorize
from rotorsim.time_integration.problem import SecondOrderProblem

MIN_FREE = 400
"""Models with at most this many free DOFs are integrated in full (module docstring)."""
MODE_COUNTS = (8, 16, 32, 64)
"""Numbers of fixed-interface modes tried, in this order (from one eigensolution)."""
MAX_MODES = max(MODE_COUNTS) + 8
"""Modes computed at most (the largest count and room for its cluster)."""
MIN_REVOLUTIONS = 10.0
"""Runs shorter than this many revolutions at the top speed are integrated in full: the
reduction's set-up (an eigensolution of the interior) costs as much as a short run of the
full model, and a reduced step saves about half a full one (measured on the 1,000-DOF
rotor of ``benchmarks/bench_transient.py``: 4 ms, 0.4 revolutions at rtol 1e-3, full 0.17
s against 0.30 s reduced; 40 ms, 1.49 s against 1.10 s)."""
RINGING_SHARE = 0.2
"""Share of ``rtol`` allowed to the a-priori truncation error (the rest to the stepper)."""
MAX_FRACTION = 0.25
"""Largest reduced size, as a fraction of the full one."""

Reduced = tuple[SecondOrderProblem, ReducedBasis | None, dict[str, Any]]


def auto_reduction(system: RotorSystem, problem: SecondOrderProblem, loads: TransientLoads,
                   speeds: tuple[float, float], duration: float, rtol: float,
                   motion: float | None, weights: tuple[float, ...] | None,
                   eligible: bool = True) -> Reduced:
    """The problem to integrate: reduced when the checks of the module docstring pass.

    Parameters
    ----------
    speeds : (basis speed, top speed) [rad/s]
        Speed of the linear matrices of the basis, and the largest speed of the run (the
        unbalance load of the error estimate).
    duration : float
        Length of the run [s].
    motion : float or None
        A-priori motion of the full model (largest weighted unbalance amplitude) [m].
    weights : tuple of float or None
        Weights of the free DOFs in the error (:func:`~.auto.dof_weights`).
    eligible : bool
        False for runs the estimate does not cover (torque drive, continuation).

    Returns
    -------
    (problem, basis or None, decision) : the decision has ``reduced`` (bool), ``reason``
    and, when modes were tried, ``modes``, ``estimate`` (relative to the motion) and
    ``frequency_error`` of each count.
    """
    revolutions = speeds[1] * duration / (2.0 * np.pi)
    reason = _ineligible(system, problem, loads, motion, weights, eligible, revolutions)
    if reason:
        return problem, None, {"reduced": False, "reason": reason}
    assert weights is not None and motion
    n, boundary, inner = split_dofs(system)
    K_ii, M_ii, S, _ = _interior(system, loads, inner, speeds)
    largest = min(MAX_MODES, int(MAX_FRACTION * n) - boundary.size - 4, inner.size)
    if largest < MODE_COUNTS[0]:
        return problem, None, {"reduced": False, "reason": "too few interior DOFs"}
    freqs, phi = fixed_interface_modes(K_ii, M_ii, largest)
    w = np.asarray(weights)[inner]
    tried: list[dict[str, float]] = []
    for count in (c for c in MODE_COUNTS if c <= freqs.size):
        count = _cluster_end(freqs, count)
        kept = phi[:, :count]
        r = S - kept @ (kept.T @ (M_ii @ S))
        record = {"modes": count, "estimate": float(np.max(w[:, None] * np.abs(r))) / motion}
        tried.append(record)
        if record["estimate"] > RINGING_SHARE * rtol:
            continue
        reduced, basis, report = reduce_problem(system, problem, loads, count, speeds[0],
                                                modes=(freqs[:count], kept))
        record["frequency_error"] = float(report["max_relative_error"])
        if record["frequency_error"] <= rtol:
            return reduced, basis, {"reduced": True, "reason": "checks passed",
                                    "tried": tried, **report}
    return problem, None, {"reduced": False, "tried": tried,
                           "reason": "no mode count up to the size limit passed the checks"}


def split_dofs(system: RotorSystem) -> tuple[int, np.ndarray, np.ndarray]:
    """The number of free DOFs, the nonlinear (boundary) DOFs and the interior ones."""
    assert system.nonlinear is not None
    n = system.n_free
    boundary = np.unique(system.nonlinear.dofs)
    return n, boundary, np.setdiff1d(np.arange(n), boundary)


def _cluster_end(freqs: FloatArray, count: int) -> int:
    """``count`` raised to keep the last cluster of equal frequencies whole (as
    :func:`~rotorsim.assembly.reduction.fixed_interface_modes` does)."""
    last = freqs[count - 1]
    return count + int(np.count_nonzero(freqs[count:] <= last * (1.0 + CLUSTER_RTOL) + 1e-12))


def _ineligible(system: RotorSystem, problem: SecondOrderProblem, loads: TransientLoads,
                motion: float | None, weights: tuple[float, ...] | None,
                eligible: bool, revolutions: float) -> str:
    """Why the run is integrated in full without trying modes ('' when it may not be)."""
    checks = [
        (not eligible, "torque drive or continued run"),
        (system.nonlinear is None or not isinstance(problem.restoring, RestoringForce),
         "no nonlinear bearing DOFs to keep as boundary"),
        (problem.speed_terms is not None, "speed-dependent linear bearings"),
        (any(x is not None for x in (loads.base, loads.forces, loads.torsion)),
         "base excitation, force function or torsion loads (not in the estimate)"),
        (loads.unbalance is None or not motion or weights is None,
         "no unbalance: no a-priori motion and error estimate"),
        (revolutions < MIN_REVOLUTIONS,
         f"{revolutions:.3g} revolutions < {MIN_REVOLUTIONS:g}: the set-up would not pay"),
        (system.n_free <= MIN_FREE,
         f"{system.n_free} free DOFs <= {MIN_FREE}: a full step costs as much as a "
         "reduced one"),
    ]
    return next((text for bad, text in checks if bad), "")


def _interior(system: RotorSystem, loads: TransientLoads, inner: np.ndarray,
              speeds: tuple[float, float]) -> tuple[Any, Any, FloatArray, Any]:
    """``K_ii``, ``M_ii``, the interior static responses (n_i, 2) to both phases of the
    unbalance load at the top speed and the factorisation of ``K_ii`` (which
    :func:`~rotorsim.assembly.reduction.craig_bampton` can reuse)."""
    mats = system.matrices(speeds[0])
    K, M = sp.csr_matrix(mats.K), sp.csr_matrix(mats.M)
    K_ii, M_ii = K[inner][:, inner].tocsc(), M[inner][:, inner].tocsc()
    assert loads.unbalance is not None
    ratio = 1.0 if loads.unbalance_ratio is None else loads.unbalance_ratio
    f = (np.asarray(ratio * speeds[1]) ** 2 * loads.unbalance)[inner]
    lu = factorize(K_ii, where="transient: reduction estimate")
    S = np.asarray(lu.solve(np.column_stack([f.real, f.imag]))).reshape(inner.size, 2)
    return K_ii, M_ii, S, lu
