"""Floquet stability of a harmonic-balance solution: result type, classification, Hill.

Three ways to the ``2n`` Floquet multipliers of the variational equation

    M y'' + (D + C_t(t)) y' + (K + K_t(t)) y = 0,     D = C + W G,
    K_t = dr/dq, C_t = dr/dv along the periodic solution (period T = 2 pi / omega):

* :func:`hill` (here): Hill's method, spectral in the harmonics; cheap for small ``n``
  because it reuses the HB Jacobian;
* :func:`~rotorsim.harmonic_balance.monodromy.hsu`: Hsu's discrete transition matrix from
  the tangents at the time samples (seed 002 eqs 3.37-3.38), for any ``n``;
* :func:`~rotorsim.harmonic_balance.monodromy.variational`: integration of the
  variational equations over one period with the Newmark stepper (small ``n``; a check).

Hill's method. Inserting ``y = e^{lam t} p(t)`` with ``p`` periodic into the variational
equation and balancing the harmonics of ``p`` gives the quadratic eigenproblem

    (J + lam D1 + lam^2 D2) P = 0,   J = dR/dX (the HB Jacobian of all DOFs),
    D1 = 2 omega nabla (x) M + I (x) D + Gamma^+ diag(C_t) Gamma,   D2 = I (x) M,

solved densely on its companion pencil (size ``2 (2H + 1) n``). Each Floquet exponent
appears ``2H + 1`` times, shifted by ``i m omega``; ``2n`` are selected:

* ``selection="eigenvector"`` (default): the exponents whose eigenvectors are centred on
  harmonic 0, i.e. the smallest ``|mean harmonic index|`` of the eigenvector written in
  complex exponentials ``p = sum_m p_m e^{i m tau}`` (weights ``|p_m|^2``). A shift by
  ``i omega`` moves that mean by exactly one, so one copy per exponent has it in
  ``[-1/2, 1/2]``, and it is the copy least affected by the truncation at ``+-H``; for a
  linear time-invariant system it returns the exact eigenvalues, not shifted copies.
* ``selection="imaginary"``: the ``2n`` exponents with the smallest ``|Im lam|``
  (the classical criterion; same multipliers when the truncation is converged, but it
  picks copies concentrated on harmonics ``m != 0`` when the natural frequencies exceed
  ``omega / 2``; for a mode above ``H omega`` only the copies at the truncation edge
  remain, the least accurate ones in a nonlinear problem).

Among ties (period doubling: ``sigma +- i omega / 2`` are copies of one exponent) a
candidate that is a shifted copy of one already chosen is skipped.

Multipliers are ``exp(lam T)``. The solution is stable when all ``|mu| < 1`` (for an
autonomous problem the trivial multiplier nearest ``+1`` is excluded). The *critical*
multiplier is the largest in modulus; its position names the bifurcation at which it
leaves the unit circle: real ``> 0`` fold (or branch point), real ``< 0`` period doubling,
complex Neimark-Sacker.

References
----------
Seed 002 section 3.5.2.2 (Floquet multipliers, eqs 3.37-3.38). G. W. Hill, Acta Math. 8
(1886) 1-36. A. Lazarus, O. Thomas, C. R. Mecanique 338 (2010) 510-517 (Hill's method with
HB, eigenvector-based sorting). M. Krack, J. Gross, *Harmonic Balance for Nonlinear
Vibration Problems*, Springer 2019, section 3.5.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Literal

import numpy as np
import scipy.linalg as sl
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError, Status
from rotorsim.harmonic_balance.fourier import ComplexArray, FloatArray, derivative_matrix
from rotorsim.harmonic_balance.nonlinear import nonlinear_harmonics
from rotorsim.harmonic_balance.problem import as_dense
from rotorsim.harmonic_balance.residual import HBResidual, linear_jacobian

COPY_TOL = 1e-4
"""Relative distance below which two Hill exponents count as shifted copies."""

CRITICAL_KINDS = ("fold", "period_doubling", "neimark_sacker")
"""Names of the critical multiplier's position: +1 side, -1 side, complex pair."""


@dataclass(frozen=True, eq=False)
class FloquetResult:
    """Floquet multipliers of a periodic solution and their reading.

    Attributes
    ----------
    multipliers : complex array (2n,)
        Sorted by decreasing modulus.
    exponents : complex array (2n,)
        ``log(mu) / T`` [1/s] (principal branch) in the same order; Hill's method gives the
        selected exponents themselves.
    period : float
        ``T = 2 pi / omega`` [s].
    stable : bool
        All multipliers (except the trivial one of an autonomous problem) inside the unit
        circle.
    critical : complex
        The largest multiplier in modulus (trivial one excluded).
    kind : str
        Where ``critical`` sits: "fold" (real positive), "period_doubling" (real negative)
        or "neimark_sacker" (complex).
    method : str
        "hill", "hsu" or "variational".
    stats : dict
        ``wall_time`` [s] and method-specific counts.
    status : Status
    """

    multipliers: ComplexArray
    exponents: ComplexArray
    period: float
    stable: bool
    critical: complex
    kind: str
    method: str
    stats: dict[str, float]
    status: Status = Status.OK

    @property
    def max_modulus(self) -> float:
        """``|critical|``."""
        return abs(self.critical)


def classify(multipliers: ArrayLike, *, autonomous: bool = False,
             imag_tol: float = 1e-6) -> tuple[bool, complex, str]:
    """Stability, critical multiplier and its kind.

    Parameters
    ----------
    multipliers : complex array-like
    autonomous : bool
        Exclude the multiplier nearest ``+1`` (phase shift along the orbit).
    imag_tol : float
        ``|Im mu| <= imag_tol * max(|mu|, 1)`` counts as real.

    Examples
    --------
    >>> classify([0.5, -1.2, 0.1j])
    (False, (-1.2+0j), 'period_doubling')
    >>> classify([1.0 + 1e-12j, 0.9 + 0.5j, 0.9 - 0.5j], autonomous=True)
    (False, (0.9+0.5j), 'neimark_sacker')
    """
    mu = np.asarray(multipliers, dtype=complex).reshape(-1)
    if autonomous:
        if mu.size == 0:
            raise ModelError("an autonomous problem has at least the trivial multiplier",
                             "classify")
        mu = np.delete(mu, int(np.argmin(np.abs(mu - 1.0))))
    if mu.size == 0:
        return True, 0j, "fold"
    order = np.lexsort((-mu.imag, -np.abs(mu)))
    crit = complex(mu[order[0]])
    if abs(crit.imag) <= imag_tol * max(abs(crit), 1.0):
        kind = "fold" if crit.real >= 0 else "period_doubling"
        crit = complex(crit.real, 0.0)
    else:
        kind = "neimark_sacker"
    return bool(abs(crit) < 1.0), crit, kind


def floquet_result(multipliers: ArrayLike, omega: float, method: str,
                   stats: dict[str, float], *, exponents: ArrayLike | None = None,
                   autonomous: bool = False) -> FloquetResult:
    """Sort, classify and pack multipliers (exponents from ``log(mu) / T`` if not given)."""
    mu = np.asarray(multipliers, dtype=complex).reshape(-1)
    T = 2.0 * math.pi / omega
    lam = np.log(mu) / T if exponents is None else np.asarray(exponents, dtype=complex)
    order = np.lexsort((-mu.imag, -np.abs(mu)))
    stable, crit, kind = classify(mu, autonomous=autonomous)
    return FloquetResult(mu[order], lam[order], T, stable, crit, kind, method, stats)


def hill(residual: HBResidual, x: ArrayLike, omega: float, param: float = 0.0, *,
         selection: Literal["eigenvector", "imaginary"] = "eigenvector",
         autonomous: bool = False) -> FloquetResult:
    """Floquet multipliers by Hill's method (see the module docstring).

    Parameters
    ----------
    residual : HBResidual
        Condensed or full; Hill's matrices are always built on all DOFs (dense, size
        ``2 (2H + 1) n``: intended for ``(2H + 1) n`` up to a few hundred).
    x : array (residual.size,)
        A solution of ``residual`` at ``omega`` and ``param``.
    omega, param : float
    selection : {"eigenvector", "imaginary"}
        How the ``2n`` exponents are picked among the ``2 (2H + 1) n``.
    autonomous : bool
        Exclude the trivial multiplier from the stability decision.

    Examples
    --------
    A damped linear oscillator: the exponents are its eigenvalues ``-0.05 +- i sqrt(1 -
    0.05^2)``.

    >>> from rotorsim.harmonic_balance.problem import HBProblem
    >>> from rotorsim.harmonic_balance.residual import make_residual
    >>> pb = HBProblem(np.eye(1), np.eye(1), 0.1 * np.eye(1))
    >>> fl = hill(make_residual(pb, 3, condense=False), np.zeros(7), 0.7)
    >>> np.round(fl.exponents, 6).tolist(), fl.stable
    ([(-0.05+0.998749j), (-0.05-0.998749j)], True)
    """
    if selection not in ("eigenvector", "imaginary"):
        raise TypeError(f"unknown selection {selection!r}; valid: eigenvector, imaginary")
    clock = time.perf_counter()
    J, D1, D2 = hill_matrices(residual, x, omega, param)
    m = J.shape[0]
    A = np.block([[np.zeros((m, m)), np.eye(m)], [-J, -D1]])
    B = np.block([[np.eye(m), np.zeros((m, m))], [np.zeros((m, m)), D2]])
    lam, V = sl.eig(A, B)
    finite = np.isfinite(lam)
    lam, P = lam[finite], V[:m, finite]
    n = residual.problem.n
    if lam.size < 2 * n:
        raise ModelError(f"only {lam.size} finite Hill eigenvalues for {2 * n} exponents "
                         "(singular mass matrix)", "hill")
    if selection == "eigenvector":
        score = np.abs(mean_harmonic_index(P, residual.harmonics, n))
    else:
        score = np.abs(lam.imag)
    chosen = select_exponents(lam, score, 2 * n, omega)
    T = 2.0 * math.pi / omega
    stats = {"eigen_solves": 1.0, "size": float(2 * m),
             "wall_time": time.perf_counter() - clock}
    return floquet_result(np.exp(lam[chosen] * T), omega, "hill", stats,
                          exponents=lam[chosen], autonomous=autonomous)


def select_exponents(lam: ComplexArray, score: FloatArray, count: int,
                     omega: float) -> list[int]:
    """Indices of ``count`` exponents, best ``score`` first, one copy per family.

    A candidate is skipped when it is a shifted copy ``lam' = lam + i m omega`` (``m != 0``,
    relative tolerance ``COPY_TOL``) of one already chosen: at a period-doubling multiplier
    the copies ``sigma +- i omega / 2`` tie in both criteria. Equal exponents (``m = 0``,
    a double multiplier) are kept.
    """
    chosen: list[int] = []
    for i in np.argsort(score, kind="stable"):
        d = lam[i] - lam[chosen]
        shift = np.round(d.imag / omega)
        tol = COPY_TOL * (abs(lam[i]) + omega)
        copy = (np.abs(d.real) <= tol) & (np.abs(d.imag - shift * omega) <= tol) & (shift != 0)
        if not copy.any():
            chosen.append(int(i))
        if len(chosen) == count:
            break
    return chosen


def hill_matrices(residual: HBResidual, x: ArrayLike, omega: float,
                  param: float = 0.0) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Dense ``J``, ``D1``, ``D2`` of Hill's quadratic eigenproblem on all DOFs."""
    pb, aft, H = residual.problem, residual.aft, residual.harmonics
    X = residual.expand(x, omega, param)
    nl = nonlinear_harmonics(pb, aft, X[:, pb.nl_dofs], omega, param, jacobian=True,
                             velocity_jacobian=True)
    assert nl.jacobian is not None and nl.velocity_jacobian is not None
    idx = (np.arange(aft.rows)[:, None] * pb.n + pb.nl_dofs[None, :]).reshape(-1)
    J = linear_jacobian(pb, H, omega)
    J[np.ix_(idx, idx)] += nl.jacobian
    M = as_dense(pb.mass)
    eye = np.eye(aft.rows)
    D1 = 2.0 * omega * np.kron(derivative_matrix(H), M) + np.kron(
        eye, as_dense(pb.damping_matrix(omega)))
    D1[np.ix_(idx, idx)] += nl.velocity_jacobian
    return J, D1, np.asarray(np.kron(eye, M), dtype=np.float64)


def mean_harmonic_index(P: ComplexArray, harmonics: int, n: int) -> FloatArray:
    """Mean harmonic index ``sum m |p_m|^2 / sum |p_m|^2`` of each column of ``P``.

    ``P`` ((2H + 1) n, count) holds real-layout coefficients (complex-valued); the complex
    exponential amplitudes are ``p_0 = P_0``, ``p_{+-h} = (P_hc -+ i P_hs) / 2``.
    """
    Q = P.reshape(2 * harmonics + 1, n, -1)
    w0 = np.sum(np.abs(Q[0]) ** 2, axis=0)
    wp = np.sum(np.abs(Q[1::2] - 1j * Q[2::2]) ** 2, axis=1) / 4.0    # (H, count)
    wm = np.sum(np.abs(Q[1::2] + 1j * Q[2::2]) ** 2, axis=1) / 4.0
    h = np.arange(1, harmonics + 1)[:, None]
    total = w0 + wp.sum(axis=0) + wm.sum(axis=0)
    return (h * (wp - wm)).sum(axis=0) / np.where(total > 0, total, 1.0)
