"""Stability of a rotor's torus: the quasi-periodic Hill method on a Craig-Bampton model of
the linear part (:func:`~rotorsim.harmonic_balance.quasi.hill.hill_exponents`).

The Hill matrix has ``2 n`` rows per stability tone. On the rotor's active DOFs (149 on the
default model) that is too large for a dense eigenproblem at every point of a branch, so
the linear part is reduced as for the periodic multipliers: the bearing DOFs stay physical,
their static constraint modes and the fixed-interface modes up to ``cutoff`` are kept. The
reduction only serves the exponents; the torus itself is the full solution. The cutoff
defaults to twice the highest tone ``a w1 + b w2`` of the stability box, with at least 4
modes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.quasiperiodic.problem import WHERE
from rotorsim.assembly.reduction import fixed_interface_modes
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.quasi import QuasiProblem
from rotorsim.harmonic_balance.quasi.hill import (
    EDGE_SHARE,
    MAX_ROWS,
    TorusExponents,
    hill_exponents,
)
from rotorsim.solvers.linear import factorize

FloatArray = NDArray[np.float64]
CUTOFF_FACTOR = 2.0
"""Fixed-interface modes are kept up to this multiple of ``a w1 + b w2`` (default)."""
MIN_MODES = 4
"""Fixed-interface modes kept at least."""


def reduced_quasi_problem(problem: QuasiProblem, cutoff: float) -> tuple[QuasiProblem, int]:
    """Craig-Bampton reduction of ``problem``'s linear part, the nonlinear DOFs first.

    Returns the reduced problem (``problem`` itself when every DOF is nonlinear; no
    excitation: the variational equation does not use it)
    and the number of fixed-interface modes kept (those up to ``cutoff`` [rad/s], at
    least :data:`MIN_MODES`).

    Raises
    ------
    ModelError
        The linear part is singular with the bearing DOFs clamped.
    """
    N = np.asarray(problem.nl_dofs, dtype=np.int64)
    L = np.setdiff1d(np.arange(problem.n), N)
    if L.size == 0:
        return problem, 0
    M, K = sp.csr_matrix(problem.M), sp.csr_matrix(problem.K)
    K_LL, M_LL = K[L][:, L], M[L][:, L]
    try:
        psi = -np.asarray(factorize(K_LL, where="Craig-Bampton constraint modes").solve(
            K[L][:, N].toarray()))
    except ConvergenceError as exc:
        raise ModelError("the linear part is singular with the bearing DOFs clamped: the "
                         "torus's stability cannot use a reduced model", WHERE) from exc
    phi = _modes_up_to(K_LL, M_LL, cutoff)
    k = N.size
    T = np.zeros((problem.n, k + phi.shape[1]))
    T[N, np.arange(k)] = 1.0
    T[np.ix_(L, np.arange(k))] = psi.reshape(L.size, k)
    T[np.ix_(L, k + np.arange(phi.shape[1]))] = phi

    def project(A: Any) -> FloatArray | None:
        return None if A is None else T.T @ (sp.csr_matrix(A) @ T)

    reduced = QuasiProblem(project(M), project(problem.C), project(K), project(problem.G),
                           nl_dofs=np.arange(k, dtype=np.int64), force=problem.force,
                           spin=problem.spin, spin_ratio=problem.spin_ratio)
    return reduced, int(phi.shape[1])


def _modes_up_to(K_LL: Any, M_LL: Any, cutoff: float) -> FloatArray:
    """Mass-normalised fixed-interface modes with ``w <= cutoff``, at least MIN_MODES
    (pairs of equal frequencies whole: :func:`fixed_interface_modes`)."""
    n = K_LL.shape[0]
    want = min(max(2 * MIN_MODES, 8), n)
    while True:
        w, phi = fixed_interface_modes(K_LL, M_LL, want)
        if w.size == 0 or w[-1] > cutoff or want >= n:
            keep = max(int(np.count_nonzero(w <= cutoff)), min(MIN_MODES, w.size))
            while keep < w.size and w[keep] <= w[keep - 1] * (1 + 1e-6) + 1e-12:
                keep += 1                       # a pair of equal frequencies stays whole
            return np.asarray(phi[:, :keep])
        want = min(2 * want, n)


K1_STEPS = (1, 2, 3, 4, 6, 8, 10, 12, 16, 20)
"""Shaft orders ``a`` of the stability boxes tried in turn by :func:`torus_stability`."""
AGREE_RTOL = 1e-3
"""Two consecutive boxes agree when their largest real parts differ by at most this
fraction of the larger magnitude (or both lie within the tolerance of zero)."""
STABILITY_TOL = 1e-5
"""Growth per shaft revolution ``lam T`` below which a torus counts as stable: an undamped
mode (its exponent zero to round-off, which Hill's eigenvalues return as +-1e-10) must
not flip the verdict, as ``max |mu| < 1 + tol`` for periodic orbits."""


@dataclass(frozen=True, eq=False)
class TorusStability:
    """The exponents of a torus with the evidence of their convergence.

    Attributes
    ----------
    exponents : TorusExponents
        From the last box tried.
    converged : bool
        The last two boxes agree (:data:`AGREE_RTOL`) and the last one's exponents lie
        inside it (edge share at most :data:`~rotorsim.harmonic_balance.quasi.hill.
        EDGE_SHARE`). False: the sign may be wrong; use a larger solution box.
    largest : array (b,)
        Largest real part [1/s] of each box tried.
    boxes : tuple of (int, int)
    modes : int
        Fixed-interface modes of the reduced model.
    tolerance : float
        [1/s]: stable when the largest real part is below it (:data:`STABILITY_TOL` per
        shaft revolution).
    checked : bool
        True: the boxes were grown at this torus. False: only the first box was solved
        here, and ``converged`` rests on the tori checked on both sides of it along the
        branch (:func:`~rotorsim.analyses.quasiperiodic.branch_stability.
        branch_stability`).
    """

    exponents: TorusExponents
    converged: bool
    largest: FloatArray
    boxes: tuple[tuple[int, int], ...]
    modes: int
    tolerance: float = 0.0
    checked: bool = True

    @property
    def stable(self) -> bool:
        return self.exponents.largest < self.tolerance


def _boxes(aft: Any) -> list[tuple[int, int]]:
    """Stability boxes to try (see :func:`torus_stability`)."""
    n1, n2 = aft.grid     # a box's tone differences must stay distinct on the grid
    top1, top2 = (max(min(int(v), (n - 1) // 4), 1)
                  for v, n in zip(np.abs(aft.harmonics.k).max(axis=0), (n1, n2), strict=True))
    boxes = [(1, 1)] + [(a, top2) for a in K1_STEPS if a <= top1]
    if boxes[-1] != (top1, top2):
        boxes.append((top1, top2))
    return list(dict.fromkeys(boxes))


def torus_stability(problem: QuasiProblem, X: FloatArray, aft: Any, w1: float, w2: float,
                    box: tuple[int, int] | None = None, cutoff: float | None = None,
                    first: TorusStability | None = None) -> TorusStability:
    """Exponents of the torus with coefficients ``X (rows, n)`` of ``problem``'s DOFs on the
    reduced model (module docstring).

    With ``box=None`` the stability box grows from (1, 1) to ``(1, b)``, ``(2, b)``,
    ``(3, b)`` ... (``b`` the solution's largest VC order, the shaft orders
    :data:`K1_STEPS` up to the solution's) until two consecutive boxes agree
    (:data:`AGREE_RTOL`) and the critical exponent lies inside the last one. A weakly
    modulated torus (the default model) stops at ``(1, b)``. A contact that opens and
    closes (a rigid rotor in its clearance) can need every VC order of the solution: its
    parametric instability is missed by any box with fewer (the sign is then wrong), which
    is why the VC orders come first.

    ``first``: this torus's result for the first box alone (``box=(1, 1)``, the same
    ``cutoff``), whose exponents are then reused instead of solved again.
    """
    boxes = [box] if box is not None else _boxes(aft)
    if first is not None and (box is not None or first.boxes != (boxes[0],)):
        raise ModelError(f"first must be the result of the box {boxes[0]} alone, got the "
                         f"boxes {first.boxes}", f"{WHERE}.first")
    X_nl = np.asarray(X)[:, np.asarray(problem.nl_dofs, dtype=np.int64)]
    largest: list[float] = []
    tried: list[tuple[int, int]] = []
    ex, reduced, modes, reach = None, problem, 0, -1.0
    tol = STABILITY_TOL * w1 / (2 * np.pi)
    for b in boxes:
        if first is not None and not tried:
            ex, modes = first.exponents, first.modes
            largest.append(ex.largest)
            tried.append(b)
            continue
        need = CUTOFF_FACTOR * (abs(b[0]) * w1 + abs(b[1]) * w2) if cutoff is None \
            else float(cutoff)
        if need > reach:      # the modes a wider box reaches
            reduced, modes = reduced_quasi_problem(problem, need)
            reach = need
        if 2 * reduced.n * (2 * b[0] + 1) * (2 * b[1] + 1) > MAX_ROWS:
            break
        ex = hill_exponents(reduced, X_nl, aft, w1, w2, box=b)
        largest.append(ex.largest)
        tried.append(b)
        inside = ex.edge_share.size > 0 and ex.edge_share[0] <= EDGE_SHARE
        if len(largest) >= 2 and inside and abs(largest[-1] - largest[-2]) <= max(
                AGREE_RTOL * max(abs(largest[-1]), abs(largest[-2])), tol):
            return TorusStability(ex, True, np.array(largest), tuple(tried), modes, tol)
    if ex is None:
        raise ModelError(f"the smallest stability box {boxes[0]} already needs a Hill "
                         f"matrix above {MAX_ROWS} rows on {reduced.n} reduced DOFs", WHERE)
    return TorusStability(ex, box is not None and ex.edge_share.size > 0 and
                          ex.edge_share[0] <= EDGE_SHARE, np.array(largest), tuple(tried),
                          modes, tol)
