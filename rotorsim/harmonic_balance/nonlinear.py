"""AFT of the nonlinear force: harmonics, analytic Jacobian and parameter derivatives.

From the coefficients ``X_nl`` (2H + 1, k) of the nonlinear DOFs:

1. time samples ``q = Gamma X_nl`` and ``v = omega Gamma nabla X_nl`` (inverse FFT);
2. one batched call of the force callback at the ``N`` phases;
3. ``F_nl = Gamma^+ f`` (FFT, seed 002 eqs 3.34-3.36) and the Jacobian

       dF_nl / dX_nl = Gamma^+ diag(K_t) Gamma + omega Gamma^+ diag(C_t) Gamma nabla

   assembled from the FFT of the tangent samples (:meth:`AFT.tangent_jacobian`), which is
   the closed form of the seed's element-by-element sums below eq 3.36;
4. ``dF_nl / domega = Gamma^+ (C_t Gamma nabla X_nl)`` (velocity dependence, analytic) plus,
   if the force depends explicitly on ``omega``, a central difference of the callback;
5. ``dF_nl / dp`` by a central difference of the callback (no tangents requested).

References
----------
Seed 002 section 3.5.2.1, eqs 3.34-3.36 and the Jacobian blocks that follow them.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from rotorsim.harmonic_balance.fourier import AFT, FloatArray, derivative
from rotorsim.harmonic_balance.problem import HBProblem

FD_STEP = 6e-6
"""Relative step of the central differences (about ``eps**(1/3)``: truncation and round-off
errors balance at relative size ``eps**(2/3) ~ 4e-11``)."""


@dataclass(frozen=True, eq=False)
class NonlinearHarmonics:
    """The nonlinear force in the frequency domain.

    Attributes
    ----------
    force : array (2H + 1, k)
        Coefficients of ``f`` [N].
    jacobian : array ((2H + 1) k, (2H + 1) k) or None
        ``dF / dX_nl`` (harmonic-major).
    velocity_jacobian : array ((2H + 1) k, (2H + 1) k) or None
        ``Gamma^+ diag(C_t) Gamma`` (without ``nabla`` and ``omega``), used by Hill's method.
    d_omega : array (2H + 1, k) or None
        ``dF / domega`` at fixed ``X_nl``.
    """

    force: FloatArray
    jacobian: FloatArray | None = None
    velocity_jacobian: FloatArray | None = None
    d_omega: FloatArray | None = None


def step_size(value: float, scale: float = 1.0) -> float:
    """Central-difference step ``FD_STEP * max(|value|, scale)``."""
    return FD_STEP * max(abs(value), scale)


def nonlinear_harmonics(problem: HBProblem, aft: AFT, Xn: FloatArray, omega: float,
                        param: float, *, jacobian: bool = True, d_omega: bool = False,
                        velocity_jacobian: bool = False) -> NonlinearHarmonics:
    """AFT of the force at the nonlinear-DOF coefficients ``Xn`` (2H + 1, k).

    Examples
    --------
    ``f = q^3`` at ``q = cos tau`` gives ``3/4 cos tau + 1/4 cos 3 tau``:

    >>> from rotorsim.harmonic_balance.problem import HBProblem
    >>> cubic = lambda q, v, tau, w, p: (q**3, 3 * q[:, :, None]**2, None)
    >>> pb = HBProblem(np.eye(1), np.eye(1), nl_dofs=[0], force=cubic)
    >>> out = nonlinear_harmonics(pb, AFT(3), np.array([[0], [1], [0], [0], [0], [0], [0.]]),
    ...                           1.0, 0.0)
    >>> (np.round(out.force.ravel(), 12) + 0.0).tolist()
    [0.0, 0.75, 0.0, 0.0, 0.0, 0.25, 0.0]
    """
    k = problem.k
    rows = aft.rows
    if problem.force is None:
        zero_j = np.zeros((rows * k, rows * k))
        return NonlinearHarmonics(np.zeros((rows, k)), zero_j if jacobian else None,
                                  zero_j if velocity_jacobian else None,
                                  np.zeros((rows, k)) if d_omega else None)
    dX = derivative(Xn)
    q, dq = aft.to_time(Xn), aft.to_time(dX)
    ev = problem.nonlinear(q, omega * dq, aft.tau, omega, param,
                           tangents=jacobian or d_omega or velocity_jacobian)
    J = Jv = None
    if jacobian:
        assert ev.dfdq is not None
        J = aft.tangent_jacobian(ev.dfdq)
        if ev.dfdv is not None:
            J += omega * aft.tangent_jacobian(ev.dfdv, derivative=True)
    if velocity_jacobian:
        Jv = (np.zeros((rows * k, rows * k)) if ev.dfdv is None
              else aft.tangent_jacobian(ev.dfdv))
    dw = None
    if d_omega:
        dw = np.zeros((rows, k))
        if ev.dfdv is not None:
            dw += aft.to_frequency(np.einsum("sij,sj->si", ev.dfdv, dq))
        if problem.force_uses_omega:
            dw += aft.to_frequency(central_difference(
                lambda h: problem.nonlinear(q, omega * dq, aft.tau, omega + h, param,
                                            tangents=False).f, step_size(omega)))
    return NonlinearHarmonics(aft.to_frequency(ev.f), J, Jv, dw)


def nonlinear_param_derivative(problem: HBProblem, aft: AFT, Xn: FloatArray, omega: float,
                               param: float) -> FloatArray:
    """``dF_nl / dp`` (2H + 1, k) by central differences of the callback at fixed ``Xn``."""
    if problem.force is None:
        return np.zeros((aft.rows, problem.k))
    q, v = aft.to_time(Xn), omega * aft.to_time(derivative(Xn))
    df = central_difference(
        lambda h: problem.nonlinear(q, v, aft.tau, omega, param + h, tangents=False).f,
        step_size(param, problem.param_scale))
    return aft.to_frequency(df)


def excitation_derivatives(problem: HBProblem, aft: AFT, omega: float, param: float, *,
                           d_omega: bool, d_param: bool) -> tuple[FloatArray, FloatArray]:
    """``dF_ext / domega`` and ``dF_ext / dp`` (2H + 1, n) by central differences.

    Zero (no callback evaluated) for a constant ``excitation`` array without ``load``, and
    for a derivative not requested.
    """
    zero = np.zeros((aft.rows, problem.n))
    if problem.load is None and not callable(problem.excitation):
        return zero, zero
    dw = dp = zero
    if d_omega:
        dw = central_difference(
            lambda h: problem.excitation_coefficients(aft, omega + h, param), step_size(omega))
    if d_param:
        dp = central_difference(
            lambda h: problem.excitation_coefficients(aft, omega, param + h),
            step_size(param, problem.param_scale))
    return dw, dp


def central_difference(fun: Callable[[float], FloatArray], h: float) -> FloatArray:
    """``(fun(h) - fun(-h)) / (2 h)``."""
    return (fun(h) - fun(-h)) / (2.0 * h)
