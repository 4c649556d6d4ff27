"""Steady-state harmonic response: unbalance response and receptance (frequency response).

Both solve ``(K(W) - w^2 M + i w (C(W) + W G)) X = F`` for ``x(t) = Re(X e^{i w t})``, the
steady state of ``M q'' + (C + W G) q' + K q = Re(F e^{i w t})``. Each frequency needs one
sparse complex LU of the dynamic stiffness, solved for all right-hand sides at once.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.linear.argument_checks import check_speed
from rotorsim.analyses.rigid_motions import free_rigid_motions, held_dofs
from rotorsim.analyses.system_input import as_system
from rotorsim.assembly.loads import nodal_load, spool_groups, unbalance_amplitudes
from rotorsim.assembly.system import RotorSystem, SystemMatrices
from rotorsim.elements.base import as_float_array
from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.model.rotor import Rotor
from rotorsim.progress import with_progress
from rotorsim.results.frequency_response import FrequencyResponseResult
from rotorsim.solvers.linear import factorize
from rotorsim.solvers.stats import Stats
from rotorsim.solvers.threads import one_blas_thread

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
_ON_FAILURE = ("raise", "record")


@checked_keywords
def unbalance_response(
    rotor: Rotor | RotorSystem,
    speeds: ArrayLike,
    unbalance: Sequence[tuple[int, float, float]],
    *,
    progress: bool = False,
    on_failure: str = "raise",
) -> FrequencyResponseResult:
    """Synchronous response to an unbalance distribution at each spin speed.

    At every speed ``W`` the excitation frequency is ``w = W`` and the force on ``(ux, uy)``
    of each unbalanced node is ``me W^2 [cos(W t + a), sin(W t + a)]``.

    Parameters
    ----------
    rotor : Rotor or RotorSystem
        The model.
    speeds : array (F,)
        Spin speeds [rad/s], finite and >= 0.
    unbalance : list of (node, magnitude, phase)
        Node, mass-eccentricity product [kg m] and angle [rad] of each unbalance.
    progress : bool
        Show a progress bar (needs tqdm).
    on_failure : {"raise", "record"}
        On a singular dynamic stiffness (undamped resonance hit exactly) raise
        :class:`ConvergenceError`, or record NaN with ``Status.FAILED`` for that point.
        At ``W = 0`` the unbalance force vanishes and the response is exactly zero, also
        for a rotor with free axial or torsional motion (no solve is made there).

    Returns
    -------
    FrequencyResponseResult
        One input column (the whole distribution); amplitudes in [m] and [rad].

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    >>> bearings = [rs.BearingElement(n=0, kxx=1e7, cxx=1e3), rs.BearingElement(n=4, kxx=1e7,
    ...             cxx=1e3)]
    >>> rotor = rs.Rotor(shaft, [rs.DiskElement(n=2, m=20.0, Id=0.1, Ip=0.2)], bearings)
    >>> r = unbalance_response(rotor, [100.0, 200.0], [(2, 1e-4, 0.0)])
    >>> r.response.shape, r.stats["factorizations"]
    ((2, 30, 1), 2)
    >>> bool(r.orbit(2).whirl_ratio[0] > 0.99)   # isotropic supports: forward circle
    True
    """
    system = as_system(rotor)
    w = _frequencies(speeds, "speeds")
    base = unbalance_amplitudes(system, unbalance)[:, None]
    options = {"unbalance": [tuple(u) for u in unbalance]}
    spools = spool_groups(system, unbalance)
    if list(spools) == [1.0]:
        labels = tuple(f"unbalance {me:g} kg m at node {n}, {a:g} rad"
                       for n, me, a in unbalance)
        return _harmonic_sweep(
            system, w, w, lambda i: base * w[i] ** 2, kind="unbalance",
            inputs=("; ".join(labels),), progress=progress, on_failure=on_failure,
            options=options)
    parts = [_spool_sweep(system, w, ratio, items, progress, on_failure, options)
             for ratio, items in spools.items()]
    return combine_spools(parts, np.array(list(spools), dtype=float))


def _spool_sweep(system: RotorSystem, speeds: FloatArray, ratio: float,
                 items: list[tuple[int, float, float]], progress: bool, on_failure: str,
                 options: dict[str, Any]) -> FrequencyResponseResult:
    """Response to the unbalance of one spool: it turns at ``ratio W``, so its unbalance
    force ``me (r W)^2`` rotates at the signed frequency ``w = r W`` (backwards in the
    fixed frame for a counter-rotating spool), while the gyroscopic terms of every line
    follow the reference speed ``W``."""
    base = unbalance_amplitudes(system, items)[:, None]
    w = ratio * speeds
    labels = "; ".join(f"unbalance {me:g} kg m at node {n}, {a:g} rad" for n, me, a in items)
    result = _harmonic_sweep(
        system, w, speeds, lambda i: base * w[i] ** 2, kind="unbalance",
        inputs=(f"spool at {ratio:g}X: {labels}",), progress=progress, on_failure=on_failure,
        options=options)
    if ratio > 0:
        return result
    # the same motion written at the positive frequency |w|: Re(X e^{iwt}) = Re(X* e^{i|w|t})
    return dataclasses.replace(result, frequencies=np.abs(w), response=result.response.conj())


def combine_spools(parts: list[FrequencyResponseResult], ratios: FloatArray
                   ) -> FrequencyResponseResult:
    """One result with an input column per spool; ``frequencies`` is the reference speed and
    column ``k`` responds at ``ratios[k]`` times it (:attr:`input_ratios`)."""
    first = parts[0]
    status = np.max(np.stack([p.point_status for p in parts]), axis=0)
    stats = {key: float(sum(p.stats.get(key, 0.0) for p in parts)) for key in first.stats}
    return FrequencyResponseResult(
        frequencies=first.speeds, speeds=first.speeds,
        response=np.concatenate([p.response for p in parts], axis=2),
        dof_map=first.dof_map, nodes_pos=first.nodes_pos,
        inputs=tuple(p.inputs[0] for p in parts), kind="unbalance", point_status=status,
        options=first.options, stats=stats,
        status=Status.FAILED if np.any(status != Status.OK) else Status.OK,
        summary=first.summary, input_ratios=ratios)


@checked_keywords
def frequency_response(
    rotor: Rotor | RotorSystem,
    frequencies: ArrayLike,
    inputs: Sequence[tuple[int, str]],
    *,
    speed: float | None = None,
    progress: bool = False,
    on_failure: str = "raise",
) -> FrequencyResponseResult:
    """Receptance columns: response of every DOF to unit harmonic forces or moments.

    Parameters
    ----------
    rotor : Rotor or RotorSystem
        The model.
    frequencies : array (F,)
        Excitation frequencies w [rad/s], finite and >= 0.
    inputs : list of (node, dof)
        Where each unit force (``ux, uy, uz`` [N]) or moment (``rx, ry, rz`` [N m]) acts.
    speed : float, optional
        Fixed spin speed W [rad/s], finite and >= 0 (see
        :mod:`rotorsim.analyses.linear.argument_checks`); ``None`` means synchronous excitation
        (W = w).
    progress, on_failure
        As in :func:`unbalance_response`.

    Returns
    -------
    FrequencyResponseResult
        ``response[:, j, k]`` is the receptance ``H_jk(w)`` [m/N, rad/N, m/(N m), ...].

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    >>> bearings = [rs.BearingElement(n=0, kxx=1e7, cxx=1e3), rs.BearingElement(n=4, kxx=1e7,
    ...             cxx=1e3)]
    >>> rotor = rs.Rotor(shaft, [], bearings).without_axial_torsion()
    >>> h = frequency_response(rotor, [10.0, 20.0], [(1, "ux"), (3, "ux")], speed=0.0)
    >>> bool(np.allclose(h.complex(3, "ux", input=0), h.complex(1, "ux", input=1)))
    True
    """
    system = as_system(rotor)
    w = _frequencies(frequencies, "frequencies")
    if speed is None:
        spins = w
    else:
        spins = np.full_like(w, check_speed(speed, "frequency_response"))
    if isinstance(inputs, str) or not isinstance(inputs, Sequence) or not inputs:
        raise ModelError("give a non-empty list of (node, dof)", "inputs")
    columns = []
    for i, item in enumerate(inputs):
        if not isinstance(item, Sequence) or isinstance(item, str) or len(item) != 2:
            raise ModelError(f"expected (node, dof), got {item!r}", f"inputs[{i}]")
        columns.append(nodal_load(system, item[0], item[1], 1.0, where=f"inputs[{i}]"))
    rhs = np.stack(columns, axis=1).astype(complex)
    return _harmonic_sweep(
        system, w, spins, lambda i: rhs, kind="receptance",
        inputs=tuple(f"unit {'force' if d[0] == 'u' else 'moment'} {d} at node {n}"
                     for n, d in inputs),
        progress=progress, on_failure=on_failure,
        options={"inputs": [tuple(x) for x in inputs], "speed": speed},
    )


def _frequencies(values: ArrayLike, name: str) -> FloatArray:
    arr = np.atleast_1d(as_float_array(values, "values", name))
    if arr.ndim != 1 or arr.size == 0:
        raise ModelError(f"must be a non-empty 1-D array [rad/s], got shape {arr.shape}", name)
    bad = np.flatnonzero(~np.isfinite(arr) | (arr < 0))
    if bad.size:
        raise ModelError(f"value {float(arr[bad[0]])} at index {bad[0]} is not finite and "
                         ">= 0", name)
    return arr


def _dynamic_stiffness(
    system: RotorSystem, mats: SystemMatrices, w: float, spin: float
) -> sp.csr_matrix:
    """``K - w^2 M + i w (C + W G)`` as one CSR matrix on the shared sparsity pattern.

    All four matrices come from ``system.pattern``, so their data arrays align entry by entry
    and the combination is a single vectorised sum (no sparse-sparse additions).
    """
    parts = (mats.K, mats.M, mats.C, mats.G)
    if any(m.data.size != system.pattern.nnz for m in parts):  # not on the shared pattern
        return (mats.K - w**2 * mats.M + 1j * w * (mats.C + spin * mats.G)).tocsr()
    data = (mats.K.data - w**2 * mats.M.data) + 1j * w * (mats.C.data + spin * mats.G.data)
    return system.pattern.matrix(data)


@one_blas_thread()
def _harmonic_sweep(
    system: RotorSystem,
    w: FloatArray,
    spins: FloatArray,
    rhs: Callable[[int], ComplexArray],
    *,
    kind: str,
    inputs: tuple[str, ...],
    progress: bool,
    on_failure: str,
    options: dict[str, Any],
) -> FrequencyResponseResult:
    """Factorise the dynamic stiffness once per frequency and solve for all inputs."""
    if on_failure not in _ON_FAILURE:
        raise TypeError(f"on_failure must be one of {_ON_FAILURE}, got {on_failure!r}")
    stats = Stats()
    dof_map = system.dof_map
    n_inputs = rhs(0).shape[1]
    response = np.zeros((w.size, dof_map.ndof, n_inputs), dtype=complex)
    status = np.full(w.size, int(Status.OK), dtype=np.int64)
    speed_dependent = bool(system.variable_bearings)
    mats = system.matrices(float(spins[0]))
    for i in with_progress(range(w.size), progress, desc=kind, unit="pt"):
        if speed_dependent and (i == 0 or spins[i] != spins[i - 1]):
            mats = system.matrices(float(spins[i]))
        where = f"{kind} at w = {w[i]:.6g} rad/s (point {i})"
        try:
            response[i, dof_map.free, :] = _solve_point(
                system, _dynamic_stiffness(system, mats, w[i], spins[i]), rhs(i), w[i],
                where, stats)
        except ConvergenceError:
            if on_failure == "raise":
                raise
            response[i] = np.nan
            status[i] = int(Status.FAILED)
    failed = bool(np.any(status != Status.OK))
    return FrequencyResponseResult(
        frequencies=w, speeds=np.asarray(spins, dtype=float), response=response,
        dof_map=dof_map, nodes_pos=system.nodes_pos, inputs=inputs, kind=kind,
        point_status=status, options={**options, "on_failure": on_failure},
        stats=stats.finish(), status=Status.FAILED if failed else Status.OK,
        summary=system.summary,
    )


def _solve_point(system: RotorSystem, Z: sp.csr_matrix, load: ComplexArray, w: float,
                 where: str, stats: Stats) -> ComplexArray:
    """Response ``Z^-1 load`` at one frequency, on the free DOFs.

    A zero load (unbalance at W = 0) has exactly zero response, with no solve. At ``w = 0``
    the dynamic stiffness is the stiffness ``K(W)``, singular when the rotor has free rigid
    motions (axial or torsional, on radial bearings): the static response is then found
    with those motions held, as in :func:`rotorsim.analyses.statics.static.static`, provided the
    load does no work on them (otherwise it is unbounded and ConvergenceError says so).
    """
    if not np.any(load):
        return np.zeros(load.shape, dtype=complex)
    try:
        return factorize(Z, stats=stats, where=where).solve(load)
    except ConvergenceError:
        if w != 0.0:
            raise
    K = sp.csr_matrix(Z.real)
    rigid = free_rigid_motions(system, K, scaled=True)
    work = np.abs(rigid.fields.T @ load)
    scale = np.linalg.norm(rigid.fields, axis=0)[:, None] * np.linalg.norm(load, axis=0)
    moved = [rigid.labels[j] for j in np.flatnonzero(np.any(work > 1e-9 * scale, axis=1))]
    if moved or not rigid.labels:
        detail = f"the load moves the free {', '.join(moved)}" if moved else "K is singular"
        raise ConvergenceError(f"the static (w = 0) response is unbounded: {detail}", where)
    keep = np.setdiff1d(np.arange(K.shape[0]), held_dofs(rigid))
    out = np.zeros(load.shape, dtype=complex)
    out[keep] = factorize(sp.csr_matrix(Z)[keep][:, keep], stats=stats,
                          where=where).solve(load[keep])
    return out
