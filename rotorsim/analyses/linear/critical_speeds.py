"""Exact undamped synchronous critical speeds and the critical-speed map.

With damping dropped and the spin tied to the whirl frequency, ``W = w / k`` for an
excitation of order ``k``, the harmonic motion ``q = Re(x e^{i w t})`` of
``M q'' + W G q' + K q = 0`` satisfies

    ``(K - w^2 M + i w W G) x = (K - w^2 (M - (i / k) G)) x = 0``,

a linear generalised eigenproblem in ``mu = w^2`` whose right-hand matrix
``M - (i / k) G`` is Hermitian (``G`` is real skew-symmetric). Its real positive
eigenvalues give the critical speeds ``W = sqrt(mu) / k`` directly, with no speed grid.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.linear.argument_checks import check_num_modes, check_sparse
from rotorsim.analyses.linear.mode_shapes import circularize, clusters, mode_kind, whirl_of
from rotorsim.analyses.system_input import as_system
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.results.critical_speeds import (
    CriticalSpeeds,
    check_harmonic,
    check_whirl_filter,
)
from rotorsim.solvers.eigen import (
    DENSE_EIGEN_THRESHOLD,
    DENSE_SHIFT_FRACTION,
    RESOLUTION,
    SHIFT_FRACTION,
    default_shift,
    rounding_energy,
    start_vector,
)
from rotorsim.solvers.linear import factorize
from rotorsim.solvers.stats import Stats
from rotorsim.solvers.threads import one_blas_thread

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True, eq=False)
class _Modes:
    """Undamped synchronous modes with the bearing coefficients frozen at one speed."""

    w: FloatArray            # whirl frequencies [rad/s]
    shapes: ComplexArray     # (ndof, m)
    whirl: NDArray[np.str_]
    kind: NDArray[np.str_]

    def take(self, index: ArrayLike) -> _Modes:
        i = np.asarray(index, dtype=np.int64)
        return _Modes(self.w[i], self.shapes[:, i], self.whirl[i], self.kind[i])

    @staticmethod
    def join(parts: list[_Modes], ndof: int) -> _Modes:
        if not parts:
            return _Modes(np.zeros(0), np.zeros((ndof, 0), complex), np.zeros(0, "<U9"),
                          np.zeros(0, "<U9"))
        return _Modes(*(np.concatenate([getattr(p, f) for p in parts], axis=-1)
                        for f in ("w", "shapes", "whirl", "kind")))


@checked_keywords
@one_blas_thread()
def critical_speeds(
    rotor: Rotor | RotorSystem,
    harmonic: float = 1,
    num_modes: int = 8,
    *,
    whirl: Literal["forward", "backward"] | None = None,
    sparse: bool | None = None,
    sigma: float | None = None,
    spool: str | None = None,
) -> CriticalSpeeds:
    """Exact undamped critical speeds of order ``harmonic``, without a speed grid.

    Solves ``K x = w^2 (M - (i/k) G) x`` (damping dropped, ``k = harmonic``) and returns
    ``W = w / k`` for the real positive finite eigenvalues, lowest first. Dense LAPACK
    (QZ) for small models; for large ones, ARPACK in shift-invert mode about ``sigma``
    [rad^2/s^2] with one sparse LU of ``K - sigma (M - (i/k) G)``. Forward and backward
    modes are told apart by the whirl of their orbits (:func:`~rotorsim.results.orbits.ellipse`);
    degenerate pairs (non-gyroscopic rotors) are first split into circular modes.
    Cross-coupled bearing stiffness (``kxy``, ``kyx``) would make the pencil
    non-Hermitian, with no real undamped synchronous crossing. As in classical undamped
    critical-speed analysis, the cross-coupled terms are dropped for a :class:`Rotor`
    (recorded in ``options["cross_coupling"]``); use :func:`~rotorsim.campbell` and
    :meth:`CampbellResult.critical_speeds` for the damped, cross-coupled crossings. An
    assembled :class:`RotorSystem` with a non-symmetric stiffness is refused with a
    :class:`ModelError` because its bearings can no longer be separated.

    Bearings tabulated against speed make ``K`` and ``M`` depend on ``W``: the ``j``-th
    critical speed is then the fixed point ``W = Wc_j(W)``, where ``Wc_j(W)`` is the
    ``j``-th critical speed with the coefficients frozen at ``W``. It is found by Brent's
    method on ``[0, W_hi]`` (``W_hi`` beyond the end of the bearing tables, where the
    coefficients are held constant, so the bracket always holds). One fixed point is
    returned per ``j``, even if ``Wc_j(W) - W`` changes sign more than once.

    Parameters
    ----------
    rotor : Rotor or RotorSystem
        The model; damping coefficients are ignored.
    harmonic : float
        Excitation order ``k`` > 0 (1: synchronous unbalance).
    num_modes : int
        Number of critical speeds returned (after the ``whirl`` filter).
    whirl : {"forward", "backward"}, optional
        Keep only modes that whirl this way (forward-only is what unbalance excites on
        isotropic supports); a mode whose node orbits whirl both ways ("mixed", common on
        anisotropic supports) counts with its predominant direction (amplitude-weighted
        whirl ratio). ``None`` keeps all, axial and torsional modes included.
    sparse : bool, optional
        Force the sparse or dense eigen solver; default sparse above
        ``DENSE_EIGEN_THRESHOLD`` free DOFs.
    sigma : float, optional
        Shift [rad^2/s^2] of the eigen solver; default ``-1e-3 w_ref^2`` with ``w_ref^2 =
        min K_ii / M_ii`` (:func:`~rotorsim.solvers.eigen.default_shift`): slightly negative
        (rigid-body modes) and scaled to the model, unaffected by stiff springs on a few DOFs.
        Rigid-body modes are told apart by a scale-free test per mode (elastic energy at the
        rounding level of ``K x``, :func:`~rotorsim.solvers.eigen.rounding_energy`).
    spool : str, optional
        On a machine of several lines: the line whose ``harmonic``-th order excites, e.g.
        ``"HP"``. Its speed ratio ``r`` makes the excitation ``w = harmonic r W``: the
        critical speeds are the reference speeds ``W`` where a mode's frequency equals
        ``harmonic |r| W``. A counter-rotating spool (``r < 0``) excites in the backward
        sense, so its mode shapes are given at the positive frequency (conjugated) and
        its unbalance excites backward-whirling modes. ``excitation`` then tells, per
        mode, how strongly that spool's unbalance drives it.

    Returns
    -------
    CriticalSpeeds
        Sorted by speed, with ``mode`` the rank, ``log_dec`` NaN (undamped) and the mode
        shapes at the critical speeds.

    References
    ----------
    Friswell, Penny, Garvey, Lees (2010), *Dynamics of Rotating Machines*: undamped
    synchronous critical speeds from the eigenproblem with ``W = w`` substituted.

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(6)]
    >>> disk = rs.DiskElement.from_geometry(3, steel, width=0.07, i_d=0.05, o_d=0.28)
    >>> bearings = [rs.BearingElement(n=0, kxx=1e6), rs.BearingElement(n=6, kxx=1e6)]
    >>> cs = critical_speeds(rs.Rotor(shaft, [disk], bearings), num_modes=2, whirl="forward")
    >>> cs.whirl.tolist(), bool(cs.speed[0] < cs.speed[1])
    (['forward', 'forward'], True)
    """
    stats = Stats()
    dropped = False
    if isinstance(rotor, Rotor) and _cross_coupled(rotor):
        rotor = rotor.with_bearings([_direct_only(b) for b in rotor.bearing_elements])
        dropped = True
    system = as_system(rotor)
    K = system.matrices(0.0).K
    if abs(K - K.T).max() > 1e-12 * abs(K).max():
        raise ModelError("the stiffness matrix is not symmetric (cross-coupled bearings): "
                         "undamped critical speeds need the Rotor, whose cross-coupling is "
                         "then dropped, or use campbell(...).critical_speeds()",
                         "critical_speeds")
    ratio = 1.0 if spool is None else system.line_ratio(spool, "critical_speeds.spool")
    if ratio == 0.0:
        raise ModelError(f"line {spool!r} does not rotate (speed ratio 0): it excites no "
                         "critical speed", "critical_speeds.spool")
    result = solve_critical_speeds(system, harmonic, num_modes, whirl, True, sparse, sigma,
                                   stats, ratio=ratio)
    options = {**result.options, "cross_coupling": "dropped" if dropped else "none",
               "spool": spool, "speed_ratio": ratio}
    excitation = None if spool is None else spool_excitation(
        system, result.mode_shapes, spool, ratio)
    return dataclasses.replace(result, options=options, stats=stats.finish(),
                               excitation=excitation)


def spool_excitation(system: RotorSystem, shapes: ComplexArray | None, spool: str,
                     ratio: float) -> FloatArray:
    """How strongly an unbalance on ``spool`` drives each mode, 0 to 1.

    A unit unbalance at node ``n`` of a spool turning in the sense ``s = sign(r)`` is the
    rotating force ``F = (1, -i s)`` on ``(ux, uy)``; its modal force is ``x^H F =
    conj(x_x) - i s conj(x_y)``. It is largest (``|x_x| + |x_y|``) for a circular orbit
    whirling with the spool and vanishes for one whirling against it. The measure is the
    largest modal force over the spool's nodes divided by the largest ``|x_x| + |x_y|``
    over all nodes: 1 for a forward (with the spool) circular mode whose largest motion is
    on the spool, 0 for a mode the spool's unbalance cannot excite (whirling against it
    on isotropic supports, or confined to other lines).
    """
    if shapes is None or shapes.shape[1] == 0:
        return np.zeros(0)
    nodes = shapes.reshape(-1, 6, shapes.shape[1])
    ux, uy = nodes[:, 0, :], nodes[:, 1, :]
    modal = np.abs(ux.conj() - 1j * np.sign(ratio) * uy.conj())
    on_spool = system.line_node_mask(spool, "critical_speeds.spool")
    scale = np.max(np.abs(ux) + np.abs(uy), axis=0)
    return np.asarray(np.max(modal[on_spool], axis=0) / np.where(scale > 0, scale, 1.0))


def _cross_coupled(rotor: Rotor) -> bool:
    return any(np.any(b.coefficient(c, b.frequency if b.frequency is not None else 0.0) != 0)
               for b in rotor.bearing_elements for c in ("kxy", "kyx"))


def _direct_only(bearing: BearingElement) -> BearingElement:
    """Copy of ``bearing`` without cross-coupled stiffness."""
    return dataclasses.replace(bearing, kxy=0.0, kyx=0.0)


def solve_critical_speeds(system: RotorSystem, harmonic: float, num_modes: int,
                          whirl: str | None, gyroscopic: bool, sparse: bool | None,
                          sigma: float | None, stats: Stats, ratio: float = 1.0
                          ) -> CriticalSpeeds:
    """Undamped critical speeds of an assembled system (the engine of :func:`critical_speeds`
    and of the critical-speed map); ``gyroscopic=False`` drops ``G``. ``ratio`` is the
    signed speed ratio of the exciting spool: the excitation order is ``harmonic ratio``."""
    harmonic = check_harmonic(harmonic, "critical_speeds")
    k = harmonic * ratio
    check_whirl_filter(whirl, "critical_speeds")
    check_num_modes(num_modes, "critical_speeds")
    sparse = check_sparse(sparse, "critical_speeds")
    if sigma is not None and not np.isfinite(sigma):
        raise ModelError(f"sigma must be finite or None, got {sigma!r}", "critical_speeds")

    def solve(speed: float) -> _Modes:
        return _lowest(system, speed, k, gyroscopic, num_modes, whirl, sparse, sigma, stats)

    if system.variable_bearings and gyroscopic:
        modes = _fixed_points(system, solve, abs(k), num_modes)
        method = "fixed point W = Wc(W) on the bearing tables (Brent)"
    else:
        modes, method = solve(0.0), "direct"
    speeds, n = modes.w / abs(k), modes.w.size
    return CriticalSpeeds(
        speed=speeds, frequency=abs(k) * speeds, mode=np.arange(n, dtype=np.int64),
        whirl=modes.whirl, kind=modes.kind, log_dec=np.full(n, np.nan), harmonic=harmonic,
        mode_shapes=modes.shapes, dof_map=system.dof_map,
        options={"num_modes": num_modes, "whirl": whirl, "sparse": sparse, "sigma": sigma,
                 "gyroscopic": gyroscopic, "bearings": method},
        summary=system.summary,
    )


def _lowest(system: RotorSystem, speed: float, k: float, gyroscopic: bool, count: int,
            whirl: str | None, sparse: bool | None, sigma: float | None,
            stats: Stats) -> _Modes:
    """The ``count`` lowest synchronous modes passing the whirl filter (coefficients at
    ``speed``); more eigenvalues are requested until enough are found or none is left."""
    n = system.n_free
    use_sparse = n > DENSE_EIGEN_THRESHOLD if sparse is None else sparse
    n_eig = min(2 * count + 10, n - 2)
    while True:
        modes = _frozen_modes(system, speed, k, gyroscopic, n_eig if use_sparse else None,
                              sigma, stats)
        keep = np.ones(modes.w.size, dtype=bool)
        if whirl == "forward" and not gyroscopic:  # x/y line modes count, one per pair
            keep = (modes.kind == "lateral") & (modes.whirl != "backward")
        elif whirl is not None:
            # elliptical ("mixed") orbits on anisotropic supports count with the direction
            # in which they predominantly whirl
            ratio = whirl_of(modes.shapes)[1] if modes.w.size else np.zeros(0)
            sense = ratio > 0 if whirl == "forward" else ratio < 0
            keep = (modes.whirl == whirl) | ((modes.whirl == "mixed") & sense)
        index = np.flatnonzero(keep)[:count]
        if index.size >= count or not use_sparse or n_eig >= n - 2:
            return modes.take(index)
        n_eig = min(2 * n_eig, n - 2)


def _frozen_modes(system: RotorSystem, speed: float, k: float, gyroscopic: bool,
                  n_eig: int | None, sigma: float | None, stats: Stats) -> _Modes:
    """All resolved real positive eigenvalues (dense, ``n_eig=None``) or those among the
    ``n_eig`` nearest ``sigma`` of ``K x = mu (M - (i/k) G) x``, with classified shapes."""
    mats = system.matrices(speed)
    K = mats.K.astype(complex)
    B = (mats.M - (1j / k) * mats.G) if gyroscopic else mats.M.astype(complex)
    stats.eigen_solves += 1
    w_shift = default_shift(mats.M, mats.K)
    if n_eig is None:  # dense: invert about a larger shift, to resolve a wider band
        pivot = sigma if sigma is not None else -(w_shift * DENSE_SHIFT_FRACTION
                                                  / SHIFT_FRACTION) ** 2
        mu, vecs = _dense_shift_invert(K, B, pivot, stats)
        complete = np.ones(mu.size, dtype=bool)
    else:
        shift = sigma if sigma is not None else -w_shift**2 / SHIFT_FRACTION
        mu, vecs = _shift_invert(K, B, n_eig, shift, stats)
        radius = np.abs(mu - shift)  # a cluster cut at the edge of the window is dropped
        complete = radius < radius.max() * (1.0 - 10 * 1e-6)
    finite = np.isfinite(mu)
    real = finite & (np.abs(mu.imag) <= 1e-6 * np.abs(np.where(finite, mu, 0)))
    energy = np.abs(mu) * np.abs(np.einsum("ij,ij->j", vecs.conj(), B @ vecs))  # x^H K x
    elastic = energy > rounding_energy(vecs, mats.K)
    keep = np.flatnonzero(real & (mu.real > 0) & elastic & complete)
    keep = keep[np.argsort(mu.real[keep], kind="stable")]
    mu_real, shapes = mu.real[keep], system.dof_map.expand(vecs[:, keep])
    if k < 0:  # excited at w = k W < 0: the same motion at the positive frequency
        shapes = shapes.conj()
    shapes = circularize(shapes, clusters(mu_real))
    kind = mode_kind(system.dof_map.expand(mats.M.diagonal()), shapes)
    whirl = np.where(kind == "lateral", whirl_of(shapes)[0], "none").astype("<U9")
    return _Modes(np.sqrt(mu_real), shapes, whirl, kind)


def _dense_shift_invert(K: sp.csr_matrix, B: sp.csr_matrix, sigma: float, stats: Stats
                        ) -> tuple[ComplexArray, ComplexArray]:
    """Eigenvalues of ``K x = mu B x``: from the dense ``(K - sigma B)^-1 B`` where it
    resolves them, each accurate relative to its distance from ``sigma`` whatever the scale
    of the stiffest spring (see :mod:`rotorsim.solvers.eigen`); above that band, where
    ``mu`` dominates ``K`` and QZ is accurate, from QZ on ``(K, B)``."""
    lu = factorize((K - sigma * B).tocsc(), stats=stats, where="critical speeds shift-invert")
    T = lu.solve(B.toarray())
    nu, vecs = sl.eig(T, check_finite=False)
    resolved = np.abs(nu) > RESOLUTION * np.abs(T).sum(axis=0).max()
    mu, vecs = sigma + 1.0 / nu[resolved], vecs[:, resolved]
    if resolved.all():
        return mu, vecs
    limit = np.min(np.abs(sigma + 1.0 / nu[~resolved & (nu != 0)]), initial=np.inf)
    high, high_vecs = sl.eig(K.toarray(), B.toarray(), check_finite=False)
    above = np.isfinite(high) & (np.abs(high) >= limit)
    return np.concatenate([mu, high[above]]), np.hstack([vecs, high_vecs[:, above]])


def _shift_invert(K: sp.csr_matrix, B: sp.csr_matrix, n_eig: int, sigma: float,
                  stats: Stats) -> tuple[ComplexArray, ComplexArray]:
    n = K.shape[0]
    lu = factorize((K - sigma * B).tocsc(), stats=stats, where="critical speeds shift-invert")
    op = spl.LinearOperator((n, n), matvec=lambda x: lu.solve(B @ x), dtype=complex)
    try:
        nu, vecs = spl.eigs(op, k=n_eig, which="LM", ncv=min(n, max(2 * n_eig + 1, 40)),
                            v0=start_vector(n).astype(complex),
                            tol=1e-12, maxiter=5000)
    except spl.ArpackNoConvergence as exc:
        raise ConvergenceError(f"ARPACK did not converge ({exc})", "critical_speeds") from exc
    stats.iterations += 1
    return sigma + 1.0 / nu, vecs


def _fixed_points(system: RotorSystem, solve: Any, k: float, num_modes: int) -> _Modes:
    from scipy.optimize import brentq  # slow to import: on first use

    cache: dict[float, _Modes] = {}

    def frozen(speed: float) -> _Modes:
        if speed not in cache:
            cache[speed] = solve(speed)
        return cache[speed]

    def gap(speed: float, j: int) -> float:
        w = frozen(speed).w
        return float(w[j] / k - speed) if j < w.size else -speed

    end = max(float(b.frequency[-1]) for _, b in system.variable_bearings
              if b.frequency is not None)
    found = []
    for j in range(min(num_modes, frozen(0.0).w.size, frozen(end).w.size)):
        high = max(end, frozen(end).w[j] / k) * 1.001 + 1e-9
        root = brentq(gap, 0.0, high, args=(j,), xtol=1e-12 * high, rtol=1e-12)
        if abs(gap(root, j)) > 1e-6 * max(root, 1.0):
            raise ConvergenceError(f"critical speed {j} jumps at {root:.6g} rad/s: no fixed "
                                   "point (mode order changes there)", "critical_speeds",
                                   residual=abs(gap(root, j)))
        found.append(frozen(root).take([j]))
    modes = _Modes.join(found, system.dof_map.ndof)
    return modes.take(np.argsort(modes.w, kind="stable"))
