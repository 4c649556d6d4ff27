"""Nonlinear elements of :mod:`rotorsim.hb`: the :class:`Element` protocol and a library.

An element acts on a few DOFs of the system and returns, batched over the ``N`` time
samples of one period (STYLE practice 3), its restoring force and the exact tangents::

    element.dofs                        -> tuple of d DOF indices
    element.evaluate(q, v)              -> (f, dfdq, dfdv)
        q, v  : (N, d)  displacements [m] and velocities [m/s] of those DOFs
        f     : (N, d)  force the element exerts ON the structure, with the sign of a
                        restoring force (it enters ``M q'' + C q' + K q + f = p``) [N]
        dfdq  : (N, d, d)  df_i / dq_j [N/m]
        dfdv  : (N, d, d)  df_i / dv_j [N s/m], or None when f does not depend on v

Any object with these two members is an element (:class:`Element` is a ``Protocol``); the
tangents must be the exact derivatives (``rotorsim.hb.check_tangents`` compares them with
finite differences).

The library elements are one-dimensional: they act along the relative coordinate
``u = q[dof] - q[other]`` (``u = q[dof]`` when grounded), ``f = law(u, u')`` on ``dof``
and ``-f`` on ``other`` (the force direction ``w = (1, -1)`` of NLvib):

* :class:`CubicSpring`  ``f = k3 u^3``;
* :class:`UnilateralSpring`  ``f = k (u - g)`` for ``u > g``, else 0 (contact after a gap
  ``g >= 0``; ``side=-1`` for contact at ``u < -g``);
* :class:`BilateralGap`  ``f = k (u - g)`` for ``u > g``, ``k (u + g)`` for ``u < -g``,
  else 0 (clearance ``g`` on both sides);
* :class:`HertzContact`  ``f = k max(u - g, 0)^e`` (``e = 3/2`` by default; ``side=-1``
  as above);
* :class:`CoulombFriction`  ``f = F tanh(u' / eps)`` (regularised dry friction).

A piecewise law takes the left-sided value at its switching point (the contact force is
zero at ``u = g`` either way); its tangent there is the one of the open gap.

References
----------
M. Krack, J. Gross, *Harmonic Balance for Nonlinear Vibration Problems*, Springer 2019,
section 2.3 and the NLvib element types (cubicSpring, unilateralSpring, tanhDryFriction).
K. L. Johnson, *Contact Mechanics*, Cambridge 1985, section 4.2 (Hertz, ``F ~ delta^3/2``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.fourier import FloatArray

Tangents = tuple[FloatArray, FloatArray, FloatArray | None]
"""``(f (N, d), dfdq (N, d, d), dfdv (N, d, d) or None)``."""


@runtime_checkable
class Element(Protocol):
    """What a nonlinear element provides (see the module docstring)."""

    @property
    def dofs(self) -> tuple[int, ...]: ...

    def evaluate(self, q: FloatArray, v: FloatArray) -> Tangents: ...


class _Scalar:
    """An element along ``u = q[dof] - q[other]`` (base of the library elements, which
    are frozen dataclasses declaring ``dof``, their parameters, then ``other``)."""

    dof: int
    other: int | None

    @property
    def dofs(self) -> tuple[int, ...]:
        """``(dof,)`` or ``(dof, other)``."""
        return (self.dof,) if self.other is None else (self.dof, self.other)

    @property
    def _direction(self) -> FloatArray:
        return np.array([1.0] if self.other is None else [1.0, -1.0])

    def law(self, u: FloatArray, du: FloatArray) -> tuple[FloatArray, FloatArray,
                                                          FloatArray | None]:
        """Scalar force and derivatives ``(f, df/du, df/du')`` at ``u, u'`` (N,)."""
        raise NotImplementedError

    def evaluate(self, q: FloatArray, v: FloatArray) -> Tangents:
        """Force and tangents on :attr:`dofs` (module docstring), batched over samples."""
        w = self._direction
        f, dfdu, dfdv = self.law(q @ w, v @ w)
        ww = np.outer(w, w)
        return (f[:, None] * w, dfdu[:, None, None] * ww,
                None if dfdv is None else dfdv[:, None, None] * ww)

    def _check(self, **values: float) -> None:
        """Reject a bad DOF (not an integer, or ``other == dof``) and non-finite values."""
        name = type(self).__name__
        for key, index in (("dof", self.dof), ("other", self.other)):
            if index is not None and (isinstance(index, bool)
                                      or not isinstance(index, int | np.integer)):
                raise ModelError(f"{key} must be an integer DOF index, got {index!r}", name)
        if self.other is not None and self.other == self.dof:
            raise ModelError(f"other = dof = {self.dof}: an element needs two different DOFs",
                             name)
        for key, value in values.items():
            if not math.isfinite(value):
                raise ModelError(f"{key} must be finite, got {value!r}", name)


@dataclass(frozen=True)
class CubicSpring(_Scalar):
    """Cubic spring ``f = k3 u^3`` (``k3 < 0`` softens).

    Parameters
    ----------
    dof : int
        DOF the spring acts on.
    k3 : float
        Cubic stiffness [N/m^3].
    other : int, optional
        Second DOF (spring between ``dof`` and ``other``); grounded if omitted.

    Examples
    --------
    >>> f, dfdq, dfdv = CubicSpring(0, 2.0).evaluate(np.array([[0.5]]), np.zeros((1, 1)))
    >>> float(f[0, 0]), float(dfdq[0, 0, 0]), dfdv
    (0.25, 1.5, None)
    """

    dof: int
    k3: float
    other: int | None = None

    def __post_init__(self) -> None:
        self._check(k3=self.k3)

    def law(self, u: FloatArray, du: FloatArray) -> tuple[FloatArray, FloatArray, None]:
        """``k3 u^3`` and ``3 k3 u^2``."""
        return self.k3 * u**3, 3.0 * self.k3 * u**2, None


@dataclass(frozen=True)
class UnilateralSpring(_Scalar):
    """Spring that engages after a gap: ``f = k (s u - g)`` for ``s u > g`` (times ``s``).

    Parameters
    ----------
    dof : int
    stiffness : float
        Contact stiffness ``k > 0`` [N/m].
    gap : float
        Gap ``g >= 0`` [m] before contact.
    other : int, optional
    side : {1, -1}
        Contact at ``u > g`` (1) or at ``u < -g`` (-1).

    Examples
    --------
    >>> el = UnilateralSpring(0, stiffness=100.0, gap=1.0)
    >>> f, dfdq, _ = el.evaluate(np.array([[0.5], [1.5]]), np.zeros((2, 1)))
    >>> f.ravel().tolist(), dfdq.ravel().tolist()
    ([0.0, 50.0], [0.0, 100.0])
    """

    dof: int
    stiffness: float
    gap: float = 0.0
    other: int | None = None
    side: int = 1

    def __post_init__(self) -> None:
        self._check(stiffness=self.stiffness, gap=self.gap)
        _positive(self, "stiffness", self.stiffness)
        _gap(self, self.gap)
        _side(self, self.side)

    def law(self, u: FloatArray, du: FloatArray) -> tuple[FloatArray, FloatArray, None]:
        """``s k max(s u - g, 0)`` and ``k [s u > g]``."""
        s = self.side * u - self.gap
        on = s > 0.0
        return (self.side * self.stiffness * np.where(on, s, 0.0),
                np.where(on, self.stiffness, 0.0), None)


@dataclass(frozen=True)
class BilateralGap(_Scalar):
    """Clearance ``g`` on both sides: ``f = k (u - g)`` above ``g``, ``k (u + g)`` below
    ``-g``, 0 between (a journal in a bearing clearance along one axis).

    Parameters
    ----------
    dof : int
    stiffness : float
        Contact stiffness ``k > 0`` [N/m].
    gap : float
        Clearance ``g >= 0`` [m] on each side.
    other : int, optional

    Examples
    --------
    >>> el = BilateralGap(0, stiffness=10.0, gap=1.0)
    >>> el.evaluate(np.array([[-2.0], [0.3], [1.5]]), np.zeros((3, 1)))[0].ravel().tolist()
    [-10.0, 0.0, 5.0]
    """

    dof: int
    stiffness: float
    gap: float = 0.0
    other: int | None = None

    def __post_init__(self) -> None:
        self._check(stiffness=self.stiffness, gap=self.gap)
        _positive(self, "stiffness", self.stiffness)
        _gap(self, self.gap)

    def law(self, u: FloatArray, du: FloatArray) -> tuple[FloatArray, FloatArray, None]:
        """``k (u - g sign u)`` outside the clearance and its slope ``k``."""
        on = np.abs(u) > self.gap
        return (self.stiffness * np.where(on, u - self.gap * np.sign(u), 0.0),
                np.where(on, self.stiffness, 0.0), None)


@dataclass(frozen=True)
class HertzContact(_Scalar):
    """Hertzian contact after a clearance: ``f = s k max(s u - g, 0)^e``.

    Parameters
    ----------
    dof : int
    stiffness : float
        ``k > 0`` [N/m^e].
    gap : float
        Clearance ``g >= 0`` [m].
    exponent : float
        ``e >= 1`` (3/2 for a point contact, 10/9 for a line contact).
    other : int, optional
    side : {1, -1}

    Examples
    --------
    >>> el = HertzContact(0, stiffness=8.0, gap=0.5)
    >>> f, dfdq, _ = el.evaluate(np.array([[1.5]]), np.zeros((1, 1)))
    >>> float(f[0, 0]), float(dfdq[0, 0, 0])
    (8.0, 12.0)
    """

    dof: int
    stiffness: float
    gap: float = 0.0
    exponent: float = 1.5
    other: int | None = None
    side: int = 1

    def __post_init__(self) -> None:
        self._check(stiffness=self.stiffness, gap=self.gap, exponent=self.exponent)
        _positive(self, "stiffness", self.stiffness)
        _gap(self, self.gap)
        _side(self, self.side)
        if self.exponent < 1.0:
            raise ModelError(f"exponent must be >= 1, got {self.exponent}",
                             "HertzContact.exponent")

    def law(self, u: FloatArray, du: FloatArray) -> tuple[FloatArray, FloatArray, None]:
        """``s k d^e`` and ``k e d^(e-1)`` with the penetration ``d = max(s u - g, 0)``."""
        d = np.maximum(self.side * u - self.gap, 0.0)
        slope = np.where(d > 0.0, self.exponent * self.stiffness
                         * d ** (self.exponent - 1.0), 0.0)
        return self.side * self.stiffness * d**self.exponent, slope, None


@dataclass(frozen=True)
class CoulombFriction(_Scalar):
    """Regularised dry friction ``f = F tanh(u' / eps)`` on the relative velocity.

    Parameters
    ----------
    dof : int
    limit_force : float
        Friction limit ``F = mu N > 0`` [N].
    eps : float
        Regularisation velocity ``> 0`` [m/s]: below it the friction acts like a viscous
        damper ``F / eps``.
    other : int, optional

    Examples
    --------
    >>> el = CoulombFriction(0, limit_force=2.0, eps=0.1)
    >>> f, dfdq, dfdv = el.evaluate(np.zeros((1, 1)), np.array([[0.0]]))
    >>> float(f[0, 0]), float(dfdq[0, 0, 0]), float(dfdv[0, 0, 0])
    (0.0, 0.0, 20.0)
    """

    dof: int
    limit_force: float
    eps: float
    other: int | None = None

    def __post_init__(self) -> None:
        self._check(limit_force=self.limit_force, eps=self.eps)
        _positive(self, "limit_force", self.limit_force)
        _positive(self, "eps", self.eps)

    def law(self, u: FloatArray, du: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``F tanh(u'/eps)``, 0 and ``F (1 - tanh^2) / eps``."""
        t = np.tanh(du / self.eps)
        return self.limit_force * t, np.zeros_like(u), self.limit_force * (1.0 - t * t) / self.eps


def _positive(element: object, name: str, value: float) -> None:
    if not value > 0.0:
        raise ModelError(f"must be > 0, got {value!r}", f"{type(element).__name__}.{name}")


def _gap(element: object, value: float) -> None:
    if value < 0.0:
        raise ModelError(f"must be >= 0 (a clearance), got {value!r}",
                         f"{type(element).__name__}.gap")


def _side(element: object, value: int) -> None:
    if value not in (1, -1):
        raise ModelError(f"must be 1 or -1, got {value!r}", f"{type(element).__name__}.side")
