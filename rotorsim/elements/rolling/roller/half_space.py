"""Finite line contact of a profiled roller on a half-space, by influence coefficients.

The contact area ``|x| <= w`` (across, rolling direction), ``|y| <= L/2`` (along the
roller, effective length ``L``) is cut into ``K`` slices along ``y`` and ``M`` strips
across ``x`` (seed 002 section 2.3.3, eqs 2.26-2.27, Figure 2.11: slices with strips).
The initial gap of a roller of reduced radius ``R`` and profile drop ``c(y)`` is
``x^2/(2R) + c(y)``; the pressures of the rectangles solve the complementarity problem of
:mod:`~rotorsim.elements.rolling.contact.influence` for an approach ``delta0 + theta y``
(:meth:`HalfSpaceLineContact.solve`) or for a given total load
(:meth:`HalfSpaceLineContact.solve_load`, the approach an unknown of the same active-set
iteration). The pressure is even in ``x``: only ``x >= 0`` is discretised, each strip
with its mirror image in the influence matrix (``N = K M`` unknowns).

Limits: frictionless half-space (no ``mu`` term of eq 2.26), both bodies elastic
half-spaces (the roller end is not a free surface: quarter-space effects are not
modelled), so the approach is the half-space approach relative to points far away.

Cost: the matrix ``(K M)^2`` is built once per geometry (block Toeplitz: ``K M^2``
influence coefficients); a solve is a few dense factorisations of the contact set, about
``(K M)^3 / 3`` flops each (``K = 40``, ``M = 12``: a few ms each).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.contact.hertz_point import (
    BEARING_STEEL_E,
    BEARING_STEEL_NU,
    effective_modulus,
)
from rotorsim.elements.rolling.contact.influence import (
    check_positive,
    rectangle_influence,
    solve_contact,
)
from rotorsim.elements.rolling.roller.profile import RollerProfile, StraightProfile
from rotorsim.errors import ConvergenceError, ModelError

FloatArray = NDArray[np.float64]


def hertz_line(line_load: float, reduced_radius: float, e_star: float) -> tuple[float, float]:
    """Hertz line contact ``(p0, b)``: ``p0 = sqrt(w E*/(pi R))`` [Pa] and
    ``b = sqrt(4 w R/(pi E*))`` [m] for the load per length ``w`` [N/m] (Johnson 1985,
    eqs 4.43-4.45; ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2``).

    Examples
    --------
    >>> p0, b = hertz_line(1e6, 0.005, 1.13e11)
    >>> round(p0 / 1e9, 4), round(b * 1e6, 2)
    (2.6821, 237.36)
    """
    p0 = math.sqrt(line_load * e_star / (math.pi * reduced_radius))
    return p0, 2.0 * line_load / (math.pi * p0)


@dataclass(frozen=True, eq=False)
class LineContactSolution:
    """Pressure field of :class:`HalfSpaceLineContact` (arrays over slices ``K`` and the
    strips ``M`` of ``x >= 0``).

    Attributes
    ----------
    y : (K,) slice centres [m];  x : (M,) strip centres [m] (``x >= 0``).
    pressure : (K, M) [Pa];  slice_load : (K,) [N];  line_load : (K,) [N/m].
    peak : (K,) largest pressure of each slice [Pa].
    load : total load [N];  moment : ``sum y q`` [N m] about the roller centre.
    approach : ``delta0`` [m];  tilt : ``theta`` [rad];  iterations : active-set steps.
    truncated : whether the outermost strip carries pressure (grid too narrow).
    """

    y: FloatArray
    x: FloatArray
    pressure: FloatArray
    slice_load: FloatArray
    line_load: FloatArray
    peak: FloatArray
    load: float
    moment: float
    approach: float
    tilt: float
    iterations: int
    truncated: bool


@dataclass(frozen=True, eq=False)
class HalfSpaceLineContact:
    """Roller-raceway line contact on a half-space, sliced (module docstring).

    Parameters
    ----------
    length : float
        Effective length ``L`` [m].
    reduced_radius : float
        ``R`` [m] across the contact (``1/R = 1/R_roller + 1/R_race``).
    e_star : float
        Contact modulus ``E*`` [Pa], ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2`` (steel on
        steel about 1.13e11; note ``E' = 2 E*`` of
        :mod:`~rotorsim.elements.rolling.roller.profile`).
    half_width : float
        Half-width ``w`` [m] of the grid across the contact; must exceed the contact
        half-width everywhere (``truncated`` in the solution says when it does not).
    profile : RollerProfile
        Drop ``c(y)`` along the roller (straight by default).
    n_slices, n_strips : int
        ``K`` slices along the length and ``M`` strips on ``0 <= x <= w``.

    Examples
    --------
    >>> c = HalfSpaceLineContact(0.02, 0.005, 1.13e11, 3e-4, n_slices=10, n_strips=6)
    >>> s = c.solve_load(5000.0)
    >>> round(s.load, 6), bool(s.peak[0] > s.peak[4])
    (5000.0, True)
    """

    length: float
    reduced_radius: float
    e_star: float
    half_width: float
    profile: RollerProfile = field(default_factory=StraightProfile)
    n_slices: int = 40
    n_strips: int = 12

    def __post_init__(self) -> None:
        where = "HalfSpaceLineContact"
        for name in ("length", "reduced_radius", "e_star", "half_width"):
            check_positive(getattr(self, name), name, where)
        for name in ("n_slices", "n_strips"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ModelError(f"{name} must be an integer >= 1, got {value!r}", where)
        self.profile.validate(self.length, where)

    @classmethod
    def for_load(cls, load: float, length: float, reduced_radius: float, e_star: float,
                 profile: RollerProfile | None = None, n_slices: int = 40,
                 n_strips: int = 12, width_factor: float = 1.6) -> HalfSpaceLineContact:
        """Grid of half-width ``width_factor`` times the Hertz half-width of the mean line
        load ``load / L`` [N]; ``width_factor`` leaves room for the wider edge zones."""
        b = hertz_line(check_positive(load, "load", "HalfSpaceLineContact") / length,
                       reduced_radius, e_star)[1]
        return cls(length, reduced_radius, e_star, width_factor * b,
                   StraightProfile() if profile is None else profile, n_slices, n_strips)

    @cached_property
    def y(self) -> FloatArray:
        """Slice centres (K,) [m]."""
        return (-0.5 + (np.arange(self.n_slices) + 0.5) / self.n_slices) * self.length

    @cached_property
    def x(self) -> FloatArray:
        """Strip centres (M,) [m] on ``x >= 0``."""
        return np.asarray((np.arange(self.n_strips) + 0.5) * (self.half_width / self.n_strips),
                          dtype=float)

    @cached_property
    def area(self) -> float:
        """Area of one rectangle of the half grid, counted twice (mirror) [m^2]."""
        return 2.0 * (self.half_width / self.n_strips) * (self.length / self.n_slices)

    @cached_property
    def compliance(self) -> FloatArray:
        """``C`` (K M, K M) [m/Pa]: displacement at each centre per unit pressure on each
        rectangle and its mirror image ``x -> -x`` (read-only). Equal slices: the blocks
        depend on ``|i - k|`` only (block Toeplitz), so ``K M^2`` coefficients are
        computed and gathered."""
        hx, hy = 0.5 * self.half_width / self.n_strips, 0.5 * self.length / self.n_slices
        x, dy = self.x, (self.y - self.y[0])[:, None, None]  # (K, 1, 1) slice offsets
        d = (rectangle_influence(x[:, None] - x[None, :], dy, hx, hy)
             + rectangle_influence(x[:, None] + x[None, :], dy, hx, hy))  # (K, M, M)
        k = np.arange(self.n_slices)
        blocks = d[np.abs(k[:, None] - k[None, :])]  # (K, K, M, M)
        n = self.n_slices * self.n_strips
        c = np.asarray(blocks.transpose(0, 2, 1, 3).reshape(n, n) / (math.pi * self.e_star),
                       dtype=float)
        c.flags.writeable = False
        return c

    @cached_property
    def gap(self) -> FloatArray:
        """Initial gap ``x^2/(2R) + c(y)`` (K M,) [m]."""
        drop = self.profile.drop(self.y / self.length, self.length)
        return np.asarray((drop[:, None] + self.x[None, :] ** 2
                           / (2.0 * self.reduced_radius)).ravel())

    def solve(self, approach: float, tilt: float = 0.0) -> LineContactSolution:
        """Pressures for the approach ``delta0 + theta y`` (``approach`` [m], ``tilt``
        [rad])."""
        yy = np.repeat(self.y, self.n_strips)
        p, it = solve_contact(self.compliance, approach + tilt * yy - self.gap)
        return self._solution(p, approach, tilt, it)

    def solve_load(self, load: float, tilt: float = 0.0, max_iter: int = 60
                   ) -> LineContactSolution:
        """Pressures and approach for the total load ``load`` [N] at the tilt [rad]."""
        load = check_positive(load, "load", "HalfSpaceLineContact.solve_load")
        c, g = self.compliance, self.gap - tilt * np.repeat(self.y, self.n_strips)
        active = g <= g.min() + 1e-12 * max(abs(g.min()), 1e-30)
        n = g.size
        for it in range(1, max_iter + 1):
            idx = np.flatnonzero(active)
            m = np.zeros((idx.size + 1, idx.size + 1))
            m[:-1, :-1] = c[np.ix_(idx, idx)]
            m[:-1, -1], m[-1, :-1] = -1.0, self.area
            sol = np.linalg.solve(m, np.concatenate([-g[idx], [load]]))
            p = np.zeros(n)
            p[idx], approach = sol[:-1], float(sol[-1])
            negative = p < 0.0
            penetration = approach - g - c @ np.maximum(p, 0.0)
            adding = ~active & (penetration > 1e-9 * max(abs(approach), 1e-30))
            if not negative.any() and not adding.any():
                return self._solution(p, approach, tilt, it)
            active = active & ~negative if negative.any() else active | adding
        raise ConvergenceError("load-controlled contact solve did not settle",
                               "HalfSpaceLineContact.solve_load", iteration=max_iter)

    def _solution(self, p: FloatArray, approach: float, tilt: float, it: int
                  ) -> LineContactSolution:
        pressure = np.maximum(p, 0.0).reshape(self.n_slices, self.n_strips)
        q = pressure.sum(axis=1) * self.area
        return LineContactSolution(
            y=self.y, x=self.x, pressure=pressure, slice_load=q,
            line_load=q / (self.length / self.n_slices), peak=pressure.max(axis=1),
            load=float(q.sum()), moment=float(self.y @ q), approach=approach, tilt=tilt,
            iterations=it, truncated=bool((pressure[:, -1] > 0.0).any()))


def roller_pressure_field(bearing: Any, delta: ArrayLike, psi: ArrayLike, roller: int,
                          race: str = "inner", e_star: float | None = None,
                          n_strips: int = 12) -> LineContactSolution:
    """Pressure field of one roller of a ``RollerBearing`` on one race, on a half-space.

    The roller's load ``Q_j`` (the bearing's own ``Kn`` law) and its tilt
    ``omega_j`` (the slope of its slice deflections) are put on a
    :class:`HalfSpaceLineContact` of the bearing's profile, length and ``n_slices``, with
    the reduced radius ``D (1 -+ gamma) / 2`` of the race (``gamma = D cos a0 / d_m``):
    the edge peak of the roller at the resolution of its slices.

    Parameters
    ----------
    bearing : RollerBearing
    delta : array (5,)
        Relative displacement ``[x, y, z, rx, ry]`` [m, rad].
    psi : array (Z,)
        Roller angles [rad].
    roller : int
        Index ``j`` of the roller.
    race : {"inner", "outer"}
    e_star : float
        Contact modulus [Pa]; default bearing steel on steel (``E = 208 GPa``,
        ``nu = 0.3``: 114.3 GPa).
    n_strips : int
        Strips across the contact (``x >= 0``).

    Examples
    --------
    >>> from rotorsim.elements.rolling.roller.bearing import RollerBearing
    >>> b = RollerBearing(14, 0.0425, 0.0075, 0.0075, Kn=3e8, model="slices", n_slices=10)
    >>> s = roller_pressure_field(b, [20e-6, 0, 0, 0, 0], b.element_angles()[0], 0)
    >>> bool(s.peak[0] > s.peak[5] > 0), round(s.load, 3)
    (True, 1803.198)
    """
    where = f"roller_pressure_field of {bearing._where}"
    if race not in ("inner", "outer"):
        raise TypeError(f"{where}: unknown race {race!r}; valid: ('inner', 'outer')")
    dk = bearing.slice_deflections(np.asarray(delta, dtype=float)[None],
                                   np.asarray(psi, dtype=float)[None])[0]
    if not 0 <= roller < dk.shape[0]:
        raise ModelError(f"roller index {roller} outside 0..{dk.shape[0] - 1}", where)
    load = float(bearing.kn / bearing.n_slices * (np.maximum(dk[roller], 0.0)
                                                   ** bearing.exponent).sum())
    if load <= 0.0:
        raise ModelError(f"roller {roller} carries no load", where)
    length = bearing.effective_length
    slope = float(np.polyfit(np.arange(dk.shape[1]), dk[roller] + bearing.profile.drop(
        bearing._line.xi, length), 1)[0]) * bearing.n_slices / length  # omega_j [rad]
    d = bearing.diameter_for("the half-space pressure field")
    gamma = d * math.cos(bearing.contact_angle) / bearing.pitch_diameter
    radius = 0.5 * d * (1.0 - gamma if race == "inner" else 1.0 + gamma)
    if e_star is None:
        e_star = effective_modulus(BEARING_STEEL_E, BEARING_STEEL_NU, BEARING_STEEL_E,
                                   BEARING_STEEL_NU)
    contact = HalfSpaceLineContact.for_load(load, length, radius, e_star, bearing.profile,
                                            int(bearing.n_slices), n_strips)
    return contact.solve_load(load, tilt=slope)
