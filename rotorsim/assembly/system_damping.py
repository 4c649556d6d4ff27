"""The modal damping matrix of an assembled machine (:mod:`rotorsim.model.damping`)."""

from __future__ import annotations

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.model.damping import MODAL_DAMPING_MAX_DOFS
from rotorsim.solvers.eigen import rounding_energy

FloatArray = NDArray[np.float64]


def modal_damping_matrix(M: sp.spmatrix, K: sp.spmatrix, ratios: tuple[float, ...],
                         where: str) -> FloatArray:
    """``M Phi diag(2 zeta_j omega_j) Phi^T M`` for the lowest elastic modes at rest.

    Parameters
    ----------
    M, K : sparse (n, n)
        Mass and constant stiffness on the free DOFs [kg, N/m].
    ratios : tuple of float
        ``zeta_j`` of the lowest elastic modes, in order of frequency [-].
    where : str
        Name of the model in error messages.

    Returns
    -------
    array (n, n)
        The damping matrix [N s/m]; mode ``j`` of ``(K, M)`` gets ``2 zeta_j omega_j`` on
        its modal coordinate and no other mode is touched (``Phi^T C Phi`` is diagonal).

    Raises
    ------
    ModelError
        Above :data:`~rotorsim.model.damping.MODAL_DAMPING_MAX_DOFS` free DOFs, when the
        mass matrix is not positive definite, or when the model has fewer elastic modes
        than ratios.
    """
    n = M.shape[0]
    if n > MODAL_DAMPING_MAX_DOFS:
        raise ModelError(f"modal damping makes a full {n} x {n} damping matrix; it is "
                         f"limited to {MODAL_DAMPING_MAX_DOFS} free DOFs (use Rayleigh "
                         "damping, alpha and beta, on larger models)", where)
    Md, Kd = M.toarray(), K.toarray()
    Kd = 0.5 * (Kd + Kd.T)  # the symmetric part (cross-coupled bearings excluded)
    try:
        w2, phi = sl.eigh(Kd, Md, check_finite=False)
    except np.linalg.LinAlgError:
        raise ModelError("modal damping needs a positive definite mass matrix: some free "
                         "DOF has stiffness but no mass", where) from None
    elastic = np.abs(w2) * np.einsum("ij,ij->j", phi, Md @ phi) > rounding_energy(phi, K)
    elastic &= w2 > 0
    index = np.flatnonzero(elastic)[: len(ratios)]
    if index.size < len(ratios):
        raise ModelError(f"{len(ratios)} modal damping ratios but only {index.size} elastic "
                         "modes", where)
    omega = np.sqrt(w2[index])
    left = Md @ phi[:, index]  # mass-normalised modes: phi^T M phi = I
    return np.asarray((left * (2.0 * np.asarray(ratios) * omega)) @ left.T)
