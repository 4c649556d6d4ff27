"""Comparing and classifying complex mode shapes: MAC, whirl direction, mode kind, and
circular forward/backward bases of degenerate eigenspaces."""

from __future__ import annotations

import itertools
from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.results.orbits import ellipse

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

CLUSTER_RTOL = 1e-6
"""Eigenvalues closer than this (relative) form a degenerate cluster."""
KINDS = np.array(["lateral", "axial", "torsional"])
_GROUPS = ([0, 1, 3, 4], [2], [5])


def mode_kind(mass_diagonal: FloatArray, shapes: ComplexArray) -> NDArray[np.str_]:
    """``"lateral"``, ``"axial"`` or ``"torsional"``: the DOF group with most kinetic energy.

    Parameters
    ----------
    mass_diagonal : array (ndof,)
        Diagonal of the structural mass matrix on all DOFs.
    shapes : complex array (ndof, p)
        Mode shapes on all DOFs.

    Examples
    --------
    >>> shape = np.zeros((6, 1)); shape[5] = 1.0
    >>> mode_kind(np.ones(6), shape).tolist()
    ['torsional']
    """
    energy = (np.abs(shapes) ** 2 * mass_diagonal[:, None]).reshape(-1, 6, shapes.shape[1])
    groups = np.stack([energy[:, g, :].sum(axis=(0, 1)) for g in _GROUPS])
    return KINDS[np.argmax(groups, axis=0)].astype("<U9")


def mac(a: ArrayLike, b: ArrayLike) -> FloatArray:
    """Modal assurance criterion of complex shapes, ``|a^H b|^2 / ((a^H a)(b^H b))``.

    Parameters
    ----------
    a : array (n, p)
    b : array (n, q)

    Returns
    -------
    array (p, q)
        1 for parallel shapes, 0 for orthogonal ones.

    Examples
    --------
    >>> forward, backward = np.array([1.0, -1j]), np.array([1.0, 1j])
    >>> mac(forward[:, None], np.stack([forward, backward], axis=1)).round(12).tolist()
    [[1.0, 0.0]]
    """
    A = np.asarray(a, dtype=complex)
    B = np.asarray(b, dtype=complex)
    num = np.abs(A.conj().T @ B) ** 2
    den = np.outer(np.sum(np.abs(A) ** 2, axis=0), np.sum(np.abs(B) ** 2, axis=0))
    return np.asarray(num / np.maximum(den, 1e-300))


PURE_TILT = 1e-9
"""A lateral mode whose largest translation orbit [m] is below this times its largest tilt
orbit [rad] has no translation to working precision (a ratio of mixed units, used only to
tell rounding from motion: any real translation of a tilting mode is many orders larger)."""


def whirl_of(shapes: ArrayLike) -> tuple[NDArray[np.str_], FloatArray]:
    """Whirl direction of lateral mode shapes from their orbit ellipses.

    Nodes whose orbit is larger than 1e-3 of the largest one are significant; a mode is
    ``"forward"`` (``"backward"``) if every significant orbit whirls forward (backward),
    ``"mixed"`` otherwise; ``"none"`` without lateral motion. A mode with no translation
    (all orbits below :data:`PURE_TILT` of its largest tilt, e.g. the conical whirl of a
    disk held at its centre) takes the orbits of its tilts ``(ry, -rx)``, which turn the
    way ``(ux, uy)`` do (``ry = dux/dz``, ``rx = -duy/dz``).

    Parameters
    ----------
    shapes : complex array (ndof, p)
        Shapes on all DOFs (6 per node, ``ux`` and ``uy`` first).

    Returns
    -------
    whirl : str array (p,)
    ratio : array (p,)
        Orbit-size weighted mean of ``(rf - rb) / (rf + rb)`` [-].

    Examples
    --------
    >>> shape = np.zeros((12, 1), complex)
    >>> shape[[0, 6], 0], shape[[1, 7], 0] = 1.0, 1j        # y lags x by -90 deg: backward
    >>> whirl_of(shape)[0].tolist()
    ['backward']
    """
    nodes = np.asarray(shapes, dtype=complex).reshape(-1, 6, np.shape(shapes)[1])
    orbit = ellipse(nodes[:, 0, :], nodes[:, 1, :])
    tilt = ellipse(nodes[:, 4, :], -nodes[:, 3, :])  # (ry, -rx) turns as (ux, uy) does
    pure_tilt = orbit.major.max(axis=0, initial=0.0) <= PURE_TILT * tilt.major.max(
        axis=0, initial=0.0)
    size = np.where(pure_tilt, tilt.major, orbit.major)
    whirl_ratio = np.where(pure_tilt, tilt.whirl_ratio, orbit.whirl_ratio)
    significant = size > 1e-3 * np.maximum(size.max(axis=0, keepdims=True), 1e-300)
    weight = np.where(significant, size, 0.0)
    ratio = (weight * whirl_ratio).sum(axis=0) / np.maximum(weight.sum(axis=0), 1e-300)
    r = np.where(significant, whirl_ratio, np.nan)
    forward = np.all(~significant | (r > 1e-6), axis=0)
    backward = np.all(~significant | (r < -1e-6), axis=0)
    whirl = np.where(forward, "forward", np.where(backward, "backward", "mixed"))
    whirl = np.where(significant.any(axis=0), whirl, "none")
    return whirl.astype("<U8"), ratio


def clusters(values: ArrayLike, rtol: float = CLUSTER_RTOL) -> list[NDArray[np.int64]]:
    """Groups (of two or more) of indices of values equal within ``rtol`` (relative).

    Examples
    --------
    >>> [c.tolist() for c in clusters([1.0, 2.0, 1.0 + 1e-9, 3.0])]
    [[0, 2]]
    """
    v = np.asarray(values, dtype=complex)
    order = np.argsort(np.abs(v), kind="stable")
    groups: list[list[int]] = [[int(order[0])]] if v.size else []
    for a, b in itertools.pairwise(order):
        if abs(v[b] - v[a]) <= rtol * max(abs(v[a]), abs(v[b]), 1e-300):
            groups[-1].append(int(b))
        else:
            groups.append([int(b)])
    return [np.array(g, dtype=np.int64) for g in groups if len(g) > 1]


def circularize(shapes: ComplexArray, groups: Iterable[NDArray[np.int64]]) -> ComplexArray:
    """Rotate each degenerate cluster of shapes to its forward and backward circular modes.

    Within an eigenspace of equal eigenvalues any basis is valid (e.g. the x-plane and
    y-plane modes of an isotropic rotor at rest). The basis returned diagonalises the
    Hermitian form ``sum |X + iY|^2 - |X - iY|^2`` over the nodes (forward minus backward
    orbit energy, ``X, Y`` the ``ux, uy`` amplitudes), so a pair becomes one forward and one
    backward circular mode, as it is for any small spin speed.

    Parameters
    ----------
    shapes : complex array (ndof, p)
        Shapes on all DOFs; columns of different clusters are left alone.
    groups : iterable of int arrays
        Column indices of each cluster, e.g. from :func:`clusters`.

    Returns
    -------
    complex array (ndof, p)
        A copy, the clusters rotated (forward-most first within a cluster).

    Examples
    --------
    >>> x_plane, y_plane = np.zeros(6, complex), np.zeros(6, complex)
    >>> x_plane[0], y_plane[1] = 1.0, 1.0
    >>> out = circularize(np.stack([x_plane, y_plane], axis=1), [np.array([0, 1])])
    >>> whirl_of(out)[0].tolist()
    ['forward', 'backward']
    """
    out = np.array(shapes, dtype=complex, copy=True)
    for g in groups:
        q, _ = np.linalg.qr(out[:, g])
        nodes = q.reshape(-1, 6, g.size)
        fwd = nodes[:, 0, :] + 1j * nodes[:, 1, :]
        bwd = nodes[:, 0, :] - 1j * nodes[:, 1, :]
        h = fwd.conj().T @ fwd - bwd.conj().T @ bwd
        _, vectors = np.linalg.eigh((h + h.conj().T) / 2.0)
        out[:, g] = q @ vectors[:, ::-1]
    return out
