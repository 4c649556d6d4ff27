"""Complex modal analysis of the damped gyroscopic rotor at one spin speed."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.linear.argument_checks import check_num_modes, check_sparse, check_speed
from rotorsim.analyses.linear.mode_shapes import (
    PURE_TILT,
    circularize,
    clusters,
    mode_kind,
    whirl_of,
)
from rotorsim.analyses.system_input import as_system
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import as_float_array
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.results.modal import ModalResult
from rotorsim.solvers.eigen import (
    DENSE_EIGEN_THRESHOLD,
    EigenPairs,
    quadratic_eigen,
    rounding_energy,
)
from rotorsim.solvers.stats import Stats
from rotorsim.solvers.threads import one_blas_thread


@checked_keywords
@one_blas_thread()
def modal(
    rotor: Rotor | RotorSystem,
    speed: float = 0.0,
    num_modes: int = 12,
    *,
    sigma: float | None = None,
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
        Spin speed W [rad/s], finite and >= 0 (spin about +z; see
        :mod:`rotorsim.analyses.linear.argument_checks` for why negative speeds are refused).
    num_modes : int
        Number of elastic modes to return (conjugate pairs count once), a positive
        integer. If the model has fewer (resolvable) modes, all are returned and
        ``notes`` says so.
    sigma : float, optional
        Real shift [rad/s] of the eigen solver: modes nearest it are found. The default,
        :func:`~rotorsim.solvers.eigen.default_shift`, is slightly negative and scaled to
        the model (``-1e-3 sqrt(min K_ii / M_ii)``, unaffected by stiff springs on a few
        DOFs): it finds the lowest modes and keeps the solve regular when the model has
        rigid-body modes.
    sparse : bool, optional
        Force sparse shift-invert (ARPACK) or dense (LAPACK); default by size.
    rigid_tol : float, optional
        Eigenvalues with ``|lam|`` below this [rad/s] are rigid-body modes. Default: a
        scale-free test per mode, ``|lam|^2 x^H M x <= 100 eps |x|^T |K| |x|`` (the
        elastic energy of the mode is at the rounding level of ``K x``), which does not
        depend on the stiffest spring of the model.

    Returns
    -------
    ModalResult

    Raises
    ------
    ModelError
        ``num_modes`` not a positive integer, a negative or non-finite speed, a non-finite
        ``sigma``, or a DOF without mass.
    ConvergenceError
        No elastic mode found, or the eigen solver failed.

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
    check_num_modes(num_modes, "modal")
    speed = check_speed(speed, "modal")
    sparse = check_sparse(sparse, "modal")
    if sigma is not None and (np.ndim(sigma) or not np.isfinite(
            as_float_array(sigma, "sigma", "modal")).all()):
        raise ModelError(f"sigma must be finite, got {sigma!r}", "modal")
    system = as_system(rotor)
    own_stats = stats is None
    stats = Stats() if stats is None else stats
    mats = system.matrices(speed)
    _check_mass(system, mats.M)
    D = mats.C + speed * mats.G

    n = system.n_free
    extra = 4
    while True:
        k = 2 * num_modes + extra
        pairs = quadratic_eigen(mats.M, D, mats.K, k, sigma=sigma, sparse=sparse, stats=stats)
        rigid, tol = _rigid(pairs.values, pairs.vectors, mats.M, mats.K, rigid_tol)
        elastic = _elastic_indices(pairs.values, rigid)
        if elastic.size >= num_modes or pairs.values.size < k or k >= 2 * n:
            break
        extra *= 2
    if elastic.size == 0:
        raise ConvergenceError("no elastic mode found", "modal", residual=None)
    notes = _shortfall(num_modes, elastic.size, pairs)
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
    options: dict[str, Any] = {"num_modes": num_modes, "sigma": pairs.sigma,
                               "rigid_tol": tol, "solver": "sparse" if use_sparse else "dense"}
    return ModalResult(
        speed=float(speed), eigenvalues=lam, wn=wn, wd=wd,
        damping_ratio=-lam.real / wn, log_dec=log_dec,
        whirl=whirl, whirl_ratio=ratio, kind=kind, mode_shapes=shapes,
        rigid_body_modes=rigid_shapes.shape[1], rigid_body_shapes=rigid_shapes,
        dof_map=system.dof_map, nodes_pos=system.nodes_pos, options=options,
        stats=stats.finish() if own_stats else {}, summary=system.summary, notes=notes,
    )


def _rigid(values: NDArray[np.complex128], vectors: NDArray[np.complex128], M: Any, K: Any,
           rigid_tol: float | None) -> tuple[NDArray[np.bool_], np.float64]:
    """Rigid-body mask of the eigenpairs and the threshold [rad/s] (the largest per-mode
    threshold of :data:`RIGID_ROUNDING` when ``rigid_tol`` is not given)."""
    if rigid_tol is not None:
        return np.abs(values) < rigid_tol, np.float64(rigid_tol)
    if values.size == 0:
        return np.zeros(0, dtype=bool), np.float64(0.0)
    kinetic = np.real(np.einsum("ij,ij->j", vectors.conj(), M @ vectors))
    threshold = np.sqrt(rounding_energy(vectors, K) / kinetic)  # |lam|^2 x^H M x = x^H K x
    return np.abs(values) <= threshold, np.float64(threshold.max())


def _shortfall(num_modes: int, found: int, pairs: EigenPairs) -> tuple[str, ...]:
    """A note when fewer than ``num_modes`` elastic modes exist or are resolved."""
    if found >= num_modes:
        return ()
    note = f"num_modes = {num_modes} asked, but the model has only {found} elastic modes"
    if pairs.unresolved:
        note = (f"num_modes = {num_modes} asked, but only {found} elastic modes are "
                f"resolved: {pairs.unresolved} eigenvalues of |lam| >= {pairs.limit:.3g} "
                "rad/s (penalty modes of near-rigid springs or massless DOFs) were left out")
    return (note,)


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
    """Each shape divided by its largest translation (by its largest entry when it has no
    translation beyond rounding, :data:`~rotorsim.analyses.linear.mode_shapes.PURE_TILT`),
    so that entry is 1."""
    n_nodes = shapes.shape[0] // 6
    trans = shapes.reshape(n_nodes, 6, -1)[:, :3, :].reshape(n_nodes * 3, -1)
    columns = np.arange(shapes.shape[1])
    ref_trans = trans[np.argmax(np.abs(trans), axis=0), columns]
    ref_all = shapes[np.argmax(np.abs(shapes), axis=0), columns]
    has_trans = np.abs(trans).max(axis=0, initial=0.0) > PURE_TILT * np.abs(shapes).max(
        axis=0, initial=0.0)
    return shapes / np.where(has_trans, ref_trans, ref_all)


def _classify(system: RotorSystem, shapes: NDArray[np.complex128]):
    kind = mode_kind(system.mass_diagonal, shapes)
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
