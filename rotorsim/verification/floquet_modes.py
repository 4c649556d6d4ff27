"""Floquet modes of a periodic branch: the multipliers with their eigenvectors, on all DOFs.

A branch of :func:`rotorsim.periodic` stores its Floquet multipliers but not their
eigenvectors. To check a bifurcation by time integration along its *critical mode*
(:mod:`rotorsim.verification.mode_growth`), this module rebuilds the branch's stability
model (the Craig-Bampton reduction of :mod:`rotorsim.analyses.periodic.stability`: the
nonlinear DOFs physical, the linear DOFs following the static constraint modes ``psi`` and
the fixed-interface modes ``phi`` below the branch's cutoff) and forms Hsu's discrete
transition matrix of a point (seed 002 eq 3.38, the "average" rule on the branch's HB time
grid, each step ``exp(Delta C_j)`` by scipy's ``expm``), the monodromy ``Phi`` that maps the
reduced state ``y = [q_r; v_r]`` at phase 0 to the state one period later.

* Right eigenvectors ``Phi r = mu r`` expand to all DOFs through the reduction basis
  ``T = [[I, 0], [psi, phi]]``: ``q = T q_r``, ``v = T v_r``.
* Left eigenvectors ``l^H Phi = mu l^H`` (the rows of ``V^-1``, ``l_i^H r_j = delta_ij``)
  give a mode's coordinate in any state: ``c = l^H [P q; P v]`` with the mass-weighted
  projection ``P = (T^T M T)^-1 T^T M`` onto the reduction basis. Along a linearised motion
  ``c_k = mu^k c_0`` for that mode alone: the other modes, neutral ones (``|mu| = 1``:
  rigid axial play, undamped modes) included, drop out by biorthogonality.

References
----------
Seed 002 section 3.5.2.2, eqs 3.37-3.38 (Hsu's method); R. R. Craig, M. C. C. Bampton,
AIAA J. 6 (1968) 1313-1319 (the reduction); Seydel (2010), *Practical Bifurcation and
Stability Analysis*, section 7.1 (monodromy, multipliers and their eigenvectors).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.periodic.stability import (
    CUTOFF_FACTOR,
    _fixed_interface_modes,
    stability_model,
)
from rotorsim.analyses.periodic.switching import rebuilt
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.monodromy import (
    PeriodicTangents,
    ordered_product,
    state_matrices,
)
from rotorsim.results.periodic import PeriodicResult
from rotorsim.solvers.linear import factorize
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True, eq=False)
class PointModes:
    """Floquet multipliers and eigenvectors of one branch point (reduced coordinates).

    Attributes
    ----------
    point : int
        Branch point.
    multipliers : complex array (2 n_s,)
        Eigenvalues of Hsu's monodromy, by decreasing modulus.
    right : complex array (2 n_s, 2 n_s)
        Right eigenvectors (columns), reduced state ``[q_r; v_r]``.
    left : complex array (2 n_s, 2 n_s)
        Left eigenvectors (rows) with ``left @ right = I``.
    """

    point: int
    multipliers: ComplexArray
    right: ComplexArray
    left: ComplexArray


class BranchModes:
    """The stability model of a branch, rebuilt, and the Floquet modes of its points.

    Parameters
    ----------
    model : Rotor, RotorSystem or Model
        The model the branch was traced on.
    result : PeriodicResult
        A branch with stability, all nodes kept.
    where : str
        Name for error messages.

    Raises
    ------
    ModelError
        When the model is not the branch's (:func:`~.switching.rebuilt`).
    """

    def __init__(self, model: Any, result: PeriodicResult, where: str) -> None:
        rb = rebuilt(model, result, (), Stats())
        o = result.options
        omega_max = float(np.max(result.fundamental))
        self.result = result
        self._rb = rb
        self._model = stability_model(rb.residual, "hsu", modes=o["stability_modes"],
                                      omega_max=omega_max, tol=float(o["stability_tol"]))
        cutoff = CUTOFF_FACTOR * rb.residual.harmonics * omega_max \
            if o["stability_modes"] == "auto" else None
        basis = _reduction_basis(rb.rp.problem, self._model.modes, cutoff, where)
        reduced = self._model.residual.problem
        _check_basis(basis, rb.rp.problem, reduced, where)
        ndof = rb.system.dof_map.ndof
        self.basis = np.zeros((ndof, basis.shape[1]))          # T on ALL DOFs
        self.basis[rb.dofs] = basis[rb.columns]
        M = sp.csr_matrix(rb.rp.problem.mass)
        projector = np.linalg.solve(np.asarray(basis.T @ (M @ basis)),
                                    np.asarray((M.T @ basis).T))
        self.projector = np.zeros((basis.shape[1], ndof))       # P on ALL DOFs
        self.projector[:, rb.dofs] = projector[:, rb.columns]

    @property
    def size(self) -> int:
        """Reduced DOFs ``n_s``."""
        return int(self.basis.shape[1])

    def at(self, point: int) -> PointModes:
        """Hsu's monodromy of branch point ``point`` and its eigen-decomposition."""
        residual = self._model.residual
        x = self._rb.unknowns(self.result, point)
        omega = float(self.result.fundamental[point])
        S = residual.samples
        tau = 2.0 * np.pi * np.arange(S) / S
        A = state_matrices(residual.problem,
                           PeriodicTangents.of(residual, self._model._unknowns(x, omega, 0.0),
                                               omega, 0.0), tau)
        A = 0.5 * (A + np.roll(A, -1, axis=0))
        step = 2.0 * np.pi / omega / S
        Phi = ordered_product(np.array([sl.expm(a * step) for a in A]))
        mu, V = sl.eig(Phi)
        order = np.lexsort((-mu.imag, -np.abs(mu)))
        mu, V = mu[order], V[:, order]
        return PointModes(point, mu, V, np.linalg.inv(V))

    def perturbation(self, modes: PointModes, j: int, size: float
                     ) -> tuple[FloatArray, FloatArray]:
        """Displacements and velocities on ALL DOFs [m, rad, m/s, rad/s] along the real
        part of mode ``j``, scaled to a largest translation of ``size`` [m]."""
        n = self.size
        r = modes.right[:, j] / modes.right[np.argmax(np.abs(modes.right[:n, j])), j]
        dq, dv = self.basis @ r[:n].real, self.basis @ r[n:].real
        translation = np.isin(np.arange(dq.size) % 6, (0, 1, 2))
        scale = size / max(float(np.max(np.abs(dq[translation]))), 1e-300)
        return scale * dq, scale * dv

    def coordinates(self, modes: PointModes, j: int, dq: FloatArray, dv: FloatArray
                    ) -> ComplexArray:
        """Coordinates ``c = l_j^H [P dq; P dv]`` of mode ``j`` in states (K, ALL DOFs)."""
        z = np.hstack((dq @ self.projector.T, dv @ self.projector.T))
        return np.asarray(z @ modes.left[j])

    def follow(self, unstable: PointModes, j: int, other: PointModes) -> int:
        """The mode of ``other`` whose displacement shape matches mode ``j`` of
        ``unstable`` best (largest modal assurance criterion in reduced coordinates)."""
        n = self.size
        ref = unstable.right[:n, j]
        shapes = other.right[:n]
        mac = np.abs(shapes.conj().T @ ref) ** 2 / (
            np.sum(np.abs(shapes) ** 2, axis=0) * np.vdot(ref, ref).real)
        return int(np.argmax(mac))


def _reduction_basis(problem: Any, modes: int, cutoff: float | None, where: str
                     ) -> FloatArray:
    """``T`` (n, n_s) of the stability model (identity for the full system)."""
    if modes < 0:
        return np.eye(problem.n)
    N, L = problem.nl_dofs, problem.linear_dofs
    K, M = sp.csr_matrix(problem.stiffness), sp.csr_matrix(problem.mass)
    K_LL = K[L][:, L]
    try:
        psi = -np.asarray(factorize(K_LL, where=where).solve(K[L][:, N].toarray()))
    except ConvergenceError as exc:
        raise ModelError("the linear part is singular with the nonlinear DOFs clamped",
                         where) from exc
    w2, phi = _fixed_interface_modes(K_LL, M[L][:, L], modes, cutoff)
    k = N.size
    T = np.zeros((problem.n, k + w2.size))
    T[N, np.arange(k)] = 1.0
    T[np.ix_(L, np.arange(k))] = psi
    T[np.ix_(L, k + np.arange(w2.size))] = phi
    return T


def _check_basis(T: FloatArray, problem: Any, reduced: Any, where: str) -> None:
    """The rebuilt basis reproduces the stability model's reduced stiffness and mass
    (to 1e-9 of their largest entry: the same factorisation and eigensolver on the same
    matrices; a sign flip of a fixed-interface mode would show as an O(1) error)."""
    for full, small in ((problem.stiffness, reduced.stiffness), (problem.mass, reduced.mass)):
        A = sp.csr_matrix(full)
        mine = np.asarray(T.T @ (A @ T))
        theirs = small.toarray() if sp.issparse(small) else np.asarray(small)
        if np.max(np.abs(mine - theirs)) > 1e-9 * np.max(np.abs(theirs)):
            raise ModelError("the rebuilt Craig-Bampton basis differs from the stability "
                             "model's", where)


__all__ = ["BranchModes", "PointModes"]
