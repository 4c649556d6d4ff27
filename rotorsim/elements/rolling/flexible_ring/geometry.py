"""Geometry of the flexible-ring roller bearing: ring sections, roller slices, contact law.

* :class:`RingSection`: area ``A``, in-plane second moment ``I`` and centre-line radius
  ``R_m`` of a bearing ring (seed 001 eqs 8-11, Fig. 3a). For the seed's rectangular
  sections the inner ring runs from the bore (or hollow-shaft) radius ``R_s`` to the inner
  raceway ``R_p - R_b``, the outer ring from the outer raceway ``R_p + R_b`` to the housing
  radius ``R_h``; both have the width ``b``.
* :class:`RollerSlices`: the slicing of a roller (seed 001 eqs 14-17, after de Mul et al.):
  slice widths ``h_k``, centre positions ``s_k`` from the roller's central section and
  profile drops ``c_k = R_b - b_k`` (``b_k`` the slice radius).
* :func:`line_contact_constant`: ``C_a`` of the Hertz line law ``q = C_a delta^n`` per unit
  length (seed 001 eq 16).

References
----------
Seed 001 (Leontiev, Ivannikov, Degtyarev 2017) eqs 8-11 and 14-17, Fig. 3a.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rotorsim.elements.rolling.roller.profile import RollerProfile, StraightProfile
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

SEED_LINE_FACTOR = 7.358
"""Length factor of seed 001 eq 16, ``C = pi E L / ((1 - nu^2) (7.358 L)^n)``."""


def _positive(value: float, name: str, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating) \
            or not math.isfinite(value) or value <= 0.0:
        raise ModelError(f"{name} must be a positive finite number, got {value!r}", where)
    return float(value)


@dataclass(frozen=True)
class RingSection:
    """Cross-section of a bearing ring treated as a curved rod (seed 001 section 2.2).

    Parameters
    ----------
    area : float
        Cross-section area ``A`` [m^2].
    inertia : float
        Second moment of area ``I`` [m^4] for bending in the plane of the ring.
    mean_radius : float
        Radius ``R_m`` of the centre line [m].

    Examples
    --------
    >>> s = RingSection.rectangular(0.0815, 0.097, 0.030)
    >>> round(s.area * 1e6, 3), round(s.mean_radius * 1e3, 3), round(s.inertia * 1e12)
    (465.0, 89.25, 9310)
    """

    area: float
    inertia: float
    mean_radius: float

    def validate(self, where: str) -> None:
        """Check that the three properties are positive and finite."""
        for name in ("area", "inertia", "mean_radius"):
            _positive(getattr(self, name), f"ring {name}", where)

    @classmethod
    def rectangular(cls, inner_radius: float, outer_radius: float, width: float,
                    where: str = "RingSection") -> RingSection:
        """Rectangular section between two radii [m] of the given axial width [m].

        ``A = b t``, ``I = b t^3 / 12``, ``R_m = (r_in + r_out) / 2`` with the radial
        thickness ``t = r_out - r_in``.
        """
        r_in = _positive(inner_radius, "inner radius", where)
        r_out = _positive(outer_radius, "outer radius", where)
        b = _positive(width, "ring width", where)
        if r_out <= r_in:
            raise ModelError(f"ring outer radius {r_out} m must exceed its inner radius "
                             f"{r_in} m", where)
        t = r_out - r_in
        return cls(area=b * t, inertia=b * t**3 / 12.0, mean_radius=0.5 * (r_in + r_out))

    def tension_stiffness(self, modulus: float, angle: float) -> float:
        """``E A theta / R_m`` [N/m]: radial stiffness of one segment in tension (eq 9)."""
        return modulus * self.area * angle / self.mean_radius

    def bending_rigidity(self, modulus: float, angle: float) -> float:
        """``E I theta`` [N m^2] of the bending energy of one segment (eq 10)."""
        return modulus * self.inertia * angle


@dataclass(frozen=True, eq=False)
class RollerSlices:
    """Slices of a roller: widths ``h_k``, centres ``s_k`` and drops ``c_k`` [m], each (K,).

    Examples
    --------
    >>> sl = RollerSlices.build(0.016, 4)
    >>> (sl.positions * 1e3).tolist(), round(float(sl.widths.sum()) * 1e3, 12)
    ([-6.0, -2.0, 2.0, 6.0], 16.0)
    """

    widths: FloatArray
    positions: FloatArray
    drops: FloatArray

    @property
    def count(self) -> int:
        """Number of slices ``K``."""
        return int(self.widths.size)

    @classmethod
    def build(cls, length: float, n_slices: int = 1,
              widths: Sequence[float] | FloatArray | None = None,
              profile: RollerProfile | None = None, where: str = "RollerSlices"
              ) -> RollerSlices:
        """Contiguous slices over the effective length ``L`` [m].

        Parameters
        ----------
        length : float
            Effective length ``L`` [m].
        n_slices : int
            ``K`` equal slices (used when ``widths`` is not given).
        widths : sequence of float, optional
            Slice widths ``h_k`` [m] from one end to the other; they must add up to ``L``
            (relative tolerance 1e-9).
        profile : RollerProfile, optional
            Crowning of the roller; its drop at each slice centre is ``c_k = R_b - b_k``
            [m] (a drop of the roller itself: it relieves both contacts). Default straight.
        where : str
            Name used in messages.
        """
        ell = _positive(length, "effective length", where)
        prof = StraightProfile() if profile is None else profile
        if widths is None:
            if isinstance(n_slices, bool) or not isinstance(n_slices, int | np.integer) \
                    or n_slices < 1:
                raise ModelError(f"n_slices must be an integer >= 1, got {n_slices!r}", where)
            h = np.full(int(n_slices), ell / int(n_slices))
        else:
            h = np.asarray(widths, dtype=float).reshape(-1)
            if h.size == 0 or not np.all(np.isfinite(h)) or np.any(h <= 0.0):
                raise ModelError(f"slice widths must be positive finite numbers, got "
                                 f"{np.asarray(widths).tolist()!r}", where)
            if not math.isclose(float(h.sum()), ell, rel_tol=1e-9):
                raise ModelError(f"slice widths add up to {float(h.sum()):.9g} m, not the "
                                 f"effective length L = {ell:.9g} m", where)
        edges = np.concatenate([[0.0], np.cumsum(h)])
        centres = 0.5 * (edges[:-1] + edges[1:]) - 0.5 * float(edges[-1])
        prof.validate(ell, where)
        drops = np.asarray(prof.drop(centres / ell, ell), dtype=float)
        if not np.all(np.isfinite(drops)):
            raise ModelError("the roller profile has an infinite drop at a slice centre",
                             where)
        return cls(widths=h, positions=centres, drops=drops)


def line_contact_constant(modulus: float, poisson: float, length: float,
                          exponent: float = 10.0 / 9.0) -> float:
    """Line-contact constant ``C_a`` per unit length [N/m^(1+n)] (seed 001 eq 16).

    ``C_a = pi E L / ((1 - nu^2) (7.358 L)^n)`` for a roller and a raceway of the same
    material; the line load of a slice is ``q = C_a delta^n`` [N/m]. A uniformly
    compressed roller of length ``L`` carries ``Q = C_a L delta^n`` per contact: for steel
    this is within 7 % of Palmgren's per-contact law (seed 002 eq 2.6).

    Parameters
    ----------
    modulus : float
        Young's modulus ``E`` [Pa].
    poisson : float
        Poisson ratio ``nu``.
    length : float
        Effective roller length ``L`` [m] (enters in SI units).
    exponent : float
        ``n`` (10/9 for a line contact).

    Examples
    --------
    >>> f"{line_contact_constant(2e11, 0.3, 0.016):.4e}"
    '1.1902e+11'
    """
    where = "line_contact_constant"
    e = _positive(modulus, "E", where)
    ell = _positive(length, "length", where)
    n = _positive(exponent, "exponent", where)
    if not (math.isfinite(poisson) and -1.0 < poisson < 0.5):
        raise ModelError(f"Poisson ratio must be in (-1, 0.5), got {poisson!r}", where)
    return math.pi * e * ell / ((1.0 - poisson**2) * (SEED_LINE_FACTOR * ell) ** n)
