"""The second-order problem that the time integrators solve (DESIGN sections 1 and 6).

The integrators know nothing about rotors: they see the equation of motion

    M a + (C + s(t) G + C_s(s(t))) v + (K + K_s(s(t))) q + r(q, v, t) = f(t)

with constant matrices ``M``, ``C``, ``G``, ``K`` (dense arrays or scipy sparse), an optional
scalar schedule ``s(t)`` (for a rotor: the spin speed W(t), with ``G`` the gyroscopic
matrix), optional matrices ``K_s(s)``, ``C_s(s)`` that follow the schedule on a few unknowns
(linear bearings tabulated over speed, :class:`SpeedTerms`), an optional nonlinear
restoring force ``r`` that returns its own tangents
``dr/dq`` and ``dr/dv``, and an optional load ``f(t)``. The analysis layer builds such a
problem from a ``RotorSystem``; tests build it from a Duffing oscillator or a Jeffcott
rotor.

The steppers work with the *net force* ``g = (C + s G + C_s) v + (K + K_s) q + r - f``, so
that the equation of motion reads ``M a + g = 0``.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Protocol

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError
from rotorsim.solvers.linear import DENSE_THRESHOLD
from rotorsim.time_integration.local_tangent import LocalMatrix

FloatArray = NDArray[np.float64]
Matrix = Any
"""A square matrix: a NumPy array or a scipy sparse matrix/array."""

RestoringForce = Callable[
    [FloatArray, FloatArray, float],
    "tuple[ArrayLike, Matrix | None, Matrix | None] | None",
]
"""``restoring(q, v, t) -> (r, dr/dq, dr/dv)`` for one sample: ``r`` (n,) [N], tangents
(n, n) dense, sparse or :class:`~.local_tangent.LocalMatrix` (nonzero on a few unknowns
only: the implicit steppers then factorise the constant part once and update it by a
low-rank solve), ``None`` for a zero tangent; returning ``None`` means ``r = 0``."""

LoadFunction = Callable[[float], ArrayLike]
"""``load(t) -> f`` (n,) [N]."""

ScheduleFunction = Callable[[float], float]
"""``speed(t) -> s`` scalar multiplying ``G`` (rad/s for a spin speed)."""


class SpeedTerms(Protocol):
    """Stiffness and damping that follow the schedule ``s`` on the unknowns ``dofs``."""

    @property
    def dofs(self) -> NDArray[np.int64]:
        """Distinct indices (k,) of the unknowns they act on."""
        ...

    def __call__(self, s: float, /) -> tuple[FloatArray, FloatArray]:
        """``K_s(s)``, ``C_s(s)`` (k, k) on ``dofs`` [N/m, N s/m]."""
        ...


@dataclass(frozen=True, eq=False)
class ForceEvaluation:
    """Net force ``g`` (n,) at one point with the tangents of its nonlinear part."""

    net: FloatArray
    stiffness_tangent: Matrix | None
    damping_tangent: Matrix | None


@dataclass(frozen=True, eq=False)
class SecondOrderProblem:
    """``M a + (C + s(t) G) v + K q + r(q, v, t) = f(t)`` with constant matrices.

    Parameters
    ----------
    mass : matrix (n, n)
        ``M`` [kg, kg m^2]; must be nonsingular unless the initial acceleration is given.
    stiffness : matrix (n, n)
        Linear stiffness ``K`` [N/m, N m/rad].
    damping : matrix (n, n), optional
        Constant damping ``C`` [N s/m]; any matrix, e.g. a skew gyroscopic term ``W G``.
    restoring : callable, optional
        ``restoring(q, v, t) -> (r, dr/dq, dr/dv)`` (see :data:`RestoringForce`). The
        tangents must be the exact derivatives for Newton to converge quadratically.
    load : callable, optional
        ``load(t) -> f`` (n,) [N]; zero if omitted.
    gyroscopic : matrix (n, n), optional
        ``G``, scaled by ``speed(t)`` in the damping term.
    speed : callable, optional
        ``speed(t) -> s`` [rad/s]; required with ``gyroscopic``. A constant schedule keeps
        one factorisation of the iteration matrix for a linear run; a varying one costs a
        refactorisation at a few speed nodes (see
        :mod:`~rotorsim.time_integration.newmark_step`).
    speed_terms : SpeedTerms, optional
        ``K_s(s)``, ``C_s(s)`` on a few unknowns (requires ``speed``): linear, so a problem
        without ``restoring`` stays linear; the Newmark steppers add them to the iteration
        matrix at each step's exact speed by a low-rank update.

    Examples
    --------
    >>> p = SecondOrderProblem(mass=np.eye(1), stiffness=4.0 * np.eye(1))
    >>> p.n, float(p.forces(np.ones(1), np.zeros(1), 0.0).net[0])
    (1, 4.0)
    """

    mass: Matrix
    stiffness: Matrix
    damping: Matrix | None = None
    restoring: RestoringForce | None = None
    load: LoadFunction | None = None
    gyroscopic: Matrix | None = None
    speed: ScheduleFunction | None = None
    speed_terms: SpeedTerms | None = None

    def __post_init__(self) -> None:
        n = _square(self.mass, "mass", None)
        for name in ("stiffness", "damping", "gyroscopic"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, _as_matrix(getattr(self, name), name, n))
        object.__setattr__(self, "mass", _as_matrix(self.mass, "mass", n))
        if (self.gyroscopic is not None or self.speed_terms is not None) != \
                (self.speed is not None):
            raise ModelError("give both 'speed' and 'gyroscopic' (or 'speed_terms'), or neither",
                             "SecondOrderProblem")
        for name in ("restoring", "load", "speed"):
            value = getattr(self, name)
            if value is not None and not callable(value):
                raise ModelError(f"must be callable, got {type(value).__name__}",
                                 f"SecondOrderProblem.{name}")

    @property
    def n(self) -> int:
        """Number of unknowns."""
        return int(self.mass.shape[0])

    @property
    def is_linear(self) -> bool:
        """True without a restoring force (one linear solve per step)."""
        return self.restoring is None

    @cached_property
    def fingerprint(self) -> str:
        """Digest of the size, the matrices and which callbacks are present.

        Checkpoints store it, so a resume on another problem is refused; the callbacks
        themselves cannot be compared. It starts with :data:`FINGERPRINT_VERSION`: a
        state stored by a version that digested the matrices otherwise is told apart.
        """
        h = hashlib.blake2b(digest_size=16)
        h.update(str(self.n).encode())
        for name in ("mass", "stiffness", "damping", "gyroscopic"):
            h.update(name.encode())
            h.update(content_digest(getattr(self, name)).to_bytes(8, "little"))
        for name in ("restoring", "load", "speed", "speed_terms"):
            h.update(f"{name}:{getattr(self, name) is not None}".encode())
        return FINGERPRINT_VERSION + h.hexdigest()

    @cached_property
    def gyroscopic_compact(self) -> Matrix | None:
        """``G`` without stored zeros (sparse; the same products, computed faster), or
        ``G`` itself when dense or absent."""
        if self.gyroscopic is None or not sp.issparse(self.gyroscopic):
            return self.gyroscopic
        G = self.gyroscopic.copy()
        G.eliminate_zeros()
        return G

    def spin(self, t: float) -> float:
        """``s(t)`` (0 without a schedule); rejects a non-finite value."""
        if self.speed is None:
            return 0.0
        s = float(self.speed(t))
        if not math.isfinite(s):
            raise ModelError(f"speed({t!r}) returned {s!r}", "SecondOrderProblem.speed")
        return s

    def external(self, t: float) -> FloatArray:
        """``f(t)`` (n,) [N], zeros without a load."""
        if self.load is None:
            return np.zeros(self.n)
        f = np.asarray(self.load(t), dtype=float).reshape(-1)
        if f.shape != (self.n,):
            raise ModelError(f"load({t!r}) has shape {f.shape}, expected ({self.n},)",
                             "SecondOrderProblem.load")
        return f

    def forces(self, q: FloatArray, v: FloatArray, t: float, *, spin: float | None = None,
               external: FloatArray | None = None) -> ForceEvaluation:
        """Net force ``g = (C + s G + C_s) v + (K + K_s) q + r - f`` and the tangents of
        ``r``.

        ``spin`` and ``external`` may be passed when already evaluated at ``t``.
        """
        s = 0.0
        if self.gyroscopic is not None or self.speed_terms is not None:
            s = self.spin(t) if spin is None else spin
        g = self.linear_force(q, v, s, self.external(t) if external is None else external)
        if self.restoring is None:
            return ForceEvaluation(g, None, None)
        out = self.restoring(q, v, t)
        if out is None:
            return ForceEvaluation(g, None, None)
        r, kt, ct = out
        r = np.asarray(r, dtype=float).reshape(-1)
        if r.shape != (self.n,):
            raise ModelError(f"restoring force has shape {r.shape}, expected ({self.n},)",
                             "SecondOrderProblem.restoring")
        return ForceEvaluation(g + r, kt, ct)

    def linear_force(self, q: FloatArray, v: FloatArray, spin: float,
                     external: FloatArray) -> FloatArray:
        """``(C + s G + C_s(s)) v + (K + K_s(s)) q - f`` at the schedule value ``spin`` with
        the load ``external`` [N]: the net force without the restoring force.

        With dense ``K`` (and ``C``) the speed terms are written into copies of them, once
        per schedule value (:class:`SpeedFolded`), so that a step's force evaluations cost
        what they cost without speed terms."""
        folded = self._speed_folded
        if folded is not None:
            K, C = folded.at(spin)
            g = K @ q + C @ v
        else:
            g = self.stiffness @ q
            if self.damping is not None:
                g = g + self.damping @ v
        if self.gyroscopic is not None:
            g = g + spin * (self.gyroscopic @ v)
        if self.speed_terms is not None and folded is None:
            dofs = self.speed_terms.dofs
            Ks, Cs = self.speed_terms(spin)
            g[dofs] += Ks @ q[dofs] + Cs @ v[dofs]
        return g - external

    @cached_property
    def _speed_folded(self) -> SpeedFolded | None:
        """Dense ``K + K_s``, ``C + C_s`` kept at the last schedule value (None without
        speed terms or with sparse ``K`` or ``C``)."""
        terms = self.speed_terms
        if terms is None or sp.issparse(self.stiffness) or sp.issparse(self.damping):
            return None
        return SpeedFolded(terms, self.stiffness, self.damping)

    def damping_at(self, spin: float) -> Matrix | None:
        """``C + s G + C_s(s)`` at the schedule value ``spin`` (None when all are absent)."""
        terms = [(1.0, self.damping), (spin, self.gyroscopic),
                 (1.0, self.speed_matrices(spin)[1])]
        if all(m is None for _, m in terms):
            return None
        return combine(terms, self.n)

    def speed_matrices(self, spin: float) -> tuple[LocalMatrix | None, LocalMatrix | None]:
        """``K_s(s)``, ``C_s(s)`` as local matrices at the schedule value ``spin`` (None
        without ``speed_terms``)."""
        if self.speed_terms is None:
            return None, None
        K, C = self.speed_terms(spin)
        dofs = self.speed_terms.dofs
        return LocalMatrix.trusted(self.n, dofs, K), LocalMatrix.trusted(self.n, dofs, C)


class SpeedFolded:
    """Dense ``K + P K_s(s) P^T`` and ``C + P C_s(s) P^T`` at the last schedule value ``s``
    asked for (``P``: the columns of the identity at the speed terms' DOFs). Only the
    entries where the terms can be nonzero (their ``pattern`` when they tell it) are
    rewritten."""

    def __init__(self, terms: SpeedTerms, stiffness: FloatArray,
                 damping: FloatArray | None) -> None:
        n, dofs = stiffness.shape[0], terms.dofs
        self.terms = terms
        pattern = getattr(terms, "pattern", None)
        self.cells = np.flatnonzero(np.ones((dofs.size, dofs.size), dtype=bool)
                                    if pattern is None else np.asarray(pattern))
        self.flat = (dofs[:, None] * n + dofs[None, :]).ravel()[self.cells]
        self.K = np.array(stiffness, dtype=float)
        self.C = np.zeros((n, n)) if damping is None else np.array(damping, dtype=float)
        self.K0, self.C0 = self.K.ravel()[self.flat], self.C.ravel()[self.flat]
        self.spin = math.nan

    def at(self, spin: float) -> tuple[FloatArray, FloatArray]:
        """The two matrices at the schedule value ``spin`` (kept by this object)."""
        if spin != self.spin:
            Ks, Cs = self.terms(spin)
            self.K.ravel()[self.flat] = self.K0 + Ks.ravel()[self.cells]
            self.C.ravel()[self.flat] = self.C0 + Cs.ravel()[self.cells]
            self.spin = spin
        return self.K, self.C


def combine(terms: list[tuple[float, Matrix | None]], n: int) -> Matrix:
    """``sum(c * A)`` over the terms with a matrix: dense for small ``n`` or all-dense
    input, CSR otherwise."""
    present = [(c, A.tocsr() if isinstance(A, LocalMatrix) else A) for c, A in terms
               if A is not None]
    if n > DENSE_THRESHOLD and any(sp.issparse(A) for _, A in present):
        out = sp.csr_matrix((n, n))
        for c, A in present:
            out = out + c * sp.csr_matrix(A)
        return out.tocsr()
    dense = np.zeros((n, n))
    for c, A in present:
        dense += c * (A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float))
    return dense


FINGERPRINT_VERSION = "2-"
"""Prefix of :attr:`SecondOrderProblem.fingerprint` (2: dense matrices digested by their
non-zero entries, :func:`content_digest`)."""


def content_digest(A: Matrix | None) -> int:
    """63-bit hash of a matrix's content: equal for equal matrices in the same storage.

    A dense array is digested by the positions and values of its non-zero entries: the
    dense matrices of a small rotor are mostly zeros (534 of 15,876 entries for 126 DOFs),
    and hashing them whole cost 0.16 ms per matrix, a few percent of a short run. Other
    matrices as :func:`matrix_digest`.
    """
    if A is None or sp.issparse(A) or isinstance(A, LocalMatrix):
        return matrix_digest(A)
    arr = np.asarray(A, dtype=float)
    flat = arr.reshape(-1)
    at = np.flatnonzero(flat)
    h = hashlib.blake2b(digest_size=8)
    h.update(str(arr.shape).encode())
    h.update(at.astype(np.int64).tobytes())
    h.update(flat[at].tobytes())
    return int.from_bytes(h.digest(), "little") >> 1


def matrix_digest(A: Matrix | None) -> int:
    """63-bit content hash of a dense or sparse matrix (0 for ``None``).

    Equal matrices in the same storage give equal digests; the steppers use it as the key of
    the cached factorisation of the iteration matrix.
    """
    if A is None:
        return 0
    h = hashlib.blake2b(digest_size=8)
    if isinstance(A, LocalMatrix):
        h.update(b"local")
        h.update(A.dofs.tobytes())
        h.update(np.ascontiguousarray(A.block).tobytes())
    elif sp.issparse(A):
        csr = sp.csr_matrix(A)
        for part in (csr.indptr, csr.indices, csr.data):
            h.update(np.ascontiguousarray(part).tobytes())
    else:
        arr = np.ascontiguousarray(A, dtype=float)
        h.update(str(arr.shape).encode())
        h.update(arr.tobytes())
    return int.from_bytes(h.digest(), "little") >> 1


def _square(A: Matrix, name: str, n: int | None) -> int:
    shape = getattr(A, "shape", np.shape(A))
    if len(shape) != 2 or shape[0] != shape[1] or (n is not None and shape[0] != n):
        expected = "square" if n is None else f"({n}, {n})"
        raise ModelError(f"shape {tuple(shape)} is not {expected}", f"SecondOrderProblem.{name}")
    return int(shape[0])


def _as_matrix(A: Matrix, name: str, n: int) -> Matrix:
    """Validated float64 copy: CSR if sparse, ndarray otherwise."""
    _square(A, name, n)
    out = sp.csr_matrix(A, dtype=float) if sp.issparse(A) else np.array(A, dtype=float)
    data = out.data if sp.issparse(out) else out
    if not np.all(np.isfinite(data)):
        raise ModelError("contains NaN or Inf", f"SecondOrderProblem.{name}")
    return out
