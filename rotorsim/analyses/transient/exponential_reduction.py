"""The automatic path's Craig-Bampton reduction ahead of exponential collocation.

Exponential collocation (:mod:`rotorsim.time_integration.exponential`) starts with a dense
eigen-decomposition of the linear rotor, of size ``2 n``: on the 150-DOF benchmark rotor
about a quarter of a short run. A Craig-Bampton model (:mod:`rotorsim.assembly.reduction`:
the bearing DOFs kept physical, constraint modes, the lowest fixed-interface modes and the
static responses to gravity and both phases of the unbalance) shrinks it; the bearing
forces still see physical displacements, and the quasi-static response to the loads is
exact.

What a reduced run cannot hold is, first, the *ringing* of the dropped modes: the
unbalance, switched on at full speed at ``t0``, sets every mode ``j`` of the interior
oscillating about its static share ``phi_j phi_j^T f / w_j^2`` with about that amplitude,
undamped. Its estimate is the interior static response to the unbalance outside the kept
modes, ``r = S - Phi Phi^T M_ii S`` with ``S = K_ii^-1 f_i`` (as in :mod:`~.auto_reduction`).
Second, the *drift*: the reduced model's modes on the bearings are a little too stiff, and
the modes set ringing at the start drift in phase against the full model's, an error that
grows with the length of the run (:mod:`~.reduction_drift`). The estimate of a mode count
is the largest of ringing plus drift over the DOFs, weighted as the error is and relative
to the a-priori motion. Measured on every node of the rotors ``bench``, ``issue14`` of
``benchmarks/bench_transient.py`` and the small test rotor (the reduced and the full model
both at rtol 1e-8, 8 to 48 modes), the truncation error relative to the stepper's motion
scale (the larger of the a-priori motion and the motion reached) was 0.2 to 0.8 times this
estimate, and 1.7 to 10 times the ringing alone, which had been the whole check (the fifth
pass measured it at the probe only, 0.1 to 1.1 times; ``docs/validation.md``).
The reduction is used with the fewest modes of :data:`MODE_COUNTS` for which

1. the estimate is at most :data:`SHARE` of ``rtol`` (the rest is left to the stepper,
   whose error on the full models was 0.07 to 0.35 of ``rtol`` over the whole rotor);
2. the lowest dropped fixed-interface frequency is at least :data:`CUTOFF` times the
   speed (the unbalance's frequency), so that the dropped modes respond quasi-statically
   to the load (their ringing apart);
3. the reduced model has at most :data:`MAX_FRACTION` of the unknowns (below that the
   eigen-decomposition saved does not repay the interior eigensolution and the basis).

The counts are searched by bisection among those whose ringing passes (the drift needs the
basis: about 2 ms a count); the estimates fell with the count on the rotors measured (the
bases are nested, so their Ritz values fall), and where they did not, bisection returns a
larger count that passes, never one that fails.
Otherwise the full model is integrated; the decision, with the estimates tried, is in
``result.options["auto_reduction"]``. At tight ``rtol`` (1e-5 on the benchmark rotors) no
count passes: the unbalance's point load at its own node converges slowly with the modes.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp

from rotorsim.analyses.transient.auto_reduction import (
    Reduced,
    _cluster_end,
    split_dofs,
)
from rotorsim.analyses.transient.loads import RestoringForce, TransientLoads
from rotorsim.analyses.transient.reduction import load_shapes, reduce_problem
from rotorsim.analyses.transient.reduction_drift import frequency_drift
from rotorsim.assembly.reduction import (
    ReducedBasis,
    constraint_parts,
    craig_bampton,
    fixed_interface_modes,
)
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray
from rotorsim.solvers.dense_groups import coupled_groups
from rotorsim.solvers.linear import factorize
from rotorsim.time_integration.base import IntArray
from rotorsim.time_integration.problem import SecondOrderProblem

MODE_COUNTS = (8, 16, 24, 32, 48)
"""Numbers of fixed-interface modes tried, in this order (from one eigensolution)."""
SHARE = 0.2
"""Share of ``rtol`` allowed to the a-priori truncation estimate, ringing and drift (module
docstring; as :data:`~.auto_reduction.RINGING_SHARE` of the Radau path)."""
CUTOFF = 5.0
"""Lowest dropped fixed-interface frequency, in multiples of the speed."""
MAX_FRACTION = 0.5
"""Largest reduced size as a fraction of the full one."""


def exponential_reduction(system: RotorSystem, problem: SecondOrderProblem,
                          loads: TransientLoads, speed: float, rtol: float,
                          motion: float | None, weights: tuple[float, ...] | None, *,
                          tangent: Any, phase: float, duration: float) -> Reduced:
    """The problem for exponential collocation at the constant ``speed`` [rad/s]: reduced
    when the checks of the module docstring pass, else ``problem`` itself.

    Parameters
    ----------
    motion : float or None
        A-priori motion of the full model (largest weighted unbalance amplitude) [m].
    weights : tuple of float or None
        Weights of the free DOFs in the error (:func:`~.auto.dof_weights`).
    tangent : LocalMatrix, sparse, array or None
        The bearings' stiffness tangent at the start [N/m] (for the drift estimate).
    phase : float
        Shaft angle at the start [rad] (the unbalance load is ``Re(f e^{i phase})`` then).
    duration : float
        Length of the run [s].

    Returns
    -------
    (problem, basis or None, decision) : the decision has ``reduced`` (bool), ``reason``
    and ``tried`` (per mode count: ``modes``, ``estimate`` relative to the motion, i.e. the
    ``ringing`` plus, for the counts the bisection tried, the frequency ``drift``, and the
    lowest dropped frequency ``cutoff`` [rad/s]); when reduced, the report of
    :func:`~.reduction.reduce_problem` too.
    """
    reason = _ineligible(system, problem, loads, motion, weights, speed)
    if reason:
        return problem, None, {"reduced": False, "reason": reason}
    assert weights is not None and motion
    n, boundary, inner = split_dofs(system)
    largest = min(max(MODE_COUNTS), int(MAX_FRACTION * n) - boundary.size - 3,
                  inner.size - 2)
    if largest < MODE_COUNTS[0]:
        return problem, None, {"reduced": False, "reason": "too few interior DOFs"}
    stiffness, mass = _dense(problem.stiffness), _dense(problem.mass)
    K_ii, M_ii, S, lu = _dense_interior(stiffness, mass, loads, inner, speed)
    freqs, phi = interior_modes(K_ii, M_ii, largest + 1)
    all_weights = np.asarray(weights)
    w = all_weights[inner]
    assert loads.unbalance is not None
    load = speed * speed * loads.unbalance * np.exp(1j * phase)
    tried: list[dict[str, Any]] = []
    candidates: list[tuple[dict[str, Any], FloatArray]] = []
    for count in (c for c in MODE_COUNTS if c <= largest):
        count = _cluster_end(freqs, count)
        if count >= freqs.size:
            break
        kept = phi[:, :count]
        r = S - kept @ (kept.T @ (M_ii @ S))
        ringing = np.max(w[:, None] * np.abs(r), axis=1)
        record = {"modes": count, "cutoff": float(freqs[count]),
                  "ringing": float(ringing.max()) / motion}
        record["estimate"] = record["ringing"]
        tried.append(record)
        # the drift only adds to the estimate: counts whose ringing fails need no basis
        if record["ringing"] <= SHARE * rtol and record["cutoff"] >= CUTOFF * abs(speed):
            candidates.append((record, ringing))

    # the constraint modes and static responses, shared by the bases of every count
    parts = constraint_parts(system, system.nonlinear.dofs,  # type: ignore[union-attr]
                             static_loads=load_shapes(loads), speed=speed,
                             interior=(K_ii, M_ii, lu), stiffness=stiffness)

    def passes(record: dict[str, Any], ringing: FloatArray) -> ReducedBasis | None:
        """The basis of ``record``'s count when its size and estimate pass."""
        count = record["modes"]
        basis = craig_bampton(system, parts.boundary, count,
                              modes=(freqs[:count], phi[:, :count]), parts=parts)
        if basis.size > MAX_FRACTION * n:
            record["size"] = basis.size
            return None
        drift = frequency_drift(basis, stiffness, mass, tangent, inner, lu,
                                load, speed, duration, all_weights)
        record["drift"] = float(drift.max()) / motion
        drift[inner] += ringing
        record["estimate"] = float(drift.max()) / motion
        return basis if record["estimate"] <= SHARE * rtol else None

    # bisection over the candidates (module docstring), each step a basis and a drift;
    # the reduced problem is formed for the count chosen only
    lo, hi, best = 0, len(candidates) - 1, None
    while lo <= hi:
        mid = (lo + hi) // 2
        found = passes(*candidates[mid])
        if found is not None:
            best, hi = found, mid - 1
        elif "size" in candidates[mid][0]:
            hi = mid - 1  # larger counts only grow
        else:
            lo = mid + 1
    if best is not None:
        reduced, basis, report = reduce_problem(system, problem, loads, best.frequencies.size,
                                                speed, check=False, basis=best)
        return reduced, basis, {"reduced": True, "reason": "checks passed", "tried": tried,
                                **report}
    return problem, None, {"reduced": False, "tried": tried,
                           "reason": "no mode count up to the size limit passed the checks"}


def interior_modes(K_ii: Any, M_ii: Any, count: int) -> tuple[FloatArray, FloatArray]:
    """The lowest ``count`` fixed-interface modes (at least; the last cluster of equal
    frequencies whole), as :func:`~rotorsim.assembly.reduction.fixed_interface_modes`
    returns them, from one dense eigensolution per group of interior DOFs that neither
    ``K_ii`` nor ``M_ii`` couples (the two bending planes, axial motion and torsion of a
    shaft carry no coupling without the bearings: four problems of a quarter of the size
    cost about a sixteenth of one).

    Returns
    -------
    frequencies : array (m,) [rad/s], ascending; modes : array (n_i, m), mass-normalised.
    """
    # dense: scipy's fancy indexing of a sparse matrix costs about 0.3 ms per block, more
    # than copying the whole matrix at the sizes integrated by exponential collocation
    # (at most EXPONENTIAL_LIMIT unknowns)
    Kd, Md = _dense(K_ii), _dense(M_ii)
    groups = coupled_groups((Kd != 0.0) | (Md != 0.0))
    if len(groups) == 1:
        return fixed_interface_modes(sp.csr_matrix(Kd), sp.csr_matrix(Md), count)
    n = Kd.shape[0]
    lams, cols = [], []
    for idx in groups:
        sub = np.ix_(idx, idx)
        top = min(count + 2, idx.size)
        # all pairs and a slice: at these sizes LAPACK's full solver is faster than the
        # subset one (measured: 0.4 against 1.0 ms at 46 DOFs)
        lam, vec = sl.eigh(Kd[sub], Md[sub], check_finite=False)
        full = np.zeros((n, top))
        full[idx] = vec[:, :top]
        lams.append(lam[:top])
        cols.append(full)
    lam = np.concatenate(lams)
    order = np.argsort(lam, kind="stable")
    w = np.sqrt(np.maximum(lam[order], 0.0))
    phi = np.hstack(cols)[:, order]
    keep = min(_cluster_end(w, min(count, w.size)), w.size)
    return w[:keep], phi[:, :keep]


def _dense(A: Any) -> FloatArray:
    """``A`` as a dense float array (the problem's matrices are dense up to
    :data:`~.equation.DENSE_STEPPING` unknowns already)."""
    return np.asarray(A.toarray() if sp.issparse(A) else A, dtype=float)


def _dense_interior(stiffness: FloatArray, mass: FloatArray, loads: TransientLoads,
                    inner: IntArray, speed: float) -> tuple[FloatArray, FloatArray,
                                                            FloatArray, Any]:
    """As :func:`~.auto_reduction._interior`, from the problem's dense ``stiffness`` and
    ``mass`` [N/m, kg] (equal to the system's at ``speed``: no speed-dependent linear
    bearings here): ``K_ii``, ``M_ii``, the interior static responses (n_i, 2) to both
    phases of the unbalance at ``speed`` [rad/s] and the dense LU of ``K_ii``. Slices of
    dense arrays cost microseconds where scipy.sparse's row and column indexing cost about
    0.3 ms each at these sizes."""
    block = np.ix_(inner, inner)
    K_ii, M_ii = stiffness[block], mass[block]
    assert loads.unbalance is not None
    ratio = 1.0 if loads.unbalance_ratio is None else loads.unbalance_ratio
    f = (np.asarray(ratio * speed) ** 2 * loads.unbalance)[inner]
    lu = factorize(K_ii, where="transient: reduction estimate", dense_threshold=inner.size)
    S = np.asarray(lu.solve(np.column_stack([f.real, f.imag]))).reshape(inner.size, 2)
    return K_ii, M_ii, S, lu


def _ineligible(system: RotorSystem, problem: SecondOrderProblem, loads: TransientLoads,
                motion: float | None, weights: tuple[float, ...] | None, speed: float
                ) -> str:
    """Why the run is integrated in full without trying modes ('' when it may not be)."""
    checks = [
        (system.nonlinear is None or not isinstance(problem.restoring, RestoringForce),
         "no nonlinear bearing DOFs to keep as boundary"),
        (problem.speed_terms is not None, "speed-dependent linear bearings"),
        (any(x is not None for x in (loads.base, loads.forces, loads.torsion)),
         "base excitation, force function or torsion loads (not in the estimate)"),
        (loads.unbalance is None or not motion or weights is None or speed == 0.0,
         "no unbalance: no a-priori motion and error estimate"),
    ]
    return next((text for bad, text in checks if bad), "")
