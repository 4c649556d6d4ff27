"""Radial roller bearing with flexible rings (seed 001, Leontiev, Ivannikov, Degtyarev 2017).

Each ring is cut into ``N`` segments of angle ``theta = 2 pi / N``, one per roller; a
segment deflects radially by ``w`` under a constant hoop force and bending moment
(seed 001 section 2.2, eqs 8-11). A roller with its two ring segments has four internal
DOFs ``[v_r, phi, w_i, w_e]`` (eq 12) and the potential of eq 19: Hertz line contacts by
slices (eqs 13-17), ring tension and bending (eqs 9-10) and the centrifugal potential of
the roller (eq 18). For a given relative displacement of the rings the rollers are solved
independently by a batched Newton method (eq 22,
:mod:`~rotorsim.elements.rolling.condensation`), condensed to their local load
``[Q_e, M_e]`` and tangent (eqs 23-26), and summed into the 5-DOF bearing force and
stiffness (eqs 3-7, :mod:`~rotorsim.elements.rolling.flexible_ring.state`). The physics of
one roller is in :mod:`~rotorsim.elements.rolling.flexible_ring.roller`.

Limits (seed 001 sections 2.2, 2.5 and 4): no axial load (``z`` carries nothing), small
displacements and rotations, each ring segment deforms on its own (good for negative or
small clearance, where the radial loads vary smoothly; too stiff when a few rollers carry
a concentrated load). With ``rigid_rings=True`` (no ``w_i``, ``w_e``) and at rest the model
equals :class:`~rotorsim.elements.rolling.roller.bearing.RollerBearing` ``(model="slices")`` with
``Kn = C L / 2^n``, ``diametral_clearance = g`` and twice the roller's profile drop.

References
----------
Seed 001 eqs 1-26.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.elements.rolling.condensation import InnerNewton
from rotorsim.elements.rolling.contact.hertz_line import LINE_EXPONENT
from rotorsim.elements.rolling.flexible_ring.checks import (
    CAGE_LAWS,
    check_parameters,
    ring_sections,
)
from rotorsim.elements.rolling.flexible_ring.geometry import (
    FloatArray,
    RingSection,
    RollerSlices,
    line_contact_constant,
)
from rotorsim.elements.rolling.flexible_ring.roller import RollerPotential
from rotorsim.elements.rolling.flexible_ring.solve import solve_state
from rotorsim.elements.rolling.flexible_ring.state import FlexibleRingState
from rotorsim.elements.rolling.geometry import cage_ratio, checked_state, element_angles
from rotorsim.elements.rolling.roller.profile import RollerProfile, StraightProfile
from rotorsim.errors import ModelError

__all__ = ["CAGE_LAWS", "FlexibleRingRollerBearing"]


@dataclass(frozen=True, eq=False)
class FlexibleRingRollerBearing:
    """Cylindrical roller bearing with flexible rings, 5 relative DOFs (seed 001).

    Parameters
    ----------
    n_rollers : int
        Number of rollers ``N``.
    pitch_radius : float
        ``R_p`` [m] (roller centres).
    roller_radius : float
        ``R_b`` [m].
    effective_length : float
        ``L`` [m].
    diametral_clearance : float
        Operating diametral clearance ``g`` [m] (eq 13); negative = preload. The rigid-ring
        :class:`~rotorsim.elements.rolling.roller.bearing.RollerBearing` takes
        ``radial_clearance = g / 2``.
    shaft_radius : float, optional
        Bore radius ``R_s`` [m] of the inner ring (with a hollow shaft: the shaft's inner
        radius); the inner ring section spans ``R_s .. R_p - R_b`` (Fig. 3a).
    housing_radius : float, optional
        ``R_h`` [m]; the outer ring section spans ``R_p + R_b .. R_h``.
    ring_width : float, optional
        Axial width ``b`` [m] of both ring sections.
    inner_ring, outer_ring : RingSection, optional
        Ring sections given directly (instead of ``shaft_radius`` / ``housing_radius``).
    E, nu : float
        Young's modulus [Pa] and Poisson ratio of rollers and rings.
    rho : float
        Density [kg/m^3] (roller mass).
    ring_modulus : float, optional
        Young's modulus of the rings [Pa] (default ``E``; a large value stiffens them).
    roller_mass : float, optional
        ``m`` [kg]; default ``rho pi R_b^2 L``.
    contact_constant : float, optional
        ``C`` [N/m^(1+n)] of the line law ``q = C delta^n`` per contact; default eq 16.
    exponent : float
        ``n`` (10/9).
    n_slices : int
        Equal slices per roller (when ``slice_widths`` is not given).
    slice_widths : tuple of float, optional
        Slice widths ``h_k`` [m], adding up to ``L``.
    profile : RollerProfile
        Roller crowning; its drop relieves each contact (eq 15, ``b_k - R_b``).
    tilt : bool
        Keep the roller tilt ``phi`` and the ring misalignment ``gamma_n`` (eq 15); without
        them the bearing carries no moment.
    rigid_rings : bool
        Drop the ring DOFs ``w_i``, ``w_e`` (rigid-ring limit).
    cage : {"rotating", "fixed"}
        Rollers at ``psi0 + 2 pi j / N + kappa phi`` or held at ``kappa = 0``.
    cage_ratio : float, optional
        ``omega_c / W`` of the centrifugal force (eq 18); default the kinematic
        ``(1 - R_b / R_p) / 2`` (inner ring turning, outer fixed).
    psi0 : float
        Angle of roller 0 at ``phi = 0`` [rad], from +x towards +y.
    speed : float
        Shaft speed ``W`` [rad/s] used when :meth:`state` gets none.
    tol, max_iter : float, int
        Inner Newton tolerance (relative to the largest roller load) and iteration limit.
    tag : str
        Name used in messages.

    Examples
    --------
    >>> b = FlexibleRingRollerBearing(n_rollers=24, pitch_radius=0.075, roller_radius=0.0065,
    ...     effective_length=0.016, diametral_clearance=-40e-6, shaft_radius=0.054,
    ...     housing_radius=0.097, ring_width=0.030)
    >>> st = b.state([[10e-6, 0, 0, 0, 0]], b.element_angles())
    >>> st.element_load.shape, st.internal.shape, bool(st.force[0, 0] > 0)
    ((1, 24), (1, 24, 4), True)
    """

    n_rollers: int
    pitch_radius: float
    roller_radius: float
    effective_length: float
    diametral_clearance: float = 0.0
    shaft_radius: float | None = None
    housing_radius: float | None = None
    ring_width: float | None = None
    inner_ring: RingSection | None = None
    outer_ring: RingSection | None = None
    E: float = 2.0e11
    nu: float = 0.3
    rho: float = 7850.0
    ring_modulus: float | None = None
    roller_mass: float | None = None
    contact_constant: float | None = None
    exponent: float = LINE_EXPONENT
    n_slices: int = 10
    slice_widths: tuple[float, ...] | None = None
    profile: RollerProfile = field(default_factory=StraightProfile)
    tilt: bool = True
    rigid_rings: bool = False
    cage: str = "rotating"
    cage_ratio: float | None = None
    psi0: float = 0.0
    speed: float = 0.0
    tol: float = 1e-10
    max_iter: int = 50
    tag: str = ""

    def __post_init__(self) -> None:
        check_parameters(self)

    @classmethod
    def from_diameters(cls, *, n_rollers: int, pitch_diameter: float, roller_diameter: float,
                       effective_length: float, diametral_clearance: float | None = None,
                       radial_clearance: float | None = None,
                       shaft_diameter: float | None = None,
                       housing_diameter: float | None = None,
                       **kwargs: Any) -> FlexibleRingRollerBearing:
        """The bearing from diameters and either clearance, as the rigid-ring models take
        them: ``pitch_diameter = 2 R_p``, ``roller_diameter = 2 R_b``, the shaft bore and
        housing outside ``shaft_diameter = 2 R_s``, ``housing_diameter = 2 R_h`` [m], and
        ``diametral_clearance = g`` or ``radial_clearance = g / 2`` [m] (one of the two,
        default 0); other keyword arguments go to the constructor.

        Examples
        --------
        >>> b = FlexibleRingRollerBearing.from_diameters(
        ...     n_rollers=24, pitch_diameter=0.15, roller_diameter=0.013,
        ...     effective_length=0.016, radial_clearance=-20e-6, shaft_diameter=0.108,
        ...     housing_diameter=0.194, ring_width=0.030)
        >>> b.pitch_radius, b.diametral_clearance
        (0.075, -4e-05)
        """
        if diametral_clearance is not None and radial_clearance is not None:
            raise ModelError("give diametral_clearance or radial_clearance, not both",
                             "FlexibleRingRollerBearing.from_diameters")
        g = (2.0 * radial_clearance if radial_clearance is not None
             else diametral_clearance or 0.0)
        return cls(n_rollers=n_rollers, pitch_radius=0.5 * pitch_diameter,
                   roller_radius=0.5 * roller_diameter, effective_length=effective_length,
                   diametral_clearance=g,
                   shaft_radius=None if shaft_diameter is None else 0.5 * shaft_diameter,
                   housing_radius=None if housing_diameter is None else 0.5 * housing_diameter,
                   **kwargs)

    # ------------------------------------------------------------------ geometry
    @property
    def label(self) -> str:
        return f"FlexibleRingRollerBearing '{self.tag}'" if self.tag \
            else "FlexibleRingRollerBearing"

    @cached_property
    def slices(self) -> RollerSlices:
        """The roller slices (widths, centres, drops)."""
        return RollerSlices.build(self.effective_length, self.n_slices, self.slice_widths,
                                  self.profile, self.label)

    @cached_property
    def sections(self) -> tuple[RingSection | None, RingSection | None]:
        """Inner and outer ring sections (``None`` for rigid rings without geometry)."""
        return ring_sections(self)

    @property
    def n_elements(self) -> int:
        """Number of rollers."""
        return int(self.n_rollers)

    @property
    def pitch_diameter(self) -> float:
        return 2.0 * self.pitch_radius

    @property
    def roller_diameter(self) -> float:
        return 2.0 * self.roller_radius

    @property
    def contact_angle(self) -> float:
        return 0.0

    @property
    def clearance(self) -> float:
        """Radial clearance ``g / 2`` [m] (rigid-ring convention, seed 000 eq 6a)."""
        return 0.5 * self.diametral_clearance

    @cached_property
    def line_constant(self) -> float:
        """``C`` [N/m^(1+n)] of each contact (given or seed 001 eq 16)."""
        if self.contact_constant is not None:
            return float(self.contact_constant)
        return line_contact_constant(self.E, self.nu, self.effective_length, self.exponent)

    @property
    def Kn(self) -> float:
        """Whole-roller constant of the rigid-ring limit, ``C L / 2^n`` [N/m^n]."""
        return self.line_constant * self.effective_length / 2.0 ** self.exponent

    @property
    def mass(self) -> float:
        """Roller mass ``m`` [kg] (given or ``rho pi R_b^2 L``)."""
        if self.roller_mass is not None:
            return float(self.roller_mass)
        return self.rho * math.pi * self.roller_radius**2 * self.effective_length

    @property
    def centrifugal_cage_ratio(self) -> float:
        """``omega_c / W`` of the centrifugal force (eq 18)."""
        if self.cage_ratio is not None:
            return float(self.cage_ratio)
        return cage_ratio(self.roller_diameter, self.pitch_diameter, 0.0)

    @property
    def kappa(self) -> float:
        """Cage ratio of the roller positions (0 for ``cage="fixed"``)."""
        return 0.0 if self.cage == "fixed" else self.centrifugal_cage_ratio

    def element_angles(self, phi: ArrayLike = 0.0) -> FloatArray:
        """Roller angles ``psi`` [rad], shape ``(S, N)``, at shaft angles ``phi`` (S,)."""
        return element_angles(self.n_rollers, phi, self.kappa, self.psi0)

    def at_speed(self, speed: float) -> FlexibleRingRollerBearing:
        """A copy whose default shaft speed is ``speed`` [rad/s] (bearing statics at speed)."""
        return dataclasses.replace(self, speed=float(speed))

    @cached_property
    def potential(self) -> RollerPotential:
        """The per-roller potential (seed 001 eq 19)."""
        theta = 2.0 * math.pi / self.n_rollers
        modulus = self.E if self.ring_modulus is None else float(self.ring_modulus)

        def ring(section: RingSection | None) -> tuple[float, float, float]:
            if section is None or self.rigid_rings:
                return 0.0, 0.0, 1.0
            return (section.tension_stiffness(modulus, theta),
                    section.bending_rigidity(modulus, theta), section.mean_radius)

        internal = (0, 1) if self.tilt else (0,)
        if not self.rigid_rings:
            internal = (*internal, 2, 3)
        return RollerPotential(self.line_constant, float(self.exponent),
                               float(self.diametral_clearance), self.slices,
                               float(self.pitch_radius), ring(self.sections[0]),
                               ring(self.sections[1]), internal, (0, 1) if self.tilt else (0,))

    @cached_property
    def newton(self) -> InnerNewton:
        """Options of the inner Newton solve."""
        if isinstance(self.max_iter, bool) or not isinstance(self.max_iter, int):
            raise ModelError(f"max_iter must be an integer >= 1, got {self.max_iter!r}",
                             self.label)
        try:
            return InnerNewton(tol=float(self.tol), max_iter=self.max_iter)
        except ModelError as exc:
            raise ModelError(str(exc), self.label) from None

    # ------------------------------------------------------------------ state
    def energy(self, delta: ArrayLike, psi: ArrayLike, speed: ArrayLike | None = None,
               internal: ArrayLike | None = None) -> FloatArray:
        """Condensed potential ``sum_j Pi*_j`` [J], shape ``(S,)``."""
        return np.asarray(self.state(delta, psi, speed, internal).energy)

    def state(self, delta: ArrayLike, psi: ArrayLike, speed: ArrayLike | None = None,
              internal: ArrayLike | None = None, details: bool = True) -> FlexibleRingState:
        """Force, exact condensed tangent and roller loads for ``S`` samples.

        Parameters
        ----------
        delta : array (S, 5)
            ``[x, y, z, rx, ry]`` of the inner ring relative to the outer ring [m, rad].
        psi : array (S, N) or (N,)
            Roller angles [rad].
        speed : float or array (S,), optional
            Shaft speed ``W`` [rad/s] (centrifugal force); default :attr:`speed`.
        internal : array (S, N, 4), optional
            ``state.internal`` of a previous call (warm start); NaN rows start cold.
        details : bool
            Also return the slice loads (``slice_load``, ``outer_slice_load``).

        Returns
        -------
        FlexibleRingState

        Raises
        ------
        ConvergenceError
            When the inner Newton fails for a roller (names the roller and the sample).
        """
        d, p = self._inputs(delta, psi)
        n_s = d.shape[0]
        w = np.asarray(self.speed if speed is None else speed, dtype=float).reshape(-1)
        if w.size not in (1, n_s) or not np.all(np.isfinite(w)):
            raise ModelError(f"speed must be finite, a scalar or ({n_s},), got shape "
                             f"{w.shape}", self.label)
        return solve_state(self, d, p, np.broadcast_to(w, (n_s,)), internal, details)

    def _inputs(self, delta: ArrayLike, psi: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Check shapes; return ``delta (S, 5)`` and ``psi (S, N)``."""
        return checked_state(delta, psi, self.n_rollers, self.label)
