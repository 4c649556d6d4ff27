"""A roller between two raceways: Hertz line contacts in series with its centrifugal force.

The contact law is the one of the rest of the package
(:mod:`rotorsim.elements.rolling.contact.hertz_line`): a roller squeezed by the total approach
``Delta`` of the two raceways carries ``Q = Kn Delta^n`` with ``n = 10/9`` and the
whole-roller constant ``Kn`` (ISO/TS 16281 ``c_L = 35948 L^(8/9)`` N/mm^(10/9) by default,
as :class:`~rotorsim.elements.rolling.roller.bearing.RollerBearing`). Each of the two contacts has
the per-contact constant ``K_c = 2^n Kn`` (two equal contacts in series give back ``Kn``:
:func:`~rotorsim.elements.rolling.contact.hertz_line.roller_constant_from_contacts`), the same split
as :mod:`~rotorsim.elements.rolling.centrifugal`.

The roller is a rigid body with one DOF, its radial position. With the raceway deflections
``w_i``, ``w_e`` (outwards) and the diametral clearance ``g`` (seed 001 eq 13, ``g/4`` per
contact), the approach is ``Delta = -g/2 + w_i - w_e``; if ``a`` is the outer-contact
deflection, the inner one is ``Delta - a``. The roller potential (seed 001 eqs 17-19, with
the centrifugal force ``F_c = m omega_c^2 R_p`` of eq 18 taken constant)::

    Pi(a) = U(Delta - a) + U(a) - F_c a,      U(d) = K_c max(d, 0)^(n+1) / (n+1)

is minimised by the roller: ``Q_e = Q_i + F_c`` (eq 20, first row). When
``Delta <= a_0 = (F_c / K_c)^(1/n)`` the roller rides on the outer raceway alone
(``Q_i = 0``, ``Q_e = F_c``). The condensed energy ``phi(Delta) = min_a Pi`` has the
derivative ``Q_i`` (envelope theorem) and the second derivative ``k_i k_e / (k_i + k_e)``,
the two contact stiffnesses ``k = n K_c d^(n-1)`` in series (eqs 23-26). Eliminating the
roller position leaves the force ``F_c`` on the outer ring as a constant load.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.contact.hertz_line import (
    LINE_EXPONENT,
    roller_constant_from_contacts,
)
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

_BISECTIONS = 80
"""Bisection steps of the roller position: the bracket shrinks below round-off."""


@dataclass(frozen=True)
class ContactState:
    """Loads, deflections, stiffness and energy of ``Z`` rollers (arrays ``(Z,)``).

    Attributes
    ----------
    inner_load, outer_load : array
        ``Q_i``, ``Q_e = Q_i + F_c`` [N].
    inner_deflection, outer_deflection : array
        Contact deflections ``Delta - a`` and ``a`` [m] (0 for an open contact).
    stiffness : array
        ``dQ_i / dDelta`` [N/m].
    energy : array
        Condensed roller energy ``phi(Delta)`` [J] (0 for an open contact without
        centrifugal force).
    """

    inner_load: FloatArray
    outer_load: FloatArray
    inner_deflection: FloatArray
    outer_deflection: FloatArray
    stiffness: FloatArray
    energy: FloatArray


@dataclass(frozen=True)
class RollerContactLaw:
    """Condensed law ``Q_i(Delta)`` of a roller between two raceways (module docstring).

    Parameters
    ----------
    kn : float
        Whole-roller constant ``Kn`` [N/m^n].
    centrifugal_force : float
        ``F_c`` [N], ``>= 0``.
    exponent : float
        ``n`` (10/9).

    Examples
    --------
    >>> law = RollerContactLaw(kn=1.0e9)
    >>> st = law.evaluate([10e-6, -1e-6])
    >>> round(float(st.inner_load[0]), 3), float(st.inner_load[1])
    (2782.559, 0.0)
    >>> fast = RollerContactLaw(kn=1.0e9, centrifugal_force=400.0).evaluate([10e-6])
    >>> round(float(fast.outer_load[0] - fast.inner_load[0]), 6)
    400.0
    """

    kn: float
    centrifugal_force: float = 0.0
    exponent: float = LINE_EXPONENT

    def __post_init__(self) -> None:
        where = "RollerContactLaw"
        if not (math.isfinite(self.kn) and self.kn > 0.0):
            raise ModelError(f"kn must be positive and finite, got {self.kn!r}", where)
        if not (math.isfinite(self.centrifugal_force) and self.centrifugal_force >= 0.0):
            raise ModelError(f"centrifugal_force must be finite and >= 0, got "
                             f"{self.centrifugal_force!r}", where)
        if not (math.isfinite(self.exponent) and self.exponent >= 1.0):
            raise ModelError(f"exponent must be >= 1, got {self.exponent!r}", where)

    @property
    def contact_constant(self) -> float:
        """Per-contact constant ``K_c = 2^n Kn`` [N/m^n].

        Examples
        --------
        >>> law = RollerContactLaw(kn=1.0e9)
        >>> from rotorsim.elements.rolling.contact.hertz_line import roller_constant_from_contacts
        >>> k = law.contact_constant
        >>> round(roller_constant_from_contacts(k, k) / 1e9, 12)
        1.0
        """
        return float(self.kn * 2.0**self.exponent)

    @property
    def outer_rest_deflection(self) -> float:
        """``a_0 = (F_c / K_c)^(1/n)`` [m]: outer deflection of a roller on the outer race."""
        return float((self.centrifugal_force / self.contact_constant) ** (1.0 / self.exponent))

    def whole_roller_constant(self) -> float:
        """``Kn`` recomputed from the two contact constants in series (consistency check)."""
        k = self.contact_constant
        return roller_constant_from_contacts(k, k, self.exponent)

    def _outer_deflection(self, delta: FloatArray, a0: float) -> FloatArray:
        """Solve ``a^n - (delta - a)^n = a_0^n`` for ``a`` in ``(delta/2, delta)`` by bisection."""
        n = self.exponent
        lo, hi = 0.5 * delta, delta.copy()
        target = a0**n
        for _ in range(_BISECTIONS):
            mid = 0.5 * (lo + hi)
            high = mid**n - np.maximum(delta - mid, 0.0) ** n > target
            hi = np.where(high, mid, hi)
            lo = np.where(high, lo, mid)
        return np.asarray(0.5 * (lo + hi))

    def evaluate(self, delta: ArrayLike) -> ContactState:
        """Roller loads, deflections, condensed stiffness and energy at approaches ``delta``.

        Parameters
        ----------
        delta : array (Z,)
            Total approach ``Delta`` of the raceways at each roller [m] (negative: gap).
        """
        d = np.asarray(delta, dtype=float)
        n, kc, fc = self.exponent, self.contact_constant, self.centrifugal_force
        a0 = self.outer_rest_deflection
        closed = d > a0
        if fc > 0.0:
            a = np.where(closed, self._outer_deflection(np.where(closed, d, 2.0 * a0), a0), a0)
        else:
            a = 0.5 * np.maximum(d, 0.0)
        x = np.where(closed, d - a, 0.0)
        q_i = kc * x**n
        k_i = n * kc * x ** (n - 1.0)
        k_e = n * kc * a ** (n - 1.0)
        both = (k_i > 0.0) & (k_e > 0.0)
        stiffness = np.where(both, k_i * k_e / np.where(both, k_i + k_e, 1.0), 0.0)
        energy = kc * (x ** (n + 1.0) + a ** (n + 1.0)) / (n + 1.0) - fc * a
        return ContactState(q_i, q_i + fc, x, a, stiffness, energy)
