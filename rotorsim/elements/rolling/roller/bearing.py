"""Rigid-ring roller bearing: cylindrical, tapered, angular-contact and thrust rollers.

Kinematics (seed 000 eqs 6a-6d, signs of DESIGN section 3). Roller ``j`` at angle
``psi_j`` has the contact normal ``n_j = (cos a0 cos psi, cos a0 sin psi, sin a0)`` and the
roller coordinate ``z' = xi L`` (``xi`` in ``[-1/2, 1/2]``, 0 at the roller centre) along
``t_j = (-sin a0 cos psi, -sin a0 sin psi, cos a0)`` (+z for a cylindrical roller). For the
relative displacement ``delta = (x, y, z, rx, ry)`` of the inner ring, the contact
deflection along the roller is

    delta_j(xi) = V_j + xi L omega_j - c(xi),
    V_j = cos a0 (x cos psi + y sin psi - r_L) + sin a0 (z + r_p (rx sin psi - ry cos psi)),
    omega_j = -rx sin psi + ry cos psi,

with ``r_p`` the pitch radius, ``r_L`` the radial clearance and ``c`` the profile drop. The
line load per unit ``xi`` is ``Kn delta^n`` (``Kn`` for the whole roller: a uniform
deflection gives ``Q = Kn delta^n``), and the strain energy
``U = sum_j Kn int delta_j^(n+1) / (n+1) dxi`` (seed 000 eqs 19-24). Force and tangent are
its exact gradient and Hessian: with ``g(xi) = d delta / d delta_bearing``,

    F = sum_j Q_j (cos a0 cos psi, cos a0 sin psi, sin a0,
                   (r_p sin a0 - e_j) sin psi, -(r_p sin a0 - e_j) cos psi)   (seed 000 eq 10)
    K = n Kn sum_j int delta^(n-1) g g^T dxi                                 (Appendix A2)

where ``Q_j = Kn int delta^n dxi`` and ``e_j = L int xi delta^n dxi / int delta^n dxi``
(eq 9). Because the integrands vanish where the contact ends, the moving limits of
eq 8 add no boundary terms to the derivatives.

Three models: ``"tilt_integral"`` integrates the linear deflection in closed form between the
limits of eq 8 (straight profiles only); ``"slices"`` sums ``K`` slices of constant
``Kn/K`` at ``xi_k`` (seed 002 eqs 2.7, 2.12-2.13), and accepts crowned profiles;
``"influence"`` couples the same slices by the half-space influence coefficients (seed 002
section 2.3.3; :mod:`~rotorsim.elements.rolling.roller.influence_model`), edge effect
included, with its own energy, force and exact (symmetric) tangent.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.rolling.contact.hertz_line import LINE_EXPONENT
from rotorsim.elements.rolling.geometry import cage_ratio, checked_state, element_angles
from rotorsim.elements.rolling.roller.checks import (
    check_options,
    finite_number,
    resolve_clearance,
    resolve_kn,
)
from rotorsim.elements.rolling.roller.influence_model import REFERENCE_PRESSURE, bearing_influence
from rotorsim.elements.rolling.roller.integrals import (
    RollerConstants,
    RollerLoads,
    assemble_tangent,
    force_stiffness,
    roller_constants,
    roller_rows,
    unit_load_directions,
)
from rotorsim.elements.rolling.roller.line_load import RollerLineLoad
from rotorsim.elements.rolling.roller.profile import RollerProfile, StraightProfile
from rotorsim.elements.rolling.roller.slice_outputs import roller_loads, slice_loads
from rotorsim.elements.rolling.state import BearingState
from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

_assemble_tangent = assemble_tangent  # the name rotorsim.elements.rolling.lubrication imports

@dataclass(frozen=True, eq=False)
class RollerBearing:
    """Roller bearing with rigid rings, 5 relative DOFs ``(x, y, z, rx, ry)``.

    Parameters
    ----------
    n_rollers : int
        Number of rollers ``Z``.
    pitch_diameter : float
        Pitch diameter ``d_m = 2 r_p`` [m] (roller centres).
    roller_diameter : float, optional
        Mean roller diameter [m]. Only needed by what uses it: the cage ratio of a
        rotating cage at a shaft angle other than 0 (transients, histories), ISO 281
        ratings and lives, contact pressures, the half-space slices, the centrifugal force
        and EHL damping; statics at ``phi = 0`` and stiffness do without it (each use
        without it raises a ``ModelError`` that names it).
    effective_length : float
        Effective contact length ``L`` [m] (required).
    Kn : float, optional
        Whole-roller load-deflection constant [N/m^n]: ``Q = Kn delta^n`` for a uniform
        total deflection ``delta`` of both contacts (ISO/TS 16281 and Lim-Singh convention;
        Palmgren's per-contact constant is ``2^n`` times larger, see
        :mod:`~rotorsim.elements.rolling.contact.hertz_line`). Default: ISO/TS 16281
        ``c_L = 35948 L^(8/9)`` N/mm^(10/9) (steel; requires ``exponent = 10/9``).
    contact_angle : float
        Unloaded contact angle ``alpha0`` [rad] in ``[0, pi/2]``: 0 cylindrical, tapered or
        angular contact in between, ``pi/2`` thrust.
    radial_clearance : float, optional
        Radial clearance ``r_L`` [m] as in seed 000 eq 6a: the radial travel of the inner
        ring before a roller is touched, per side (half the diametral clearance); negative
        = preload (interference). Its normal component ``r_L cos alpha0`` opens every
        contact. Default 0.
    diametral_clearance : float, optional
        ``P_d = 2 r_L`` [m] (catalogue "radial internal clearance"); give one of the two
        (or both, consistent).
    exponent : float
        Load-deflection exponent ``n >= 1`` (10/9 line contact).
    profile : RollerProfile
        Roller profile (``model="slices"`` or ``"influence"`` for crowned or logarithmic
        profiles).
    model : {"tilt_integral", "slices", "influence"}
        Contact model (module docstring). ``"influence"`` needs ``roller_diameter``; its
        cost: docs/benchmarks.md; its slice outputs (``slice_loads``, laminae, pressures)
        are its own (``slice_model`` is set to ``"influence"``).
    n_slices : int
        Number of slices ``K`` of the slicing model.
    psi0 : float
        Angle of roller 0 at shaft angle 0 [rad], from +x towards +y.
    cage : {"rotating", "fixed"}
        ``"rotating"``: rollers at ``psi0 + 2 pi j/Z + kappa phi`` (DESIGN section 3);
        ``"fixed"``: ``kappa = 0``.
    tag : str
        Name used in messages.
    slice_model : {"independent", "influence"}
        Slice load law of :meth:`slice_loads` and :meth:`roller_loads` (and so of the
        ISO/TS 16281 lamina life and the slice pressures): independent slices
        ``(Kn/K) delta_k^n``, or the half-space influence coefficients of
        :mod:`~rotorsim.elements.rolling.roller.slice_influence` (edge effect), normalised
        to the same roller loads. Force, stiffness and energy (statics, transients) use
        the independent law in both cases (why, and what it changes: docs/bearing_life.md,
        "Roller edge effect"); ``model="influence"`` makes the half-space drive them.
    influence_pressure : float
        Reference Hertz pressure ``p_ref`` [Pa] of ``model="influence"``: its slice strips
        have the Hertz half-widths of the line load giving the inner race ``p_ref``
        (default 1500 MPa); set it near the load case's peak pressure.

    References
    ----------
    Seed 000 eqs 6-11 (deflection, limits, eccentricity, loads), 19-26 (energy), 27 and
    Appendix A2 (stiffness); seed 002 eqs 2.7, 2.12-2.13 (slices).

    Examples
    --------
    >>> b = RollerBearing(n_rollers=14, pitch_diameter=0.0425, roller_diameter=0.0075,
    ...                   effective_length=0.0075, Kn=3.0e8, radial_clearance=1.75e-6)
    >>> s = b.state([[20e-6, 0, 0, 0, 0]], b.element_angles(0.0))
    >>> round(float(s.force[0, 0]), 1), round(float(s.element_load[0, 0]), 1)
    (5423.2, 1628.8)
    """

    n_rollers: int
    pitch_diameter: float
    roller_diameter: float | None = None
    effective_length: float = None  # type: ignore[assignment]  # required (checked)
    Kn: float | None = None
    contact_angle: float = 0.0
    radial_clearance: float | None = None
    diametral_clearance: float | None = None
    exponent: float = LINE_EXPONENT
    profile: RollerProfile = field(default_factory=StraightProfile)
    model: str = "tilt_integral"
    n_slices: int = 20
    psi0: float = 0.0
    cage: str = "rotating"
    tag: str = ""
    slice_model: str = "independent"
    influence_pressure: float = REFERENCE_PRESSURE

    def __post_init__(self) -> None:
        where = self._where
        if isinstance(self.n_rollers, bool) or not isinstance(self.n_rollers, int | np.integer) \
                or self.n_rollers < 1:
            raise ModelError(f"n_rollers must be an integer >= 1, got {self.n_rollers!r}", where)
        if self.effective_length is None:
            raise ModelError("effective_length is required (the roller's contact length "
                             "L [m])", where)
        for name in ("pitch_diameter", "roller_diameter", "effective_length"):
            value = getattr(self, name)
            if value is None and name == "roller_diameter":
                continue
            if not (finite_number(value) and value > 0.0):
                raise ModelError(f"{name} must be positive and finite, got {value!r}", where)
        if self.roller_diameter is not None and self.roller_diameter >= self.pitch_diameter:
            raise ModelError(f"roller_diameter {self.roller_diameter} m must be smaller than "
                             f"pitch_diameter {self.pitch_diameter} m", where)
        if not (finite_number(self.contact_angle)
                and 0.0 <= self.contact_angle <= 0.5 * math.pi):
            raise ModelError(f"contact_angle must be in [0, pi/2] rad (0 to 90 deg), got "
                             f"{self.contact_angle!r}", where)
        self._resolve_clearance(where)
        if not (finite_number(self.exponent) and self.exponent >= 1.0):
            raise ModelError(f"exponent must be finite and >= 1 (10/9 for line contact), got "
                             f"{self.exponent!r}", where)
        self._resolve_kn(where)
        check_options(self, where)
        if self.model == "influence":  # its slice outputs are its own
            object.__setattr__(self, "slice_model", "influence")

    @property
    def _where(self) -> str:
        return f"RollerBearing '{self.tag}'" if self.tag else "RollerBearing"

    def _resolve_clearance(self, where: str) -> None:
        object.__setattr__(self, "radial_clearance", resolve_clearance(self, where))

    def _resolve_kn(self, where: str) -> None:
        object.__setattr__(self, "Kn", resolve_kn(self, where))

    @property
    def kn(self) -> float:
        """Whole-roller constant ``Kn`` [N/m^n] (resolved: given or ISO/TS 16281)."""
        return float(self.Kn)  # type: ignore[arg-type]

    @property
    def clearance(self) -> float:
        """Radial clearance ``r_L`` [m] (resolved from radial or diametral)."""
        return float(self.radial_clearance)  # type: ignore[arg-type]

    # ----------------------------------------------------------------- kinematics
    @property
    def n_elements(self) -> int:
        """Number of rolling elements (rollers)."""
        return int(self.n_rollers)

    @cached_property
    def kappa(self) -> float:
        """Cage ratio: cage angle over shaft angle (0 for ``cage="fixed"``)."""
        if self.cage == "fixed":
            return 0.0
        return cage_ratio(self.diameter_for("the cage ratio of a rotating cage (or give "
                                            "cage='fixed')"),
                          self.pitch_diameter, self.contact_angle)

    def diameter_for(self, use: str) -> float:
        """``roller_diameter`` [m]; a ``ModelError`` naming ``use`` when it was not given."""
        if self.roller_diameter is None:
            raise ModelError(f"roller_diameter is needed for {use}", self._where)
        return float(self.roller_diameter)

    def element_angles(self, phi: ArrayLike = 0.0) -> FloatArray:
        """Roller angles ``psi`` [rad], shape ``(S, Z)``, at shaft angles ``phi`` (S,)
        (at ``phi = 0`` without the cage ratio, which needs ``roller_diameter``)."""
        still = self.roller_diameter is None and not np.any(np.asarray(phi, dtype=float))
        return element_angles(self.n_rollers, phi, 0.0 if still else self.kappa, self.psi0)

    @cached_property
    def _line(self) -> RollerLineLoad:
        """The line load along the rollers for :attr:`model` (:mod:`.line_load`)."""
        return RollerLineLoad(self.model, self.exponent, self.n_slices, self.profile,
                              self.effective_length, bearing_influence(self))

    def _inputs(self, delta: ArrayLike, psi: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Check shapes; return ``delta (S, 5)`` and ``psi (S, N)``."""
        return checked_state(delta, psi, self.n_rollers, self._where)

    @cached_property
    def _block_size(self) -> int:
        """Samples of about 32k roller-slices: small temporaries stay in cache."""
        per_sample = self.n_rollers * (1 if self.model == "tilt_integral" else self.n_slices)
        return max(1, 32768 // per_sample)

    def _blocks(self, n_samples: int) -> list[slice]:
        """Sample blocks of about 32k roller-slices (:attr:`_block_size`)."""
        size = self._block_size
        return [slice(i, i + size) for i in range(0, n_samples, size)]

    @cached_property
    def _hot(self) -> RollerConstants:
        """Constants of the evaluation (:func:`roller_constants`)."""
        return roller_constants(self.contact_angle, self.pitch_diameter, self.clearance,
                                self.effective_length, self.kn, float(self.exponent))

    def _kinematics(self, d: FloatArray, p: FloatArray) -> tuple[FloatArray, ...]:
        """``cos psi``, ``sin psi``, centre deflection ``V`` and tilt ``L omega`` (S, Z)."""
        c, s = np.cos(p), np.sin(p)
        return (c, s, *self._approach(d, c, s))

    def _approach(self, d: FloatArray, c: FloatArray, s: FloatArray
                  ) -> tuple[FloatArray, FloatArray]:
        """Centre deflection ``V`` and tilt ``L omega`` (..., Z) of ``d`` (..., 5) at
        ``c, s = cos, sin(psi)`` (..., Z), which may omit leading axes of ``d``."""
        h = self._hot
        x, y, z, rx, ry = (d[..., k, None] for k in range(5))
        rx_s, ry_c = rx * s, ry * c
        v = h.ca0 * (x * c + y * s - h.clearance) + h.sa0 * z + h.r_sa0 * (rx_s - ry_c)
        return v, h.length * (ry_c - rx_s)

    # ------------------------------------------------------------------ force
    def _force_stiffness(self, d: FloatArray, c: FloatArray, s: FloatArray
                         ) -> tuple[FloatArray, FloatArray]:
        """Force (..., S, 5) and exact tangent (..., S, 5, 5) only, as :meth:`state`,
        without checks (the hot path of
        :class:`~rotorsim.elements.rolling.element.RollingBearing`).

        ``d`` (..., S, 5) checked relative displacements, ``c, s`` (S, Z) ``cos, sin(psi)``
        shared by the leading axes of ``d`` (e.g. ``d`` (3, S, 5)).
        """
        n_samples = c.shape[0]
        copies = d.size // (5 * n_samples) if n_samples else 1
        size = max(1, self._block_size // copies)
        if n_samples <= size:
            return self._force_block(d, c, s)
        parts = [self._force_block(d[..., i:i + size, :], c[i:i + size], s[i:i + size])
                 for i in range(0, n_samples, size)]
        return (np.concatenate([f for f, _ in parts], axis=-2),
                np.concatenate([k for _, k in parts], axis=-3))

    def _force_block(self, d: FloatArray, c: FloatArray, s: FloatArray
                     ) -> tuple[FloatArray, FloatArray]:
        h = self._hot
        rows = roller_rows(h, *self._line.load_integrals(*self._approach(d, c, s)))
        force, tangent = force_stiffness(rows, c, s, h.ca, h.sa)
        return force, h.n_kn * tangent

    # ------------------------------------------------------------------ public API
    def energy(self, delta: ArrayLike, psi: ArrayLike) -> FloatArray:
        """Strain energy ``U`` [J] of all contacts, shape ``(S,)`` (seed 000 eqs 21-24)."""
        d, p = self._inputs(delta, psi)
        parts = []
        for block in self._blocks(d.shape[0]):
            _, _, v, lw = self._kinematics(d[block], p[block])
            parts.append(self._line.integrals(v, lw, energy_only=True).energy.sum(axis=1))
        return np.asarray(self.kn * np.concatenate(parts))

    def state(self, delta: ArrayLike, psi: ArrayLike) -> BearingState:
        """Force, exact tangent, energy and roller loads at ``delta`` (S, 5), ``psi`` (S, Z).

        ``force = dU/d delta`` [N, N m] (seed 000 eq 10), ``stiffness = d force / d delta``
        (eq 27, Appendix A2), symmetric; ``contact_direction`` ``g_j`` (S, Z, 5) with
        ``force = sum_j Q_j g_j`` and ``element_stiffness`` ``dQ_j/dV_j`` (S, Z).
        """
        d, p = self._inputs(delta, psi)
        parts = [self._state_block(d[block], p[block]) for block in self._blocks(d.shape[0])]
        if len(parts) == 1:
            return parts[0]
        names = ("force", "stiffness", "energy", "element_load", "contact_angle", "deflection",
                 "contact_direction", "element_stiffness")
        merged: dict[str, Any] = {k: np.concatenate([getattr(x, k) for x in parts])
                                  for k in names}
        return BearingState(**merged)

    def _state_block(self, d: FloatArray, p: FloatArray) -> BearingState:
        c, s, v, lw = self._kinematics(d, p)
        ints = self._line.integrals(v, lw)
        h = self._hot
        rows = roller_rows(h, ints.load, ints.load_moment, ints.tangent0, ints.tangent1,
                           ints.tangent2)
        force, tangent = force_stiffness(rows, c, s, h.ca, h.sa)
        q, arm = rows[3].copy(), rows[4]  # Q_j and Q_j (r_p sin a0 - e_j)
        # unit-load direction g_j = dF/dQ_j: the moment arm r_p sin a0 - e_j of eq 10
        unit_arm = np.where(q > 0.0, arm / np.where(q > 0.0, q, 1.0), h.r_sa)
        direction = unit_load_directions(c, s, unit_arm, h.ca, h.sa)
        return BearingState(
            force=force, stiffness=h.n_kn * tangent, energy=self.kn * ints.energy.sum(axis=1),
            element_load=q, contact_angle=np.full(q.shape, self.contact_angle),
            deflection=ints.peak, contact_direction=direction,
            element_stiffness=h.n_kn * ints.tangent0)

    def slice_deflections(self, delta: ArrayLike, psi: ArrayLike) -> FloatArray:
        """Deflection at the ``n_slices`` slice centres, ``(S, Z, K)`` [m] (negative: open).

        ``delta_k = V_j + xi_k L omega_j - c(xi_k)`` (seed 000 eq 6, seed 002 eq 2.2); for
        the tilt-integral model the same straight roller sampled at the slice centres.

        Examples
        --------
        >>> b = RollerBearing(14, 0.0425, 0.0075, 0.01, Kn=3e8, n_slices=4)
        >>> b.slice_deflections([[10e-6, 0, 0, 0, 2e-4]], b.element_angles())[0, 0] * 1e6
        array([ 9.25,  9.75, 10.25, 10.75])
        """
        _, _, v, lw = self._kinematics(*self._inputs(delta, psi))
        return self._line.slice_deflection(v, lw)

    def slice_loads(self, delta: ArrayLike, psi: ArrayLike) -> FloatArray:
        """Slice loads ``(S, Z, K)`` [N] at the ``n_slices`` slice centres, by
        :attr:`slice_model`: ``(Kn/K) max(delta_k, 0)^n`` or, ``"influence"``, the
        half-space distribution of the same roller loads
        (:func:`~rotorsim.elements.rolling.roller.slice_influence.influence_slice_loads`).

        Examples
        --------
        >>> b = RollerBearing(14, 0.0425, 0.0075, 0.01, Kn=3e8, n_slices=10,
        ...                   slice_model="influence")
        >>> q = b.slice_loads([[10e-6, 0, 0, 0, 0]], b.element_angles())[0, 0]
        >>> bool(q[0] > q[5] > 0)
        True
        """
        return slice_loads(self, self.slice_deflections(delta, psi))

    def roller_loads(self, delta: ArrayLike, psi: ArrayLike) -> RollerLoads:
        """Per-roller load, eccentricity (seed 000 eq 9) and loaded zone (eq 8); with
        ``slice_model="influence"`` the slice loads and eccentricity of the half-space
        distribution (:meth:`slice_loads`)."""
        _, _, v, lw = self._kinematics(*self._inputs(delta, psi))
        return roller_loads(self, v, lw)
