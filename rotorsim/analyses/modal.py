"""Complex modal analysis of the damped gyroscopic rotor at one spin speed."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.mode_shapes import circularize, clusters, mode_kind, whirl_of
from rotorsim.analyses.system_input import as_system
from rotorsim.assembly.system import RotorSystem
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.results.modal import ModalResult
from rotorsim.solvers.eigen import DENSE_EIGEN_THRESHOLD, quadratic_eigen
from rotorsim.solvers.stats import Stats
from rotorsim.solvers.threads import one_blas_thread


@one_blas_thread()
def modal(
    rotor: Rotor | RotorSystem,
    speed: float = 0.0,
    num_modes: int = 12,
    *,
    sigma: float = -1.0,
    sparse: bool | None = None,
    rigid_tol: float | None = None,
    stats: Stats | None = None,
) -> ModalResult:
    """Natural frequencies, damping and complex mode shapes at spin speed ``speed``.

    Solves ``(lam^2 M + lam (C + W G) + K) x = 0`` with the bearing coefficients at ``W``.

    Parameters
    ----------
    rotor : Rotor or RotorSystem
        The model.
    speed : float
        Spin speed W [rad/s].
    num_modes : int
        Number of elastic modes to return (conjugate pairs count once).
    sigma : float
        Real shift [rad/s] of the eigen solver: modes nearest it are found. The default,
        slightly negative, finds the lowest modes and keeps the solve regular when the
        model has rigid-body modes.
    sparse : bool, optional
        Force sparse shift-invert (ARPACK) or dense (LAPACK); default by size.
    rigid_tol : float, optional
        Eigenvalues with ``|lam|`` below this [rad/s] are rigid-body modes; default
        ``1e-6 sqrt(max K_ii / max M_ii)``.

    Returns
    -------
    ModalResult

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(6)]
    >>> bearings = [rs.BearingElement(n=0, kxx=1e6), rs.BearingElement(n=6, kxx=1e6)]
    >>> m = rs.modal(rs.Rotor(shaft, [], bearings), speed=0.0, num_modes=4)
    >>> m.rigid_body_modes, m.kind[0]
    (2, 'lateral')
    """
    if num_modes < 1:
        raise ModelError(f"num_modes must be >= 1, got {num_modes}", "modal")
    if not np.isfinite(speed):
        raise ModelError(f"speed must be finite, got {speed}", "modal")
    system = as_system(rotor)
    own_stats = stats is None
    stats = Stats() if stats is None else stats
    mats = system.matrices(speed)
    _check_mass(system, mats.M)
    D = mats.C + speed * mats.G
    diag_k, diag_m = np.abs(mats.K.diagonal()), mats.M.diagonal()
    tol = rigid_tol if rigid_tol is not None else 1e-6 * np.sqrt(diag_k.max() / diag_m.max())

    n = system.n_free
    extra = 4
    while True:
        k = 2 * num_modes + extra
        pairs = quadratic_eigen(mats.M, D, mats.K, k, sigma=sigma, sparse=sparse, stats=stats)
        rigid = np.abs(pairs.values) < tol
        elastic = _elastic_indices(pairs.values, rigid)
        if elastic.size >= num_modes or pairs.values.size >= 2 * n - 2 or k >= 2 * n:
            break
        extra *= 2
    if elastic.size == 0:
        raise ConvergenceError("no elastic mode found", "modal", residual=None)
    elastic = elastic[:num_modes]
    lam = pairs.values[elastic]
    shapes = system.dof_map.expand(pairs.vectors[:, elastic])
    groups = clusters(lam)
    if groups:  # repeated eigenvalues: report circular forward/backward modes
        shapes = circularize(shapes, groups)
    shapes = _normalise(shapes)
    whirl, ratio, kind = _classify(system, shapes)
    rigid_shapes = _rigid_basis(system.dof_map.expand(pairs.vectors[:, rigid]))
    wn = np.abs(lam)
    wd = np.abs(lam.imag)
    with np.errstate(divide="ignore", invalid="ignore"):
        log_dec = np.where(wd > 0, -2.0 * np.pi * lam.real / wd, np.inf)
    use_sparse = n > DENSE_EIGEN_THRESHOLD if sparse is None else sparse
    options: dict[str, Any] = {"num_modes": num_modes, "sigma": sigma, "rigid_tol": tol,
                               "solver": "sparse" if use_sparse else "dense"}
    return ModalResult(
        speed=float(speed), eigenvalues=lam, wn=wn, wd=wd,
        damping_ratio=-lam.real / wn, log_dec=log_dec,
        whirl=whirl, whirl_ratio=ratio, kind=kind, mode_shapes=shapes,
        rigid_body_modes=rigid_shapes.shape[1], rigid_body_shapes=rigid_shapes,
        dof_map=system.dof_map, nodes_pos=system.nodes_pos, options=options,
        stats=stats.finish() if own_stats else {}, summary=system.summary,
    )


def _check_mass(system: RotorSystem, M) -> None:
    diag = M.diagonal()
    massless = np.flatnonzero(diag <= 0)
    if massless.size:
        full = system.dof_map.free[massless[0]]
        node, local = divmod(int(full), 6)
        raise ModelError(
            f"DOF {('ux', 'uy', 'uz', 'rx', 'ry', 'rz')[local]} of node {node} has no mass;"
            " add a PointMass/DiskElement there or fix the DOF",
            "modal",
        )


def _elastic_indices(values: NDArray[np.complex128], rigid: NDArray[np.bool_]) -> NDArray:
    """Indices of elastic modes (one per conjugate pair), sorted by |lam|."""
    scale = np.abs(values)
    positive = values.imag > 1e-9 * scale
    real = np.abs(values.imag) <= 1e-9 * scale
    keep = np.flatnonzero((positive | real) & ~rigid)
    return keep[np.argsort(scale[keep], kind="stable")]


def _normalise(shapes: NDArray[np.complex128]) -> NDArray[np.complex128]:
    out = shapes.copy()
    n_nodes = shapes.shape[0] // 6
    trans = shapes.reshape(n_nodes, 6, -1)[:, :3, :].reshape(n_nodes * 3, -1)
    for j in range(shapes.shape[1]):
        col = trans[:, j] if np.abs(trans[:, j]).max() > 0 else shapes[:, j]
        ref = col[np.argmax(np.abs(col))]
        out[:, j] = shapes[:, j] / ref
    return out


def _classify(system: RotorSystem, shapes: NDArray[np.complex128]):
    mass = system.dof_map.expand(system.pattern.matrix(system.structural_mass).diagonal())
    kind = mode_kind(mass, shapes)
    whirl, ratio = whirl_of(shapes)
    whirl = np.where(kind == "lateral", whirl, "none")
    return tuple(str(w) for w in whirl), ratio, tuple(str(k) for k in kind)


def _rigid_basis(vectors: NDArray[np.complex128]) -> NDArray[np.float64]:
    if vectors.shape[1] == 0:
        return np.zeros((vectors.shape[0], 0))
    real = np.hstack([vectors.real, vectors.imag])
    u, s, _ = np.linalg.svd(real, full_matrices=False)
    rank = int(np.sum(s > 1e-6 * s.max())) if s.size else 0
    return u[:, :rank]
