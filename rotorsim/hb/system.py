"""A mechanical system for :mod:`rotorsim.hb`: matrices, nonlinear elements and forcing.

The equation of motion is

    M q'' + (C + W G) q' + K q + sum_e f_e(q_e, q_e') = sum_j p_j cos(h_j Omega t + phi_j),

with ``W = spin + spin_ratio * Omega`` [rad/s] scaling the gyroscopic matrix ``G``.
:class:`System` checks its input at the boundary (every error names the argument, the
element or the forcing at fault) and turns it into the rotor-agnostic
:class:`~rotorsim.harmonic_balance.problem.HBProblem` whose force callback gathers the
elements' forces and tangents onto the union of their DOFs.

References
----------
Seed 002 section 3.5.2.1, eqs 3.30-3.32 (the periodic problem).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.fourier import FloatArray, IntArray
from rotorsim.harmonic_balance.problem import HBProblem
from rotorsim.hb.elements import Element

WHERE = "hb.System"
MATRICES = ("mass", "stiffness", "damping", "gyroscopic")


@dataclass(frozen=True)
class Forcing:
    """Harmonic force ``amplitude cos(harmonic Omega t + phase)`` on one DOF.

    Parameters
    ----------
    dof : int
        DOF it acts on.
    amplitude : float
        [N] (a static force when ``harmonic = 0``).
    harmonic : int
        Multiple ``h >= 0`` of the response frequency ``Omega``.
    phase : float
        [rad].

    Examples
    --------
    >>> Forcing(1, 0.1).coefficients().tolist()    # (cos, sin) of harmonic 1
    [0.1, -0.0]
    """

    dof: int
    amplitude: float
    harmonic: int = 1
    phase: float = 0.0

    def __post_init__(self) -> None:
        if isinstance(self.harmonic, bool) or not isinstance(self.harmonic, int | np.integer) \
                or self.harmonic < 0:
            raise ModelError(f"must be an integer >= 0, got {self.harmonic!r}",
                             "Forcing.harmonic")
        if not (math.isfinite(self.amplitude) and math.isfinite(self.phase)):
            raise ModelError("amplitude and phase must be finite", "Forcing")

    def coefficients(self) -> FloatArray:
        """``(A cos phi, -A sin phi)`` of ``cos(h tau)``, ``sin(h tau)`` (``(A cos phi,)``
        for ``h = 0``)."""
        c, s = self.amplitude * math.cos(self.phase), -self.amplitude * math.sin(self.phase)
        return np.array([c] if self.harmonic == 0 else [c, s])


@dataclass(frozen=True, eq=False)
class System:
    """Linear matrices, nonlinear elements and harmonic forcing.

    Parameters
    ----------
    mass, stiffness : matrix (n, n) or float
        ``M`` [kg], ``K`` [N/m]: dense or scipy sparse; a number is a 1-DOF system.
    damping, gyroscopic : matrix (n, n) or float, optional
        ``C`` [N s/m] and ``G`` [N s/m per rad/s of spin].
    elements : sequence of Element
        Nonlinear elements (:mod:`rotorsim.hb.elements` or any object with ``dofs`` and
        ``evaluate``).
    forcing : Forcing, sequence of Forcing, or array-like (n,)
        External force. An array is the complex amplitude ``p`` of the fundamental,
        ``Re(p e^{i Omega t})`` (NLvib's ``Fex1``).
    spin, spin_ratio : float
        ``W = spin + spin_ratio * Omega`` [rad/s] multiplies ``G``.

    Examples
    --------
    Two masses, a cubic spring between them:

    >>> from rotorsim.hb.elements import CubicSpring
    >>> s = System(np.eye(2), [[2.0, -1.0], [-1.0, 1.0]], elements=[CubicSpring(0, 1.0, 1)],
    ...            forcing=[1.0, 0.0])
    >>> s.n, s.nl_dofs.tolist()
    (2, [0, 1])
    """

    mass: Any
    stiffness: Any
    damping: Any = None
    gyroscopic: Any = None
    elements: Sequence[Element] = ()
    forcing: Any = ()
    spin: float = 0.0
    spin_ratio: float = 0.0

    def __post_init__(self) -> None:
        n = _order(self.mass, "mass")
        for name in MATRICES:
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _matrix(value, name, n))
        elements = tuple(self.elements) if isinstance(self.elements, Sequence | tuple) \
            else (self.elements,)
        for i, element in enumerate(elements):
            _check_element(element, i, n)
        object.__setattr__(self, "elements", elements)
        if any(sp.issparse(getattr(self, name)) for name in MATRICES):
            for name in MATRICES:      # all sparse: a dense + sparse sum is an np.matrix
                value = getattr(self, name)
                if value is not None:
                    object.__setattr__(self, name, sp.csr_matrix(value))
        object.__setattr__(self, "forcing", _forcing(self.forcing, n))
        for name in ("spin", "spin_ratio"):
            if not math.isfinite(getattr(self, name)):
                raise ModelError("must be finite", f"{WHERE}.{name}")

    @property
    def n(self) -> int:
        """Number of DOFs."""
        return int(self.mass.shape[0])

    @cached_property
    def nl_dofs(self) -> IntArray:
        """Sorted union of the elements' DOFs."""
        dofs = [d for e in self.elements for d in e.dofs]
        return np.unique(np.array(dofs, dtype=np.int64))

    @cached_property
    def excitation(self) -> FloatArray:
        """Harmonic coefficients (2m + 1, n) of the forcing (layout of
        :mod:`rotorsim.harmonic_balance.fourier`), ``m`` its highest harmonic (at least 1)."""
        top = max([1, *(f.harmonic for f in self.forcing)])
        out = np.zeros((2 * top + 1, self.n))
        for f in self.forcing:
            rows = [0] if f.harmonic == 0 else [2 * f.harmonic - 1, 2 * f.harmonic]
            out[rows, f.dof] += f.coefficients()
        return out

    @cached_property
    def problem(self) -> HBProblem:
        """The :class:`~rotorsim.harmonic_balance.problem.HBProblem` of this system."""
        return HBProblem(self.mass, self.stiffness, self.damping, self.gyroscopic,
                         nl_dofs=self.nl_dofs, force=self._force if self.elements else None,
                         excitation=self.excitation, spin=self.spin,
                         spin_ratio=self.spin_ratio)

    @cached_property
    def _local(self) -> tuple[IntArray, ...]:
        """Positions of each element's DOFs among :attr:`nl_dofs`."""
        return tuple(np.searchsorted(self.nl_dofs, e.dofs).astype(np.int64)
                     for e in self.elements)

    def _force(self, q: FloatArray, v: FloatArray, tau: FloatArray, omega: float,
               param: float) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        """Force callback of the HBProblem: the elements' forces and tangents summed."""
        N, k = q.shape
        f, dfdq = np.zeros((N, k)), np.zeros((N, k, k))
        dfdv: FloatArray | None = None
        for i, (element, idx) in enumerate(zip(self.elements, self._local, strict=True)):
            fe, ke, ce = _checked(element.evaluate(q[:, idx], v[:, idx]), N, idx.size, i,
                                  element)
            f[:, idx] += fe
            block = np.ix_(np.arange(N), idx, idx)
            dfdq[block] += ke
            if ce is not None:
                dfdv = np.zeros((N, k, k)) if dfdv is None else dfdv
                dfdv[block] += ce
        return f, dfdq, dfdv


def _name(element: object, i: int) -> str:
    return f"{WHERE}.elements[{i}] ({type(element).__name__})"


def _check_element(element: object, i: int, n: int) -> None:
    if not (hasattr(element, "dofs") and callable(getattr(element, "evaluate", None))):
        raise ModelError("is not an element: it needs `dofs` and `evaluate(q, v)`",
                         _name(element, i))
    dofs = list(element.dofs)
    ints = all(isinstance(d, int | np.integer) and not isinstance(d, bool) for d in dofs)
    if not dofs or not ints or len(set(dofs)) != len(dofs):
        raise ModelError(f"dofs must be distinct integers, got {dofs!r}", _name(element, i))
    bad = [d for d in dofs if not 0 <= d < n]
    if bad:
        raise ModelError(f"DOF {bad[0]} is outside [0, {n}) of the {n}-DOF system",
                         _name(element, i))


def _checked(out: Any, N: int, d: int, i: int,
             element: object) -> tuple[FloatArray, FloatArray, FloatArray | None]:
    try:
        f, dfdq, dfdv = out
    except (TypeError, ValueError):
        raise ModelError("evaluate must return (f, dfdq, dfdv)", _name(element, i)) from None
    arrays = [np.asarray(f, dtype=float), np.asarray(dfdq, dtype=float),
              None if dfdv is None else np.asarray(dfdv, dtype=float)]
    for name, arr, shape in zip(("f", "dfdq", "dfdv"), arrays,
                                ((N, d), (N, d, d), (N, d, d)), strict=True):
        if arr is not None and arr.shape != shape:
            raise ModelError(f"returned {name} of shape {arr.shape}, expected {shape}",
                             _name(element, i))
    return arrays[0], arrays[1], arrays[2]  # type: ignore[return-value]


def _order(A: Any, name: str) -> int:
    shape = np.shape(np.atleast_2d(A)) if not sp.issparse(A) else A.shape
    if len(shape) != 2 or shape[0] != shape[1] or shape[0] == 0:
        raise ModelError(f"must be square, got shape {tuple(shape)}", f"{WHERE}.{name}")
    return int(shape[0])


def _matrix(A: Any, name: str, n: int) -> Any:
    if _order(A, name) != n:
        raise ModelError(f"shape {np.shape(np.atleast_2d(A)) if not sp.issparse(A) else A.shape}"
                         f" differs from the mass matrix ({n}, {n})", f"{WHERE}.{name}")
    out = sp.csr_matrix(A, dtype=float) if sp.issparse(A) else np.atleast_2d(
        np.array(A, dtype=float))
    if not np.all(np.isfinite(out.data if sp.issparse(out) else out)):
        raise ModelError("contains NaN or Inf", f"{WHERE}.{name}")
    return out


def _forcing(value: Any, n: int) -> tuple[Forcing, ...]:
    if isinstance(value, Forcing):
        value = (value,)
    items = list(value) if isinstance(value, Sequence | np.ndarray) else [value]
    if items and not any(isinstance(f, Forcing) for f in items):
        return _from_vector(value, n)
    for j, f in enumerate(items):
        if not isinstance(f, Forcing):
            raise ModelError(f"expected Forcing, got {type(f).__name__}",
                             f"{WHERE}.forcing[{j}]")
        if isinstance(f.dof, bool) or not isinstance(f.dof, int | np.integer) \
                or not 0 <= f.dof < n:
            raise ModelError(f"DOF {f.dof!r} is outside [0, {n}) of the {n}-DOF system",
                             f"{WHERE}.forcing[{j}]")
    return tuple(items)


def _from_vector(value: ArrayLike, n: int) -> tuple[Forcing, ...]:
    p = np.atleast_1d(np.asarray(value, dtype=complex))
    if p.shape != (n,) or not np.all(np.isfinite(p)):
        raise ModelError(f"a force vector needs {n} finite entries, got shape {p.shape}",
                         f"{WHERE}.forcing")
    return tuple(Forcing(int(j), float(abs(p[j])), 1, float(np.angle(p[j])))
                 for j in np.flatnonzero(p))
