"""Foundations and support structures as linear superelements on connection DOFs.

A support structure modelled elsewhere (an FE model of a frame, a casing, a baseplate) is
brought in by its matrices reduced to the DOFs where the machine connects to it:
``M x'' + C x' + K x = f`` on the connection DOFs ``x`` (e.g. Guyan or Craig-Bampton
reduction exported from an FE code, as NumPy ``.npy`` or Matrix Market ``.mtx`` files), or
by its modal data there: natural frequencies ``omega_j``, damping ratios ``zeta_j`` and
mass-normalised mode shapes ``Phi`` (``Phi^T M Phi = I``) at the connection DOFs. With as
many modes as connection DOFs the modal data define the matrices exactly:
``M = Phi^-T Phi^-1``, ``K = Phi^-T diag(omega^2) Phi^-1``,
``C = Phi^-T diag(2 zeta omega) Phi^-1``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.base import DOF_NAMES, DOFS_PER_NODE, ElementMatrices
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]
SYMMETRY_TOL = 1e-9
"""Largest ``|A - A^T|`` relative to ``max |A|`` of a foundation matrix."""
DEFINITENESS_TOL = 1e-9
"""Most negative eigenvalue relative to the largest one still counted as zero."""


@dataclass(frozen=True, eq=False)
class Foundation:
    """A linear superelement on connection DOFs (module docstring).

    Parameters
    ----------
    dofs : sequence of (node, dof)
        The connection DOF of every row and column, e.g. ``[(43, "ux"), (43, "uy")]``.
        Nodes off the shaft lines (housings) need no point mass: the foundation gives
        them their mass.
    M, C, K : array (n, n)
        Mass [kg, kg m^2], damping [N s/m] and stiffness [N/m] on ``dofs``; symmetric and
        positive semi-definite. ``C`` defaults to zero.
    tag : str, optional

    Examples
    --------
    >>> f = Foundation([(0, "ux"), (0, "uy")], M=np.eye(2) * 50.0, K=np.eye(2) * 1e8)
    >>> f.nodes, f.matrices().K[1, 1]
    ((0,), np.float64(100000000.0))
    """

    dofs: Sequence[tuple[int, str]]
    M: ArrayLike
    K: ArrayLike
    C: ArrayLike | None = None
    tag: str | None = None

    def __post_init__(self) -> None:
        where = self.label
        dofs = _connection_dofs(self.dofs, where)
        object.__setattr__(self, "dofs", dofs)
        n = len(dofs)
        for key in ("M", "C", "K"):
            value = getattr(self, key)
            if value is None:
                value = np.zeros((n, n))
            matrix = _matrix(value, n, key, where)
            object.__setattr__(self, key, matrix)

    @property
    def label(self) -> str:
        return f"Foundation '{self.tag}'" if self.tag else "Foundation"

    @property
    def nodes(self) -> tuple[int, ...]:
        """The connection nodes, in order of first appearance."""
        return tuple(dict.fromkeys(int(node) for node, _ in self.dofs))

    @property
    def n(self) -> int:
        return self.nodes[0]

    def matrices(self, speed: float = 0.0) -> ElementMatrices:
        """``(6 k, 6 k)`` matrices on the ``k`` connection nodes (zeros off ``dofs``)."""
        nodes = self.nodes
        index = np.array([DOFS_PER_NODE * nodes.index(int(node)) + DOF_NAMES.index(dof)
                          for node, dof in self.dofs])
        size = DOFS_PER_NODE * len(nodes)
        out = {}
        for key in ("M", "C", "K"):
            full = np.zeros((size, size))
            full[np.ix_(index, index)] = getattr(self, key)
            out[key] = full
        return ElementMatrices(M=out["M"], C=out["C"], G=np.zeros((size, size)), K=out["K"])

    @classmethod
    def from_modal(cls, dofs: Sequence[tuple[int, str]], frequencies: ArrayLike,
                   damping_ratios: ArrayLike, shapes: ArrayLike, tag: str | None = None
                   ) -> Foundation:
        """The foundation of modal data: ``frequencies`` [rad/s] ``(m,)``, ``damping_ratios``
        ``(m,)`` and mass-normalised ``shapes`` ``(n, m)`` at the ``n`` connection DOFs,
        with ``m = n`` (module docstring)."""
        where = f"Foundation '{tag}'" if tag else "Foundation"
        w = np.asarray(frequencies, dtype=float).reshape(-1)
        zeta = np.asarray(damping_ratios, dtype=float).reshape(-1)
        phi = np.asarray(shapes, dtype=float)
        n = len(tuple(dofs))
        if phi.shape != (n, w.size) or zeta.shape != w.shape:
            raise ModelError(f"shapes must be (connection DOFs {n}, modes {w.size}) and "
                             f"damping_ratios ({w.size},); got {phi.shape} and {zeta.shape}",
                             where)
        if w.size != n:
            raise ModelError(f"{w.size} modes for {n} connection DOFs: modal data define the "
                             "matrices on the connection DOFs only with as many modes as "
                             "DOFs (give the reduced M, C, K instead)", where)
        if not (np.all(np.isfinite(w)) and np.all(w >= 0) and np.all(np.isfinite(zeta))
                and np.all(zeta >= 0) and np.all(np.isfinite(phi))):
            raise ModelError("frequencies and damping ratios must be finite and >= 0, shapes "
                             "finite", where)
        try:
            inverse = np.linalg.inv(phi)
        except np.linalg.LinAlgError:
            raise ModelError("the mode shapes at the connection DOFs are linearly dependent "
                             "(singular)", where) from None
        def back(diag: FloatArray) -> FloatArray:
            return np.asarray(inverse.T @ (diag[:, None] * inverse))
        return cls(dofs, M=back(np.ones(n)), K=back(w * w), C=back(2.0 * zeta * w), tag=tag)

    @classmethod
    def from_files(cls, dofs: Sequence[tuple[int, str]], mass: str | Path,
                   stiffness: str | Path, damping: str | Path | None = None,
                   tag: str | None = None) -> Foundation:
        """The foundation of matrices in files: NumPy ``.npy`` or Matrix Market ``.mtx``."""
        where = f"Foundation '{tag}'" if tag else "Foundation"
        return cls(dofs, M=read_matrix(mass, where), K=read_matrix(stiffness, where),
                   C=None if damping is None else read_matrix(damping, where), tag=tag)


def read_matrix(path: str | Path, where: str) -> FloatArray:
    """A dense matrix from a ``.npy`` or Matrix Market ``.mtx`` file."""
    path = Path(path)
    if not path.is_file():
        raise ModelError(f"no file {str(path)!r}", where)
    try:
        if path.suffix == ".npy":
            return np.asarray(np.load(path, allow_pickle=False), dtype=float)
        if path.suffix == ".mtx":
            import scipy.io

            data: Any = scipy.io.mmread(str(path))
            return np.asarray(data.toarray() if hasattr(data, "toarray") else data,
                              dtype=float)
    except (ValueError, OSError) as exc:
        raise ModelError(f"cannot read {str(path)!r}: {exc}", where) from None
    raise ModelError(f"{str(path)!r}: use a .npy or Matrix Market .mtx file", where)


def _connection_dofs(dofs: Any, where: str) -> tuple[tuple[int, str], ...]:
    out = []
    for i, item in enumerate(tuple(dofs)):
        try:
            node, dof = item
        except (TypeError, ValueError):
            node = dof = None
        if isinstance(node, bool) or not isinstance(node, int | np.integer) or node < 0 \
                or dof not in DOF_NAMES:
            raise ModelError(f"expected (node, dof) with dof one of {DOF_NAMES}, got "
                             f"{item!r}", f"{where}.dofs[{i}]")
        out.append((int(node), str(dof)))
    if not out:
        raise ModelError("give at least one connection DOF", where)
    if len(set(out)) != len(out):
        raise ModelError("a connection DOF is listed twice", f"{where}.dofs")
    return tuple(out)


def _matrix(value: ArrayLike, n: int, key: str, where: str) -> FloatArray:
    """A symmetric positive semi-definite ``(n, n)`` matrix, or a ModelError saying why
    not (a foundation that is not passive would feed energy to the machine)."""
    try:
        matrix = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ModelError(f"{key} must be a numeric (n, n) matrix", where) from None
    if matrix.shape != (n, n):
        raise ModelError(f"{key} must be ({n}, {n}) for {n} connection DOFs, got "
                         f"{matrix.shape}", where)
    if not np.all(np.isfinite(matrix)):
        raise ModelError(f"{key} has non-finite entries", where)
    scale = float(np.abs(matrix).max())
    if scale == 0.0:
        return matrix
    asym = float(np.abs(matrix - matrix.T).max())
    if asym > SYMMETRY_TOL * scale:
        i, j = np.unravel_index(int(np.argmax(np.abs(matrix - matrix.T))), matrix.shape)
        raise ModelError(f"{key} is not symmetric: entry ({i}, {j}) differs from ({j}, {i}) by "
                         f"{asym:.3g} ({asym / scale:.2g} of its largest entry)", where)
    sym = 0.5 * (matrix + matrix.T)
    low = float(np.linalg.eigvalsh(sym).min())
    if low < -DEFINITENESS_TOL * scale * n:
        raise ModelError(f"{key} is not positive semi-definite: eigenvalue {low:.3g} (a "
                         "foundation must not feed energy to the machine)", where)
    return sym
