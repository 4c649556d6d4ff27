"""Free rigid-body motions of a constrained rotor: which motions of the whole rotor nothing
restrains, whether a load can be equilibrated, and a linear solve with those motions held.

Shared by the static, nonlinear static, frequency-response, transient-start and periodic
analyses.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from numpy.typing import NDArray

from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import factorize
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
_MOTIONS = ("rotation about x", "rotation about y", "rotation about z",
            "x (translation)", "y (translation)", "z (translation)")


@dataclass(frozen=True)
class RigidMotions:
    """Free rigid-body motions of the whole rotor (of each line of a machine).

    ``fields`` (n_free, k) holds each motion on the free DOFs, normalised to a unit
    translation [m] or a unit rotation [rad]; ``labels`` names them.
    """

    fields: FloatArray
    labels: tuple[str, ...]


def rigid_body_fields(system: RotorSystem) -> FloatArray:
    """The 6 rigid motions of the whole rotor on all DOFs, shape ``(ndof, 6)``.

    Columns: rotations about the x, y and z axes through ``z = 0`` (``uy = -z theta``,
    ``rx = theta``; ``ux = z theta``, ``ry = theta``; ``rz = theta``), then unit
    translations along x, y and z.

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> from rotorsim.model.rotor import Rotor
    >>> from rotorsim.elements.shaft import ShaftElement
    >>> from rotorsim.assembly.system import assemble
    >>> R = rigid_body_fields(assemble(Rotor([ShaftElement(L=2.0, idl=0.0, odl=0.05,
    ...                                                    material=steel)])))
    >>> R[6:12, 0].tolist()   # rotation about x at the node z = 2 m
    [0.0, -2.0, 0.0, 1.0, 0.0, 0.0]
    """
    z = np.asarray(system.nodes_pos, dtype=float)
    fields = np.zeros((z.size, DOFS_PER_NODE, 6))
    fields[:, 1, 0], fields[:, 3, 0] = -z, 1.0
    fields[:, 0, 1], fields[:, 4, 1] = z, 1.0
    fields[:, 5, 2] = 1.0
    fields[:, [0, 1, 2], [3, 4, 5]] = 1.0
    return fields.reshape(-1, 6)


def body_groups(system: RotorSystem) -> tuple[NDArray[np.int64], tuple[str, ...]]:
    """Group of every node and the group names: one group (the whole rotor) for a one-line
    rotor; each line of a machine, and its housing nodes together, otherwise (each line
    of a machine may move rigidly on its own, e.g. turn about its axis)."""
    n_nodes = system.dof_map.n_nodes
    if system.node_line is None:
        return np.zeros(n_nodes, dtype=np.int64), ("rotor",)
    group = np.asarray(system.node_line, dtype=np.int64).copy()
    names = list(system.line_names)
    if np.any(group < 0):
        group[group < 0] = len(names)
        names.append("housings")
    return group, tuple(names)


def grouped_rigid_fields(system: RotorSystem) -> FloatArray:
    """:func:`rigid_body_fields` of every body group apart, ``(ndof, 6 G)``: group ``g``'s
    six motions move only its nodes; their sum over the groups is the whole machine's."""
    group, names = body_groups(system)
    whole = rigid_body_fields(system).reshape(-1, DOFS_PER_NODE, 6)
    out = np.zeros((whole.shape[0], DOFS_PER_NODE, 6 * len(names)))
    for g in range(len(names)):
        on = group == g
        out[on, :, 6 * g:6 * g + 6] = whole[on]
    return out.reshape(-1, 6 * len(names))


def free_rigid_motions(system: RotorSystem, K: sp.spmatrix, rigid_tol: float = 1e-10,
                       *, scaled: bool = False) -> RigidMotions:
    """Rigid-body motions ``r`` of the whole rotor that ``K`` does not restrain.

    Unscaled (default), a motion is free when ``||K r|| <= rigid_tol ||K||_F ||r||``: a
    restraint weaker than ``rigid_tol`` times the stiffest entry counts as absent, which is
    what the nonlinear analyses want of placeholder ("ghost") shafts of ``E = 1 Pa`` under
    rigid rotors. ``scaled=True`` (linear :func:`static` and the frequency response) makes
    the test independent of the stiffest spring: with ``S = diag(|K_ii|^-1/2)`` (1 where
    ``K_ii = 0``), ``r`` is free when ``||S K r|| <= rigid_tol ||S K S||_F ||S^-1 r||``, so a
    1e8 N/m thrust bearing restrains the axial motion even beside 1e20 N/m radial (pinned)
    supports. The test is made on the orthonormalised span of :func:`rigid_body_fields`
    (restricted to the free DOFs), so combinations such as a rotation about a single bearing
    are found. The basis returned is in reduced row-echelon form over the named motions
    (rotations first), which turns it into pure translations and rotations about a pivot.
    """
    diag = np.abs(np.asarray(K.diagonal(), dtype=float))
    scale = np.ones(diag.size)
    if scaled:
        scale = np.where(diag > 0, 1.0 / np.sqrt(np.where(diag > 0, diag, 1.0)), 1.0)
    S = sp.diags(scale)
    Ks = sp.csr_matrix(S @ K @ S)
    R = grouped_rigid_fields(system)[system.dof_map.free]
    B = R / scale[:, None]  # the motions in scaled coordinates, each normalised below
    norms = np.linalg.norm(B, axis=0)
    norms = np.where(norms > 0, norms, 1.0)
    U, sv, Vt = np.linalg.svd(B / norms, full_matrices=False)
    keep = sv > 1e-12 * sv.max()
    Q = U[:, keep]
    both = np.vstack([Ks @ Q, Ks.T @ Q])
    _, s, wt = np.linalg.svd(both, full_matrices=True)
    s = np.concatenate([s, np.zeros(Q.shape[1] - s.size)])
    null = wt[s <= rigid_tol * spl.norm(Ks)].T  # (m, k) in Q coordinates
    if null.shape[1] == 0:
        return RigidMotions(np.zeros((R.shape[0], 0)), ())
    coef = Vt[keep].T @ (null / sv[keep][:, None]) / norms[:, None]  # (6G, k), named motions
    coef = _reduced_echelon(coef.T).T
    names = body_groups(system)[1]
    labels = tuple(_group_label(c, names) for c in coef.T)
    return RigidMotions(R @ coef, labels)


def _group_label(c: FloatArray, names: tuple[str, ...]) -> str:
    """Name of a motion with coefficients ``c`` over the groups' :data:`_MOTIONS`."""
    blocks = c.reshape(len(names), 6)
    moving = [g for g in range(len(names)) if np.any(blocks[g])]
    if len(names) == 1:
        return _label(blocks[0])
    if len(moving) == 1:
        return f"{names[moving[0]]}: {_label(blocks[moving[0]])}"
    if all(np.allclose(blocks[g], blocks[moving[0]]) for g in moving) \
            and len(moving) == len(names):
        return f"whole machine: {_label(blocks[moving[0]])}"
    return " + ".join(f"{names[g]}: {_label(blocks[g])}" for g in moving)


def _reduced_echelon(rows: FloatArray) -> FloatArray:
    """Reduced row-echelon form (leading entries 1) of a full-rank ``(k, 6)`` array."""
    A = rows.copy()
    r = 0
    for col in range(A.shape[1]):
        if r == A.shape[0]:
            break
        pivot = r + int(np.argmax(np.abs(A[r:, col])))
        if abs(A[pivot, col]) <= 1e-9 * np.abs(A).max():
            continue
        A[[r, pivot]] = A[[pivot, r]]
        A[r] /= A[r, col]
        others = np.arange(A.shape[0]) != r
        A[others] -= np.outer(A[others, col], A[r])
        r += 1
    A[np.abs(A) <= 1e-9] = 0.0
    return A


def _label(c: FloatArray) -> str:
    """Name of a rigid motion with coefficients ``c`` over :data:`_MOTIONS`."""
    nonzero = set(np.flatnonzero(c).tolist())
    pivots = {0: (4, -1.0, "x"), 1: (3, 1.0, "y")}  # rotation -> (translation, sign, axis)
    for rot, (trans, sign, axis) in pivots.items():
        if nonzero and min(nonzero) == rot and nonzero <= {rot, trans}:
            z0 = -sign * c[trans] / c[rot] if trans in nonzero else 0.0
            return f"rotation about {axis} through z = {z0 + 0.0:.6g} m"
    if len(nonzero) == 1:
        return _MOTIONS[nonzero.pop()]
    return " + ".join(f"{c[i]:.3g} * {_MOTIONS[i]}" for i in sorted(nonzero))


def check_equilibrium(rigid: RigidMotions, f: FloatArray, tol: float = 1e-9) -> None:
    """Raise if the load does work on a free rigid motion (no equilibrium exists)."""
    work = rigid.fields.T @ f
    scale = np.linalg.norm(rigid.fields, axis=0) * np.linalg.norm(f)
    bad = np.flatnonzero(np.abs(work) > tol * scale)
    if not bad.size:
        return
    order = sorted(bad, key=lambda j: "translation" not in rigid.labels[j])
    parts = []
    for j in order:
        translation = "translation" in rigid.labels[j]
        kind, unit = ("load resultant", "N") if translation else ("load moment", "N m")
        where = "in" if translation else "against"
        parts.append(f"rotor has no support {where} {rigid.labels[j]}: {kind} "
                     f"{work[j]:.6g} {unit} cannot be equilibrated")
    raise ModelError("; ".join(parts) + "; add bearings", "static")


def held_dofs(rigid: RigidMotions) -> list[int]:
    """One free DOF per free rigid motion whose value fixes that motion (the first largest
    entry of each field after eliminating the previous ones)."""
    fields = rigid.fields.copy()
    held: list[int] = []
    for j in range(fields.shape[1]):
        col = np.abs(fields[:, j])
        i = int(np.flatnonzero(col >= (1.0 - 1e-9) * col.max())[0])
        held.append(i)
        fields[:, j + 1:] -= np.outer(fields[:, j] / fields[i, j], fields[i, j + 1:])
    return held


def solve_restrained(K: sp.spmatrix, f: FloatArray, rigid: RigidMotions, stats: Stats
                      ) -> tuple[FloatArray, list[int]]:
    """Solve ``K q = f`` holding one free DOF per free rigid motion at zero."""
    held = held_dofs(rigid)
    keep = np.setdiff1d(np.arange(K.shape[0]), held)
    Kc = sp.csr_matrix(K)[keep][:, keep]
    q = np.zeros(K.shape[0])
    try:
        q[keep] = factorize(Kc, stats=stats, where="static").solve(f[keep])
    except ConvergenceError as exc:
        raise ModelError(
            "stiffness matrix is singular beyond the rigid-body motions of the whole rotor: "
            "some node or housing has no support in some direction", "static") from exc
    return q, held
