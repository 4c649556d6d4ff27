"""The frequency drift of a Craig-Bampton model: its truncation error that grows with time.

The a-priori estimate of :mod:`~.exponential_reduction` (the interior static response to the
unbalance outside the kept modes) is what the dropped modes *ring* with once the unbalance
is switched on. A reduced model also has slightly wrong natural frequencies: the modes of
the rotor on its bearings (the bearings' tangent at the start in the linear part, as
exponential collocation has it) are Ritz approximations from the basis, each a little too
stiff. A mode set ringing at the start then drifts in phase against the full model's, and
its error grows with the length of the run,
``|A_m (e^{i w_m t} - e^{i (w_m + dw_m) t})| <= A_m min(2, dw_m t)``. On the ``issue14``
rotor of ``benchmarks/bench_transient.py`` (10 ms, 1.6 revolutions) this, not the ringing,
was most of the truncation error: 4 to 10 times the ringing estimate, largest at the bearings.

The estimate, for the reduced model's modes ``(lambda_m = w_m^2, y_m = T psi_m)`` with the
bearings' tangent ``K_t`` at the start:

* **frequency error.** ``y_m`` leaves the residual ``r_m = (K_t - lambda_m M) y_m``, which
  is orthogonal to the basis. To second order the true eigenvalue is lower by
  ``sum_j (phi_j^T r_m)^2 / (w_j^2 - lambda_m)`` over the dropped fixed-interface modes
  ``phi_j`` (the kept ones and the static vectors are orthogonal to ``r_m``); with
  ``w_j^2 - lambda_m`` taken as ``w_j^2`` it is ``r_i^T K_ii^-1 r_i`` on the interior DOFs,
  one solve with the interior factorisation already made for the ringing estimate
  (Rayleigh-Ritz perturbation: J. H. Wilkinson, *The Algebraic Eigenvalue Problem*, 1965,
  ch. 2; R. R. Craig, M. C. C. Bampton, AIAA J. 6 (1968) 1313 for the basis).
  ``dw_m = dlambda_m / (2 w_m)``;
* **amplitude.** The unbalance ``Re(f e^{i W t})`` switched on at the start sets mode ``m``
  ringing with ``a_m y_m``, ``c_m = y_m^T f e^{i phi_0} /
  (lambda_m - W^2)`` (the step of the cosine phase and the kick of the sine phase),
  times the largest weighted displacement of ``y_m``;
* the drift of DOF ``i`` is ``sum_m w_i |y_im| a_m min(2, dw_m T)`` over the elastic modes,
  ``a_m = |Re c_m| + (W / w_m) |Im c_m|`` (rigid-body modes, below 1e-4 of the highest
  frequency, are exact in the basis).

Gyroscopic and damping terms are left out of these modes (an estimate, not the motion).
On ``bench``, ``issue14`` and the small test rotor (every node, the reduced and the full
model both at rtol 1e-8), the ringing and drift estimates together were 1.3 to 5 times the
truncation error found relative to the stepper's motion scale (``docs/validation.md``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.linalg as sl

from rotorsim.assembly.reduction import ReducedBasis
from rotorsim.elements.base import FloatArray
from rotorsim.time_integration.local_tangent import LocalMatrix

RIGID = 1e-4
"""Modes below this fraction of the highest frequency are rigid-body modes (no drift)."""


def frequency_drift(basis: ReducedBasis, stiffness: Any, mass: Any, tangent: Any,
                    inner: np.ndarray, interior_lu: Any, load: np.ndarray, speed: float,
                    duration: float, weights: FloatArray) -> FloatArray:
    """The weighted displacement error [m] of each free DOF (n,) that the reduced model's
    frequency errors can cause over ``duration`` [s] (module docstring); ``inf`` at a
    resonance.

    Parameters
    ----------
    basis : ReducedBasis
        The Craig-Bampton basis ``T`` (n, m) on the free DOFs.
    stiffness, mass : sparse or array (n, n)
        The full model's linear stiffness [N/m] and mass [kg].
    tangent : LocalMatrix, sparse, array or None
        The bearings' stiffness tangent at the start [N/m].
    inner : int array
        The interior (non-boundary) free DOFs, the rows of ``interior_lu``.
    interior_lu : factorisation
        Of ``K_ii`` (``.solve`` of an (n_i, m) right-hand side).
    load : complex array (n,)
        The unbalance load ``f e^{i phi_0}`` at the start [N] (``Re(load e^{i W (t -
        t0)})`` acts on the rotor).
    speed : float
        ``W`` [rad/s].
    duration : float
        Length of the run [s].
    weights : array (n,)
        Weights of the free DOFs in the error (1 for translations, a length for rotations).
    """
    T = basis.T
    try:
        lam, psi, shift = ritz_modes(T, stiffness, mass, tangent, inner, interior_lu)
    except (sl.LinAlgError, ValueError):
        return np.full(T.shape[0], np.inf)
    w = np.sqrt(np.maximum(lam, 0.0))
    elastic = w > RIGID * float(w.max(initial=0.0))
    if not elastic.any():
        return np.zeros(T.shape[0])
    w, lam, psi, shift = w[elastic], lam[elastic], psi[:, elastic], shift[elastic]
    Y = T @ psi
    with np.errstate(divide="ignore", invalid="ignore"):
        c = (Y.T @ load) / (lam - speed * speed)
    ring = np.abs(c.real) + speed / w * np.abs(c.imag)
    phase = np.abs(shift) * duration / (2.0 * w)
    with np.errstate(invalid="ignore"):
        drift = (np.asarray(weights)[:, None] * np.abs(Y)) @ (ring * np.minimum(2.0, phase))
    return np.where(np.isfinite(drift), drift, np.inf)


def ritz_modes(T: FloatArray, stiffness: Any, mass: Any, tangent: Any, inner: np.ndarray,
               interior_lu: Any) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The undamped modes of the model reduced on ``T`` (n, m) with the bearings' tangent,
    and the second-order estimate of how much each eigenvalue exceeds the full model's
    (module docstring; arguments as for :func:`frequency_drift`).

    Returns
    -------
    lam : array (m,) [rad^2/s^2], ascending; psi : array (m, m), mass-normalised reduced
    modes; shift : array (m,) [rad^2/s^2], ``r_i^T K_ii^-1 r_i`` of each mode.

    Raises
    ------
    numpy.linalg.LinAlgError
        When the reduced mass is not positive definite.
    """
    KT = np.asarray(stiffness @ T)
    if isinstance(tangent, LocalMatrix):
        KT[tangent.dofs] += tangent.block @ T[tangent.dofs]
    elif tangent is not None:
        KT = KT + np.asarray(tangent @ T)
    MT = np.asarray(mass @ T)
    Kr, Mr = T.T @ KT, T.T @ MT
    lam, psi = sl.eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T), check_finite=False)
    residual = (KT @ psi - (MT @ psi) * lam)[inner]
    flex = np.asarray(interior_lu.solve(residual)).reshape(residual.shape)
    return lam, psi, np.einsum("ij,ij->j", residual, flex)
