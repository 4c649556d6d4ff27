"""Campbell diagram: damped modes over a spin-speed grid, tracked through crossings.

Also holds the mode-shape tools shared with the critical-speed analyses: the modal
assurance criterion (:func:`mac`), the whirl classification of complex shapes
(:func:`whirl_of`) and the split of degenerate forward/backward pairs into circular
modes (:func:`circularize`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.linear.argument_checks import (
    NEGATIVE_SPEED_HINT,
    check_num_modes,
    check_sparse,
)
from rotorsim.analyses.linear.campbell_reduced import RESIDUAL_TOL, SpeedModes, reduced_modes
from rotorsim.analyses.linear.modal import _classify, _normalise, modal
from rotorsim.analyses.linear.mode_shapes import circularize, clusters, mac
from rotorsim.analyses.system_input import as_system
from rotorsim.assembly.system import RotorSystem
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.model.rotor import Rotor
from rotorsim.progress import with_progress
from rotorsim.results.campbell import CampbellResult
from rotorsim.solvers.stats import Stats
from rotorsim.solvers.threads import one_blas_thread

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

EXTRA_CANDIDATES = 4
"""Modes computed beyond ``num_modes`` at every speed, so tracks have candidates to follow."""
METHODS = ("auto", "reduced", "full")
REDUCED_MIN_DOFS = 300
"""``method="auto"`` reduces models with at least this many free DOFs: the basis of 20 or so
modes at two speeds has 50-70 columns, and projecting a smaller model gains little."""
_FIELDS = ("wd", "wn", "log_dec", "damping_ratio", "whirl_ratio", "tracking_mac")


@dataclass(frozen=True, eq=False)
class _Candidates:
    """Modes at one speed, degenerate clusters circularised."""

    eigenvalues: ComplexArray
    shapes: ComplexArray
    fields: dict[str, FloatArray]
    whirl: NDArray[np.str_]
    kind: NDArray[np.str_]


@checked_keywords
@one_blas_thread()
def campbell(
    rotor: Rotor | RotorSystem,
    speeds: ArrayLike,
    num_modes: int = 12,
    *,
    sparse: bool | None = None,
    sigma: float | None = None,
    on_failure: Literal["raise", "record"] = "raise",
    progress: bool = False,
    method: Literal["auto", "reduced", "full"] = "auto",
    tol: float = RESIDUAL_TOL,
) -> CampbellResult:
    """Campbell diagram: damped natural frequencies tracked over spin speed.

    The model is assembled once and ``num_modes + 4`` modes are computed at every speed
    (bearing coefficients at that speed). ``method="full"`` calls
    :func:`~rotorsim.analyses.linear.modal.modal` (one shift-invert ARPACK solve) at every
    speed. ``method="reduced"`` solves in full only at the first and last speeds and, at
    the others, projects the problem on the real basis their modes span, refined until
    every returned mode's relative residual in the full space,
    ``||P^-1 (lam^2 M + lam (C + W G) + K) x|| / ||x||`` (``P`` the shifted stiffness), is
    at most ``tol`` (:mod:`rotorsim.analyses.linear.campbell_reduced`); ``"auto"`` (the
    default) takes it for models of at least :data:`REDUCED_MIN_DOFS` free DOFs and three
    or more speeds (unless ``sparse=False``). Tracks start
    from the ``num_modes`` lowest modes at the first speed; at each next speed, tracks are
    matched to candidates by :func:`scipy.optimize.linear_sum_assignment` on the cost
    ``(1 - MAC) + |lam - lam_prev| / |lam_prev|`` (MAC of the complex shapes, relative
    change of the complex eigenvalue), so a column follows one physical mode through
    crossings (forward and backward modes are MAC-orthogonal) and veering.

    Degenerate eigenvalues (forward/backward pairs of an isotropic rotor at rest, or at
    every speed of a non-gyroscopic one) have an arbitrary eigenvector basis; each such
    cluster is first rotated to its circular forward and backward modes
    (:func:`circularize`), which are the limits of the branches at small speed, so the
    tracks leave a zero-speed pair along the correct forward and backward branches.

    Parameters
    ----------
    rotor : Rotor or RotorSystem
        The model.
    speeds : array_like (S,)
        Spin speeds [rad/s]: finite, non-negative (spin is about +z by convention; a
        reverse-spinning rotor is the same rotor seen from its other end, see
        :mod:`rotorsim.analyses.linear.argument_checks`) and strictly increasing.
    num_modes : int
        Number of tracks (elastic modes of all kinds; conjugate pairs count once), a
        positive integer. Tracks beyond the modes the model has hold ``NaN``, and
        ``notes`` says so.
    sparse : bool, optional
        Force the sparse (ARPACK) or dense eigen solver; default by model size.
    sigma : float, optional
        Real shift [rad/s] of the eigen solver; default scale-aware (see ``modal``).
    on_failure : {"raise", "record"}
        On a failed modal solve, raise :class:`~rotorsim.errors.ConvergenceError`, or
        record the speed's status and leave ``NaN`` in its row.
    progress : bool
        Show a tqdm progress bar.
    method : {"auto", "reduced", "full"}
        How the modes at each speed are found (above).
    tol : float
        Largest relative residual of a mode of the reduced method [-]; the default 1e-6
        keeps the eigenvalues within about 1e-10 (relative) of the full solve's
        (``docs/benchmarks.md``). The residuals are in ``stats["max_residual"]``.

    Returns
    -------
    CampbellResult

    Raises
    ------
    ModelError
        Empty, non-finite, negative or non-increasing speeds; ``num_modes < 1``; a bad
        ``on_failure``, ``method`` or ``tol``.
    ConvergenceError
        A modal solve failed and ``on_failure="raise"``.

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    >>> disk = rs.DiskElement.from_geometry(2, steel, width=0.07, i_d=0.05, o_d=0.35)
    >>> bearings = [rs.BearingElement(n=0, kxx=1e6), rs.BearingElement(n=4, kxx=1e6)]
    >>> c = campbell(rs.Rotor(shaft, [disk], bearings), [0.0, 200.0, 400.0], num_modes=4)
    >>> c.wd.shape, c.whirl[-1, :2].tolist()
    ((3, 4), ['forward', 'backward'])
    """
    grid = _check_inputs(speeds, num_modes, on_failure)
    sparse = check_sparse(sparse, "campbell")
    _check_method(method, tol)
    system = as_system(rotor)
    stats = Stats()
    reduced = method == "reduced" or (method == "auto" and grid.size >= 3
                                      and sparse is not False
                                      and system.n_free >= REDUCED_MIN_DOFS)
    solved: list[SpeedModes | Exception] = []
    info: dict[str, float] = {}
    if reduced:
        solved, info = reduced_modes(system, grid, num_modes + EXTRA_CANDIDATES, sigma=sigma,
                                     tol=tol, sparse=sparse, stats=stats)
    n_speeds = grid.size
    out = {name: np.full((n_speeds, num_modes), np.nan) for name in _FIELDS}
    whirl = np.full((n_speeds, num_modes), "", dtype="<U9")
    kind = np.full((n_speeds, num_modes), "", dtype="<U9")
    status = np.full(n_speeds, int(Status.OK), dtype=np.int64)
    previous: tuple[ComplexArray, ComplexArray] | None = None
    fewest = num_modes
    for i in with_progress(range(n_speeds), progress, desc="campbell", unit="speed"):
        try:
            if reduced:
                cand = _from_modes(system, solved[i])
            else:
                cand = _candidates(system, float(grid[i]), num_modes, sparse, sigma, stats)
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            if on_failure == "raise":
                raise ConvergenceError(f"modal analysis failed at speed {grid[i]:.6g} rad/s"
                                       f" ({exc})", "campbell", step=i) from exc
            status[i] = int(Status.NOT_CONVERGED if isinstance(exc, ConvergenceError)
                            else Status.FAILED)
            continue
        fewest = min(fewest, cand.eigenvalues.size)
        take, quality = _assign(previous, cand, num_modes)
        cols = np.flatnonzero(take >= 0)
        picked = take[cols]
        for name, values in cand.fields.items():
            out[name][i, cols] = values[picked]
        out["tracking_mac"][i, cols] = quality[cols]
        whirl[i, cols], kind[i, cols] = cand.whirl[picked], cand.kind[picked]
        lam = np.full(num_modes, np.nan, dtype=complex)
        lam[cols] = cand.eigenvalues[picked]
        shapes = np.zeros((cand.shapes.shape[0], num_modes), dtype=complex)
        shapes[:, cols] = cand.shapes[:, picked]
        if previous is not None:  # a track without a candidate keeps its last shape
            missing = take < 0
            lam[missing], shapes[:, missing] = previous[0][missing], previous[1][:, missing]
        previous = (lam, shapes)
    options: dict[str, Any] = {
        "num_modes": num_modes, "candidates": num_modes + EXTRA_CANDIDATES, "sparse": sparse,
        "sigma": sigma, "on_failure": on_failure,
        "method": "reduced" if reduced else "full", **({"tol": tol} if reduced else {}),
        "tracking": "Hungarian assignment on (1 - MAC) + relative eigenvalue change; "
                    "degenerate clusters split into circular forward/backward modes",
    }
    notes = () if fewest >= num_modes else (
        f"num_modes = {num_modes} asked, but the model has only {fewest} elastic modes at "
        "some speeds: the other tracks hold NaN there",)
    return CampbellResult(speeds=grid, whirl=whirl, kind=kind, status=status,
                          options=options, stats={**stats.finish(), **info},
                          summary=system.summary, notes=notes, **out)


def _check_method(method: str, tol: float) -> None:
    if method not in METHODS:
        raise ModelError(f"method must be one of {METHODS}, got {method!r}", "campbell")
    if isinstance(tol, bool) or not isinstance(tol, int | float) or not 0 < tol < 1:
        raise ModelError(f"tol must be a number in (0, 1), got {tol!r}", "campbell")


def _from_modes(system: RotorSystem, modes: SpeedModes | Exception) -> _Candidates:
    """Candidates from the eigenpairs of the reduced method, post-processed as
    :func:`~rotorsim.analyses.linear.modal.modal` does (circular pairs, normalised shapes,
    whirl and kind)."""
    if isinstance(modes, Exception):
        raise modes
    lam = modes.values
    shapes = system.dof_map.expand(modes.vectors)
    groups = clusters(lam)
    if groups:
        shapes = circularize(shapes, groups)
    shapes = _normalise(shapes)
    whirl, ratio, kind = _classify(system, shapes)
    wn, wd = np.abs(lam), np.abs(lam.imag)
    with np.errstate(divide="ignore", invalid="ignore"):
        log_dec = np.where(wd > 0, -2.0 * np.pi * lam.real / wd, np.inf)
    fields = {"wd": wd, "wn": wn, "log_dec": log_dec, "damping_ratio": -lam.real / wn,
              "whirl_ratio": np.asarray(ratio, dtype=float)}
    return _Candidates(lam, shapes, fields, np.array(whirl, dtype="<U9"),
                       np.array(kind, dtype="<U9"))


def _check_inputs(speeds: ArrayLike, num_modes: int, on_failure: str) -> FloatArray:
    where = "campbell"
    if on_failure not in ("raise", "record"):
        raise ModelError(f"on_failure must be 'raise' or 'record', got {on_failure!r}", where)
    check_num_modes(num_modes, where)
    try:
        grid = np.atleast_1d(np.asarray(speeds, dtype=float))
    except (TypeError, ValueError) as exc:
        raise ModelError(f"speeds must be numbers, got {speeds!r}", where) from exc
    if grid.ndim != 1 or grid.size == 0:
        raise ModelError("speeds must be a non-empty 1-D array", where)
    if not np.all(np.isfinite(grid)):
        raise ModelError(f"speeds must be finite; got {grid[~np.isfinite(grid)][:3]}", where)
    if np.any(grid < 0):
        raise ModelError(f"speeds must be >= 0 rad/s, got {grid[grid < 0][0]!r}: "
                         f"{NEGATIVE_SPEED_HINT}", where)
    if np.any(np.diff(grid) <= 0):
        raise ModelError("speeds must be strictly increasing", where)
    return grid


def _candidates(system: RotorSystem, speed: float, num_modes: int, sparse: bool | None,
                sigma: float | None, stats: Stats) -> _Candidates:
    res = modal(system, speed, num_modes + EXTRA_CANDIDATES, sigma=sigma, sparse=sparse,
                stats=stats)
    shapes = res.mode_shapes
    whirl = np.array(res.whirl, dtype="<U9")
    ratio = np.array(res.whirl_ratio, dtype=float)
    kind = np.array(res.kind, dtype="<U9")
    fields = {"wd": res.wd, "wn": res.wn, "log_dec": res.log_dec,
              "damping_ratio": res.damping_ratio, "whirl_ratio": ratio}
    return _Candidates(res.eigenvalues, shapes, fields, whirl, kind)


def _assign(previous: tuple[ComplexArray, ComplexArray] | None, cand: _Candidates,
            num_modes: int) -> tuple[NDArray[np.int64], FloatArray]:
    """Candidate index per track (-1 if none) and the MAC of each match."""
    n_cand = cand.eigenvalues.size
    take = np.full(num_modes, -1, dtype=np.int64)
    quality = np.full(num_modes, np.nan)
    if previous is None:
        first = min(num_modes, n_cand)
        take[:first] = np.arange(first)
        return take, quality
    lam_prev, shapes_prev = previous
    similarity = mac(shapes_prev, cand.shapes)
    scale = np.maximum(np.abs(lam_prev), 1e-300)[:, None]
    change = np.abs(cand.eigenvalues[None, :] - lam_prev[:, None]) / scale
    cost = (1.0 - similarity) + np.where(np.isfinite(change), change, 1e6)
    from scipy.optimize import linear_sum_assignment  # slow to import: on first use

    rows, cols = linear_sum_assignment(cost)
    take[rows] = cols
    quality[rows] = similarity[rows, cols]
    return take, quality
