"""The Liouville check of a set of Floquet multipliers.

For the first-order variational equation ``y' = A(t) y`` (see
:mod:`~rotorsim.harmonic_balance.monodromy`), Liouville's formula gives

    det Phi(T) = prod_i mu_i = exp( int_0^T trace A(t) dt ),
    trace A = -trace( M^-1 (C + W G + C_t(t)) ),

so ``sum_i log|mu_i| = sum_i Re(lam_i) T`` must equal the integrated trace. The check costs
one trace (the ``k x k`` block of ``M^-1`` on the nonlinear DOFs against ``C_t`` at the
samples; nothing at all for a velocity-independent force, whose trace is constant).

Measure. :func:`liouville_error` returns

    e = | sum_i Re(lam_i) T - int_0^T trace A dt | / (2 n),

the mean error of ``log|mu_i|`` over the ``2 n`` multipliers. To first order
``d log|mu| = d|mu| / |mu|``, and ``|sum d_i| <= 2 n max |d_i|``: ``e`` is a *lower bound* on
the largest relative error of a multiplier's modulus. A check that fails
(``e > LIOUVILLE_TOL``) proves that some ``|mu_i|`` is wrong by more than the tolerance of
the stability decision; a check that passes proves nothing (the errors may cancel; Hsu's
product of exponentials satisfies the identity to round-off whatever its sampling error,
because ``det exp(Delta C_j) = exp(Delta trace C_j)`` exactly -- see
:mod:`~rotorsim.harmonic_balance.tangent_switches` for what catches those).

Hill's method gives the exponents themselves, so the check applies to its ``2 n``
selected exponents even when some multipliers underflow. The other methods give
``mu = eig(Phi)``, whose smallest eigenvalues are lost to round-off (relative error
``eps ||Phi|| / |mu|``): below :data:`RESOLVABLE` times the largest the sum of logarithms
means nothing, and the check returns NaN (not applicable). So does a Hill selection with
fewer than ``2 n`` exponents.

References
----------
J. Liouville, J. Math. Pures Appl. 3 (1838) 342-349 (Abel-Jacobi-Liouville identity);
E. A. Coddington, N. Levinson, *Theory of Ordinary Differential Equations*, McGraw-Hill
1955, chapter 1, theorem 7.3; M. Krack, J. Gross, *Harmonic Balance for Nonlinear Vibration
Problems*, Springer 2019, section 3.5 (its use as an accuracy check of Hill's method).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from rotorsim.errors import ConvergenceError
from rotorsim.harmonic_balance.floquet import FloquetResult
from rotorsim.harmonic_balance.fourier import FloatArray
from rotorsim.harmonic_balance.problem import HBProblem, as_dense
from rotorsim.solvers.linear import factorize

LIOUVILLE_TOL = 1e-5
"""Largest accepted :func:`liouville_error`: the default stability tolerance on
``|mu| - 1`` (``analyses.periodic.stability.DEFAULT_TOL``). A larger error proves a modulus
error larger than the margin the stability decision relies on."""
RESOLVABLE = 1e-8
"""Smallest ``|mu| / max |mu|`` for which ``log|mu|`` from ``eig(Phi)`` is trusted (an
eigenvalue ``1e-8`` times the largest keeps about 8 of 16 digits)."""


@dataclass(frozen=True, eq=False)
class TraceModel:
    """The constant parts of ``trace A`` of a problem (computed once, then per orbit only
    the nonlinear damping tangent).

    Attributes
    ----------
    problem : HBProblem
    """

    problem: HBProblem

    @cached_property
    def _parts(self) -> tuple[float, float, FloatArray] | None:
        pb = self.problem
        try:
            lu = factorize(pb.mass, where="mass matrix")
        except ConvergenceError:
            return None
        Minv = np.asarray(lu.solve(np.eye(pb.n)), dtype=float)
        C = 0.0 if pb.damping is None else float(np.sum(Minv * as_dense(pb.damping).T))
        G = 0.0 if pb.gyroscopic is None else float(np.sum(Minv * as_dense(pb.gyroscopic).T))
        return C, G, Minv[np.ix_(pb.nl_dofs, pb.nl_dofs)]

    @property
    def available(self) -> bool:
        """False for a singular mass matrix (no first-order form)."""
        return self._parts is not None

    def integral(self, omega: float, damping_tangents: FloatArray | None = None) -> float:
        """``int_0^T trace A dt`` [-] with ``C_t`` (S, k, k) at ``S`` equally spaced phases
        (trapezoidal rule, spectrally accurate for a smooth periodic ``C_t``; None: no
        velocity-dependent force). NaN for a singular mass matrix."""
        if self._parts is None:
            return math.nan
        C, G, B = self._parts
        T = 2.0 * math.pi / omega
        mean = C + self.problem.spin_speed(omega) * G
        if damping_tangents is not None and damping_tangents.size:
            mean += float(np.mean(np.einsum("ij,sji->s", B, damping_tangents)))
        return -T * mean


def liouville_error(result: FloquetResult, trace_integral: float, *,
                    size: int | None = None) -> float:
    """Mean error of ``log|mu|`` against Liouville's formula (module docstring).

    Parameters
    ----------
    result : FloquetResult
        Any method's multipliers; Hill's exponents are used directly.
    trace_integral : float
        ``int_0^T trace A dt`` along the orbit (:meth:`TraceModel.integral`).
    size : int, optional
        Expected number of multipliers ``2 n`` (a Hill selection may return fewer).

    Returns
    -------
    float
        ``e >= 0``, or NaN when the check does not apply (module docstring).

    Examples
    --------
    ``x'' + 0.1 x' + x = 0``: the exponents sum to ``-0.1``, so over ``T = 2 pi`` the trace
    integral is ``-0.2 pi``.

    >>> from rotorsim.harmonic_balance.floquet import floquet_result
    >>> lam = np.array([-0.05 + 0.99875j, -0.05 - 0.99875j])
    >>> fl = floquet_result(np.exp(2 * np.pi * lam), 1.0, "hsu", {})
    >>> liouville_error(fl, -0.2 * np.pi) < 1e-15
    True
    >>> round(liouville_error(fl, -0.2 * np.pi * 1.01), 6)   # 1 % off the trace: 2 pi 1e-3 / 2
    0.003142
    """
    mu = np.asarray(result.multipliers, dtype=complex)
    modulus = np.abs(mu)
    if not math.isfinite(trace_integral) or mu.size == 0 or mu.size % 2 \
            or (size is not None and mu.size != size):
        return math.nan
    if result.method == "hill":
        total = float(np.sum(np.asarray(result.exponents).real)) * result.period
    else:
        if modulus.min() < RESOLVABLE * modulus.max():
            return math.nan
        total = float(np.sum(np.log(modulus)))
    return abs(total - trace_integral) / mu.size
