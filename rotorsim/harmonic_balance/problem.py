"""The harmonic-balance problem: matrices, nonlinear DOFs, force callback and excitation.

Rotor-agnostic (DESIGN section 1). The equation is

    M q'' + (C + W G) q' + K q + r(q_nl, q_nl', tau, omega, p) = f(tau, omega, p)

for ``n`` unknowns ``q(t)``, periodic with fundamental frequency ``omega`` [rad/s] and
phase ``tau = omega t`` [rad]. The nonlinear restoring force ``r`` acts on the ``k``
unknowns ``nl_dofs`` only. ``W = spin + spin_ratio * omega`` [rad/s] scales the gyroscopic
matrix: a rotor under unbalance has ``spin_ratio = 1`` (``omega = W``); a varying-compliance
response with fundamental ``omega = Z kappa W`` has ``spin_ratio = 1 / (Z kappa)``; a fixed
spin with an excitation of independent frequency has ``spin_ratio = 0``.

Callbacks (all batched over the ``N`` time samples, STYLE practice 3):

* ``force(q, v, tau, omega, p) -> (f, dfdq, dfdv)`` with ``q, v`` (N, k) the displacements
  [m, rad] and velocities of the nonlinear DOFs, ``tau`` (N,) the phases [rad] (a rotor turns
  them into shaft angles ``phi = W tau / omega`` for the rolling-element positions) and ``p``
  the scalar continuation parameter; returns ``f`` (N, k) [N], ``dfdq`` (N, k, k) and
  ``dfdv`` (N, k, k) or ``None`` for a force independent of ``v``. The tangents must be the
  exact derivatives. Set ``force_uses_omega=True`` if ``f`` depends on ``omega`` other than
  through ``v`` (e.g. centrifugal loads ~ W^2): ``d/domega`` then adds a finite difference.
* ``excitation``: harmonic coefficients of ``f``, an array (2m + 1, n) in the layout of
  :mod:`~rotorsim.harmonic_balance.fourier` or a callable ``excitation(omega, p)``
  returning one (unbalance: ``omega**2 * coefficients``); truncated or zero-padded to ``H``.
* ``load(tau, omega, p) -> (N, n)``: ``f`` sampled in time, transformed by FFT (aliasing
  and truncation as for the nonlinear force).

References
----------
Seed 002 section 3.5.2.1, eqs 3.30-3.32 (Fourier series of displacements, bearing forces and
external loads).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.fourier import AFT, FloatArray, IntArray, resize

Matrix = Any
"""A square matrix: NumPy array or scipy sparse matrix/array."""

NonlinearForce = Callable[
    [FloatArray, FloatArray, FloatArray, float, float],
    "tuple[ArrayLike, ArrayLike, ArrayLike | None]",
]
"""``force(q (N,k), v (N,k), tau (N,), omega, p) -> (f (N,k), dfdq (N,k,k), dfdv | None)``."""

Excitation = Callable[[float, float], ArrayLike]
"""``excitation(omega, p) -> coefficients (2m + 1, n)`` [N]."""

SampledLoad = Callable[[FloatArray, float, float], ArrayLike]
"""``load(tau (N,), omega, p) -> f (N, n)`` [N]."""


@dataclass(frozen=True, eq=False)
class NonlinearSamples:
    """One evaluation of the force callback at ``N`` samples (validated shapes)."""

    f: FloatArray
    dfdq: FloatArray | None
    dfdv: FloatArray | None


@dataclass(frozen=True, eq=False)
class HBProblem:
    """Linear matrices, nonlinear DOFs and force, and excitation of a periodic problem.

    Parameters
    ----------
    mass, stiffness : matrix (n, n)
        ``M`` [kg], ``K`` [N/m]; dense or scipy sparse.
    damping, gyroscopic : matrix (n, n), optional
        ``C`` [N s/m] and ``G`` [N s/m per rad/s of spin] (zero if omitted).
    nl_dofs : sequence of int
        Indices (k,) of the unknowns the nonlinear force acts on, in the order the force
        callback expects (unique).
    force : NonlinearForce, optional
        See the module docstring; requires ``nl_dofs``.
    excitation : array (2m + 1, n) or Excitation, optional
        Harmonic coefficients of the external force.
    load : SampledLoad, optional
        External force sampled in time (added to ``excitation``).
    spin, spin_ratio : float
        ``W = spin + spin_ratio * omega`` [rad/s].
    force_uses_omega : bool
        The force depends explicitly on ``omega`` (see the module docstring).
    param_scale : float
        Typical size of the continuation parameter ``p``; the central differences in ``p``
        use the step ``6e-6 * max(|p|, param_scale)``.

    Examples
    --------
    Duffing ``x'' + 0.1 x' + x + x^3 = cos(omega t)``:

    >>> cubic = lambda q, v, tau, w, p: (q**3, 3 * q[:, :, None]**2, None)
    >>> duffing = HBProblem(np.eye(1), np.eye(1), damping=0.1 * np.eye(1), nl_dofs=[0],
    ...                     force=cubic, excitation=[[0.0], [1.0], [0.0]])
    >>> duffing.n, duffing.k, duffing.linear_dofs.tolist()
    (1, 1, [])
    """

    mass: Matrix
    stiffness: Matrix
    damping: Matrix | None = None
    gyroscopic: Matrix | None = None
    nl_dofs: Any = ()
    force: NonlinearForce | None = None
    excitation: Any = None
    load: SampledLoad | None = None
    spin: float = 0.0
    spin_ratio: float = 0.0
    force_uses_omega: bool = False
    param_scale: float = 1.0

    def __post_init__(self) -> None:
        n = _shape(self.mass, "mass")
        for name in ("mass", "stiffness", "damping", "gyroscopic"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _as_matrix(value, name, n))
        nl = np.array(self.nl_dofs, dtype=np.int64).reshape(-1)
        if len(np.unique(nl)) != nl.size or (nl.size and (nl.min() < 0 or nl.max() >= n)):
            raise ModelError(f"must be unique indices in [0, {n}), got {nl.tolist()}",
                             "HBProblem.nl_dofs")
        object.__setattr__(self, "nl_dofs", nl)
        if self.force is not None and (not callable(self.force) or nl.size == 0):
            raise ModelError("needs a callable and at least one nonlinear DOF",
                             "HBProblem.force")
        if self.excitation is not None and not callable(self.excitation):
            object.__setattr__(self, "excitation", _coefficients(self.excitation, n))
        if self.load is not None and not callable(self.load):
            raise ModelError("must be callable load(tau, omega, p)", "HBProblem.load")
        for name in ("spin", "spin_ratio"):
            if not math.isfinite(getattr(self, name)):
                raise ModelError("must be finite", f"HBProblem.{name}")
        if not (math.isfinite(self.param_scale) and self.param_scale > 0):
            raise ModelError("must be positive and finite", "HBProblem.param_scale")

    @property
    def n(self) -> int:
        """Number of unknowns ``n``."""
        return int(self.mass.shape[0])

    @property
    def k(self) -> int:
        """Number of nonlinear DOFs ``k``."""
        return int(self.nl_dofs.size)

    @cached_property
    def linear_dofs(self) -> IntArray:
        """Indices of the unknowns without nonlinear force (sorted)."""
        mask = np.ones(self.n, dtype=bool)
        mask[self.nl_dofs] = False
        return np.flatnonzero(mask).astype(np.int64)

    def spin_speed(self, omega: float) -> float:
        """``W = spin + spin_ratio * omega`` [rad/s]."""
        return self.spin + self.spin_ratio * omega

    def excitation_coefficients(self, aft: AFT, omega: float, param: float) -> FloatArray:
        """Coefficients (2H + 1, n) of ``f`` (``excitation`` plus the FFT of ``load``)."""
        out = np.zeros((aft.rows, self.n))
        if self.excitation is not None:
            coeff = self.excitation
            if callable(coeff):
                coeff = _coefficients(coeff(omega, param), self.n)
            out += resize(coeff, aft.harmonics)
        if self.load is not None:
            f = np.asarray(self.load(aft.tau, omega, param), dtype=float)
            if f.shape != (aft.samples, self.n) or not np.all(np.isfinite(f)):
                raise ModelError(f"must return finite values of shape ({aft.samples}, "
                                 f"{self.n}), got {f.shape}", "HBProblem.load")
            out += aft.to_frequency(f)
        return out

    def nonlinear(self, q: FloatArray, v: FloatArray, tau: FloatArray, omega: float,
                  param: float, *, tangents: bool = True) -> NonlinearSamples:
        """Call ``force`` and check its output; zeros without a force.

        ``tangents=False`` drops the tangents (for finite differences of ``f``).
        """
        N, k = q.shape
        if self.force is None:
            zero = np.zeros((N, k, k))
            return NonlinearSamples(np.zeros((N, k)), zero if tangents else None, None)
        f, dfdq, dfdv = self.force(q, v, tau, omega, param)
        f = _checked(f, (N, k), "f")
        if not tangents:
            return NonlinearSamples(f, None, None)
        return NonlinearSamples(f, _checked(dfdq, (N, k, k), "dfdq"),
                                None if dfdv is None else _checked(dfdv, (N, k, k), "dfdv"))

    def damping_matrix(self, omega: float) -> Matrix:
        """``C + W G`` (dense or CSR; zero matrix when both are absent)."""
        return self._combine([(1.0, self.damping), (self.spin_speed(omega), self.gyroscopic)])

    def damping_derivative(self) -> Matrix:
        """``d(C + W G) / d omega = spin_ratio * G``."""
        return self._combine([(self.spin_ratio, self.gyroscopic)])

    def _combine(self, terms: list[tuple[float, Matrix | None]]) -> Matrix:
        present = [(c, A) for c, A in terms if A is not None]
        if any(sp.issparse(A) for _, A in present):
            out = sp.csr_matrix((self.n, self.n))
            for c, A in present:  # a dense term added to a sparse one would give np.matrix
                out = out + c * sp.csr_matrix(A)
            return out.tocsr()
        dense = np.zeros((self.n, self.n))
        for c, A in present:
            dense += c * A
        return dense


def as_dense(A: Matrix) -> FloatArray:
    """``A`` as a float ndarray (``toarray()`` for a sparse matrix)."""
    return np.asarray(A.toarray() if sp.issparse(A) else A, dtype=np.float64)


def _shape(A: Matrix, name: str) -> int:
    shape = getattr(A, "shape", np.shape(A))
    if len(shape) != 2 or shape[0] != shape[1] or shape[0] == 0:
        raise ModelError(f"shape {tuple(shape)} is not square", f"HBProblem.{name}")
    return int(shape[0])


def _as_matrix(A: Matrix, name: str, n: int) -> Matrix:
    if _shape(A, name) != n:
        raise ModelError(f"shape {A.shape} differs from the mass matrix ({n}, {n})",
                         f"HBProblem.{name}")
    out = sp.csr_matrix(A, dtype=float) if sp.issparse(A) else np.array(A, dtype=float)
    if not np.all(np.isfinite(out.data if sp.issparse(out) else out)):
        raise ModelError("contains NaN or Inf", f"HBProblem.{name}")
    return out


def _coefficients(value: ArrayLike, n: int) -> FloatArray:
    arr = np.array(value, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != n or arr.shape[0] % 2 != 1:
        raise ModelError(f"needs shape (2m + 1, {n}), got {arr.shape}", "HBProblem.excitation")
    if not np.all(np.isfinite(arr)):
        raise ModelError("contains NaN or Inf", "HBProblem.excitation")
    return arr


def _checked(value: ArrayLike, shape: tuple[int, ...], name: str) -> FloatArray:
    arr = np.asarray(value, dtype=float)
    if arr.shape != shape:
        raise ModelError(f"returned {name} of shape {arr.shape}, expected {shape}",
                         "HBProblem.force")
    return arr
