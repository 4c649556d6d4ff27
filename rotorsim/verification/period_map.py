"""The period map of a rotor, measured with the time integrator next to a periodic orbit.

A periodic orbit of period ``T`` is a fixed point ``z* = P(z*)`` of the period map ``P``
that takes the state ``z = (q, v)`` at ``t`` to the state at ``t + T``; its Floquet
multipliers are the eigenvalues of the monodromy matrix ``M = dP/dz (z*)`` (seed 002
section 3.5.3; Seydel 2010, *Practical Bifurcation and Stability Analysis*, section 7.1).
This module measures ``P`` with :func:`rotorsim.transient` on the full finite-element
model, a code path independent of harmonic balance and its Floquet methods, in two ways:

* :func:`linearised_growth` -- power iteration ``w_(k+1) = (P(z0 + h w_k) - P(z0)) / h``
  with ``w`` renormalised every period: ``|w_(k+1)| / |w_k|`` tends to the largest
  ``|mu|`` of the period map linearised at ``z0`` (the harmonic-balance state), one
  one-period transient per iteration;
* :func:`trajectory_growth` -- a free transient from ``z0`` and one from ``z0 + h w``:
  their difference ``d_k`` at ``t = k T`` grows or decays like ``max |mu|^k`` while both
  stay within the neighbourhood where ``P`` is linear.

Both give a sequence ``d_k`` (``k = 0..K``) that tends to ``M^k d_0``. The dominant
multipliers follow from it by a linear recurrence ``d_(k+1) = sum_i a_i d_(k+1-i)`` of
order ``p`` fitted by least squares over the second half of the sequence, all components
at once (Prony's method; a Krylov/Ritz estimate of the ``p`` multipliers that dominate
the sequence, :func:`dominant_multipliers`): a complex pair makes ``|d_k|`` beat over
tens of periods, which a growth ratio of norms cannot separate from growth or decay, but
a recurrence of order 2 fits exactly. The observed components are the lateral
translations ``ux, uy`` of all nodes, which the slow (critical) dynamics of a rotor
dominates.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.transient.speed_profile import ConstantSpeed
from rotorsim.analyses.transient.transient import transient
from rotorsim.assembly.system import RotorSystem
from rotorsim.options import Excitation, Output

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Growth:
    """Growth of a perturbation per period, measured with the time integrator.

    Attributes
    ----------
    multipliers : complex array (p,)
        The multipliers that dominate the sequence, by decreasing modulus
        (:func:`dominant_multipliers`).
    factors : array (K,)
        ``|d_(k+1)| / |d_k|`` of every period.
    periods : int
        Periods integrated (all transients of the measurement together).
    """

    multipliers: NDArray[np.complex128]
    factors: FloatArray
    periods: int

    @property
    def rho(self) -> float:
        """Estimate of ``max |mu|``, the growth per period [-]."""
        return float(np.abs(self.multipliers[0]))


@dataclass(frozen=True)
class PeriodMap:
    """The period map of a rotor at one constant speed, by :func:`rotorsim.transient`.

    Parameters
    ----------
    system : RotorSystem
        The assembled rotor with its nonlinear elements (all DOFs integrated).
    speed : float
        Constant spin speed [rad/s].
    period : float
        Period ``T`` of the orbit [s].
    excitation : Excitation
        Unbalance, gravity and constant loads (the same as the periodic run's).
    phi0 : float
        Shaft angle at the start of every run [rad].
    steps : int
        Time steps per period (constant step ``T / steps``).
    method : str
        A fixed-step method of :func:`rotorsim.transient` (default the non-dissipative
        average acceleration).
    """

    system: RotorSystem
    speed: float
    period: float
    excitation: Excitation
    phi0: float = 0.0
    steps: int = 200
    method: str = "average_acceleration"
    periods_run: list[int] = field(default_factory=list, compare=False, repr=False)

    def flow(self, q0: FloatArray, v0: FloatArray, periods: int
             ) -> tuple[FloatArray, FloatArray]:
        """States at ``t = k T``, ``k = 0..periods``: displacements and velocities on ALL
        DOFs, arrays (periods + 1, 6 n_nodes) [m, rad, m/s, rad/s]."""
        T = self.period
        res = transient(self.system, periods * T, T / self.steps,
                        speed=ConstantSpeed(self.speed, phi0=self.phi0),
                        excitation=self.excitation, initial=(q0, v0), method=self.method,
                        output=Output(every=self.steps, velocities=True))
        self.periods_run.append(periods)
        ndof = self.system.dof_map.ndof
        q = np.zeros((res.t.size, ndof))
        v = np.zeros((res.t.size, ndof))
        q[:, res.dofs], v[:, res.dofs] = res.q, res.v
        return q, v

    @property
    def translations(self) -> NDArray[np.int64]:
        """ALL-DOF indices of ``ux`` and ``uy`` of every node (the measured norm)."""
        n = self.system.dof_map.n_nodes
        return (6 * np.arange(n)[:, None] + np.array([0, 1])[None, :]).ravel()


def _norm(pm: PeriodMap, dq: FloatArray) -> float:
    return float(np.linalg.norm(dq[..., pm.translations]))


def dominant_multipliers(sequence: FloatArray, order: int = 2) -> NDArray[np.complex128]:
    """Multipliers that dominate a sequence ``d_k ~ M^k d_0``, by decreasing modulus.

    Fits ``d_(k+1) = a_1 d_k + ... + a_p d_(k+1-p)`` (``p = order``) by least squares over
    the second half of ``sequence`` (K + 1, n), all n components together, and returns the
    roots of ``z^p - a_1 z^(p-1) - ... - a_p`` (Prony's method).

    Examples
    --------
    >>> mu = 0.9 * np.exp(0.3j)                 # a decaying complex pair: |d_k| beats
    >>> k = np.arange(31)[:, None]
    >>> d = np.real(np.array([1.0, 2.0j]) * mu**k)
    >>> np.round(np.abs(dominant_multipliers(d)), 6)
    array([0.9, 0.9])
    """
    d = np.asarray(sequence, dtype=float)
    first = max(order, (d.shape[0] - 1) // 2)
    rows = np.arange(first, d.shape[0])            # predicted d_k
    A = np.stack([d[rows - i].ravel() for i in range(1, order + 1)], axis=1)
    a = np.linalg.lstsq(A, d[rows].ravel(), rcond=None)[0]
    roots = np.roots(np.concatenate([[1.0], -a]))
    return roots[np.argsort(-np.abs(roots))].astype(complex)


def linearised_growth(pm: PeriodMap, q0: FloatArray, v0: FloatArray,
                      direction: tuple[FloatArray, FloatArray], iterations: int,
                      order: int = 2) -> Growth:
    """Power iteration on the period map linearised at ``(q0, v0)`` by finite differences.

    ``direction`` = ``(dq, dv)`` on ALL DOFs is the first perturbation; its size is the
    finite-difference step (keep it small against the orbit, large against the Newton
    tolerance of the integrator). Costs ``iterations + 1`` one-period transients.
    """
    dq, dv = (np.asarray(d, dtype=float) for d in direction)
    size = _norm(pm, dq)
    qb, vb = pm.flow(q0, v0, 1)
    factors = np.empty(iterations)
    sequence = [dq[pm.translations] / size]
    for k in range(iterations):
        qp, vp = pm.flow(q0 + dq, v0 + dv, 1)
        dq, dv = qp[1] - qb[1], vp[1] - vb[1]
        grown = _norm(pm, dq)
        factors[k] = grown / size
        sequence.append(dq[pm.translations] * np.prod(factors[:k]) / size)
        dq, dv = dq * (size / grown), dv * (size / grown)
    return Growth(dominant_multipliers(np.array(sequence), order), factors,
                  iterations + 1)


def trajectory_growth(pm: PeriodMap, q0: FloatArray, v0: FloatArray,
                      direction: tuple[FloatArray, FloatArray], periods: int,
                      order: int = 2) -> tuple[Growth, FloatArray]:
    """Growth of the difference of two free transients, from ``(q0, v0)`` and from
    ``(q0, v0) + direction``, over ``periods`` periods.

    Returns the growth and the displacements of the first run at ``t = k T`` (periods + 1,
    6 n_nodes) [m, rad].
    """
    dq, dv = (np.asarray(d, dtype=float) for d in direction)
    qb, _ = pm.flow(q0, v0, periods)
    qp, _ = pm.flow(q0 + dq, v0 + dv, periods)
    sequence = (qp - qb)[:, pm.translations]
    sizes = np.linalg.norm(sequence, axis=1)
    factors = sizes[1:] / np.maximum(sizes[:-1], np.finfo(float).tiny)
    return Growth(dominant_multipliers(sequence, order), factors, 2 * periods), qb
