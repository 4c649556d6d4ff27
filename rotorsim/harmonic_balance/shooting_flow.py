"""The real trajectory of an :class:`~.problem.HBProblem` with its variational equations,
integrated over one period.

State ``y = [q; v]`` (2n,) of

    M q'' + (C + W G) q' + K q + r(q_nl, q_nl', tau, omega, p) = f(tau, omega, p),
    tau = omega t,

with ``f`` evaluated exactly in time (the ``excitation`` harmonics and the sampled ``load``
called at each phase, no Fourier truncation). Augmented with the monodromy matrix ``Phi``
(2n, 2n) of ``Phi' = A(t, y) Phi``, ``Phi(0) = I``, ``A`` the first-order Jacobian with the
*exact* force tangents ``dr/dq``, ``dr/dv`` of :meth:`HBProblem.nonlinear` at the current
state, and with ``s' = trace A`` (``s(T)`` is the integrated trace of Liouville's formula,
:mod:`~.liouville`). One right-hand side costs one force call on one sample and
``O(n^2 k + n^3)`` flops for ``A Phi``.

Stepper. scipy's DOP853 (explicit Runge-Kutta of order 8 with embedded error estimators of
orders 5 and 3, Hairer-Norsett-Wanner) under error control. Where a contact closes or
opens, ``f`` is continuous but ``A`` jumps; a step that straddles the jump commits a local
error ``O(h |Delta A| |Phi|)`` that the embedded estimate also sees, so the step is rejected
and shrunk until that error is below ``atol + rtol |z|``: each switch costs a few rejected
steps and leaves an error of the order of the tolerance (no event function is needed, which
an HBProblem's opaque force could not supply anyway). The tests confirm this against an
integration with event location at the contact. Because ``f`` is continuous across the
switch, the jump of ``A`` needs no saltation matrix (it is the identity); a force that
itself jumps (impacts, unregularised Coulomb friction) is outside this module.

References
----------
E. Hairer, S. P. Norsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
Springer 1993, section II.10 (DOP853) and section II.5-II.6 (variational equations).
R. Seydel, *Practical Bifurcation and Stability Analysis*, 3rd ed., Springer 2010, section
7.1 (shooting, monodromy by the variational equations). R. I. Leine, H. Nijmeijer,
*Dynamics and Bifurcations of Non-Smooth Mechanical Systems*, Springer 2004, chapter 3
(saltation matrices; identity for a continuous vector field).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.fourier import AFT, FloatArray
from rotorsim.harmonic_balance.problem import HBProblem, as_dense
from rotorsim.solvers.linear import factorize


@dataclass(frozen=True, eq=False)
class PeriodMap:
    """One period of the real trajectory and its monodromy matrix.

    Attributes
    ----------
    start, end : arrays (2n,)
        ``y(0)`` and ``y(T)`` (``[q; v]`` [m, m/s]).
    monodromy : array (2n, 2n)
        ``Phi(T) = d y(T) / d y(0)``.
    trace_integral : float
        ``int_0^T trace A dt`` along the trajectory.
    stats : dict
        ``steps``, ``rhs_evaluations``.
    """

    start: FloatArray
    end: FloatArray
    monodromy: FloatArray
    trace_integral: float
    stats: dict[str, float]


@dataclass(frozen=True, eq=False)
class FirstOrderFlow:
    """Right-hand side of the augmented first-order system at ``omega``, ``param``."""

    problem: HBProblem
    omega: float
    param: float = 0.0

    @cached_property
    def _matrices(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        pb = self.problem
        try:
            lu = factorize(pb.mass, where="mass matrix")
        except ConvergenceError as exc:
            raise ModelError("shooting needs a nonsingular mass matrix",
                             "shooting") from exc
        Minv = np.asarray(lu.solve(np.eye(pb.n)), dtype=float)
        D = as_dense(pb.damping_matrix(self.omega))
        return Minv, Minv @ as_dense(pb.stiffness), Minv @ D, Minv[:, pb.nl_dofs]

    @cached_property
    def _excitation(self) -> tuple[AFT, FloatArray] | None:
        coeff = self.problem.excitation
        if coeff is None:
            return None
        if callable(coeff):
            coeff = np.asarray(coeff(self.omega, self.param), dtype=float)
        coeff = np.asarray(coeff, dtype=float)
        if coeff.ndim != 2 or coeff.shape[1] != self.problem.n or coeff.shape[0] % 2 != 1:
            raise ModelError(f"needs shape (2m + 1, {self.problem.n}), got {coeff.shape}",
                             "HBProblem.excitation")
        return AFT((coeff.shape[0] - 1) // 2, coeff.shape[0]), coeff

    def external(self, t: float) -> FloatArray:
        """``M^-1 f(t)`` (n,) [m/s^2]."""
        pb, tau = self.problem, np.array([self.omega * t])
        f = np.zeros(pb.n)
        if self._excitation is not None:
            aft, coeff = self._excitation
            f += (aft.basis(tau) @ coeff)[0]
        if pb.load is not None:
            f += np.asarray(pb.load(tau, self.omega, self.param), dtype=float).reshape(-1)
        return self._matrices[0] @ f

    def rhs(self, t: float, z: FloatArray) -> FloatArray:
        """``z' `` for ``z = [q, v, Phi (row-major), s]`` (2n + 4n^2 + 1,)."""
        pb = self.problem
        n, nl = pb.n, pb.nl_dofs
        _, MK, MD, ME = self._matrices
        q, v = z[:n], z[n:2 * n]
        P = z[2 * n: 2 * n + 4 * n * n].reshape(2 * n, 2 * n)
        ev = pb.nonlinear(q[nl][None, :], v[nl][None, :], np.array([self.omega * t]),
                          self.omega, self.param)
        assert ev.dfdq is not None
        Kt, Ct = ev.dfdq[0], None if ev.dfdv is None else ev.dfdv[0]
        a = self.external(t) - MK @ q - MD @ v - ME @ ev.f[0]
        P1, P2 = P[:n], P[n:]
        dP2 = -MK @ P1 - MD @ P2 - ME @ (Kt @ P1[nl])
        trace = -float(np.trace(MD))
        if Ct is not None:
            dP2 -= ME @ (Ct @ P2[nl])
            trace -= float(np.sum(ME[nl] * Ct.T))
        return np.concatenate((v, a, P2.reshape(-1), dP2.reshape(-1), [trace]))

    def period(self, y0: FloatArray, *, rtol: float = 1e-10, scale: float | None = None,
               max_step: float | None = None, max_steps: int = 200_000) -> PeriodMap:
        """Integrate ``y`` and ``Phi`` from ``y0`` over ``[0, T]`` (module docstring).

        Parameters
        ----------
        y0 : array (2n,)
            ``[q; v]`` at ``t = 0`` [m, m/s].
        rtol : float
            Relative tolerance of DOP853.
        scale : float, optional
            Displacement scale [m] of the absolute tolerances (``atol = rtol scale`` on
            ``q``, ``rtol omega scale`` on ``v``; ``Phi`` and ``s`` are O(1) in units of
            ``1 / omega``). Default ``max(|q0|, |v0| / omega)`` (1 for a zero start).
        max_step : float, optional
            Largest step [s] (default ``T / 64``: no step can skip a short contact
            unseen).
        max_steps : int
            Accepted steps before :class:`~rotorsim.errors.ConvergenceError`.
        """
        from scipy.integrate import DOP853  # scipy.integrate only when shooting runs

        n, w = self.problem.n, self.omega
        T = 2.0 * math.pi / w
        y0 = np.asarray(y0, dtype=float).reshape(-1)
        if y0.shape != (2 * n,) or not np.all(np.isfinite(y0)):
            raise ModelError(f"needs 2n = {2 * n} finite values, got shape {y0.shape}",
                             "shooting initial state")
        size = float(max(np.abs(y0[:n]).max(), np.abs(y0[n:]).max() / w))
        s = scale if scale is not None else (size if size > 0 else 1.0)
        block = np.block([[np.ones((n, n)), np.full((n, n), 1.0 / w)],
                          [np.full((n, n), w), np.ones((n, n))]])
        atol = rtol * np.concatenate((np.full(n, s), np.full(n, w * s), block.reshape(-1),
                                      [1.0]))
        z0 = np.concatenate((y0, np.eye(2 * n).reshape(-1), [0.0]))
        solver = DOP853(self.rhs, 0.0, z0, T, rtol=rtol, atol=atol,
                        max_step=T / 64 if max_step is None else max_step)
        steps = 0
        while solver.status == "running":
            solver.step()
            steps += 1
            if solver.status == "failed" or steps > max_steps:
                raise ConvergenceError(f"DOP853 stopped at t = {solver.t:.6g} s of T = "
                                       f"{T:.6g} s: {solver.status}, {steps} steps",
                                       "shooting", step=steps)
        z = solver.y
        return PeriodMap(y0, z[:2 * n].copy(), z[2 * n: -1].reshape(2 * n, 2 * n).copy(),
                         float(z[-1]), {"steps": float(steps),
                                        "rhs_evaluations": float(solver.nfev)})
