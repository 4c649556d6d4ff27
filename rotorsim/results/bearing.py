"""Results of bearing statics: one equilibrium, and the stiffness over an element pass."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import Status

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

BEARING_DOFS = ("x", "y", "z", "rx", "ry")
"""Relative DOFs of a bearing, inner minus outer ring (DESIGN section 3)."""


@dataclass(frozen=True, eq=False)
class EnergyMinimum:
    """One local minimum of the bearing potential energy (global search).

    Attributes
    ----------
    displacement : array (5,)
        ``[x, y, z, rx, ry]`` [m, rad] (held DOFs at 0).
    energy : float
        Total potential energy ``U - F.delta`` [J] (seed 000 eqs 18, 26).
    hessian_eigenvalues : array (n_free,)
        Ascending eigenvalues of the dimensionless Hessian on the free DOFs (all > 0 at
        a strict minimum).
    hits : int
        Number of starts of the search that converged to it.
    """

    displacement: FloatArray
    energy: float
    hessian_eigenvalues: FloatArray
    hits: int

    @property
    def positive_definite(self) -> bool:
        w = self.hessian_eigenvalues
        return bool(w.size == 0 or w[0] > 1e-12 * max(float(np.abs(w).max()), 1e-300))


@dataclass(frozen=True, eq=False)
class BearingEquilibriumResult:
    """Static equilibrium of a rigid-ring bearing under a load on its inner ring.

    Attributes
    ----------
    displacement : array (5,)
        ``delta = [x, y, z, rx, ry]`` of the inner ring relative to the outer ring [m, rad].
    load : array (5,)
        Applied load ``[Fx, Fy, Fz, Mx, My]`` on the inner ring [N, N m].
    force : array (5,)
        Restoring force ``dU/d delta`` of the bearing at ``displacement`` (equals the load,
        plus ``load_stiffness @ delta`` if given, at equilibrium).
    method : str
        ``"newton"``, ``"energy"`` or ``"global"``.
    phi : float
        Shaft angle [rad] at which the rolling elements were placed.
    element_angles, element_load, contact_angle, deflection : arrays (N,)
        Angular position [rad], normal contact load [N], loaded contact angle [rad] and
        contact deflection [m] of each rolling element.
    stiffness : array (5, 5)
        ``dF/d delta`` at the equilibrium [N/m, N/rad, N m/rad] (seed 000 eq 27); rows and
        columns of held DOFs are those of the model (zero for a DOF the contacts ignore).
    energy, strain_energy : float
        Total potential energy ``U - F.delta`` and strain energy ``U`` [J].
    residual : float
        ``max |(F - load) s| / max |load s|`` with ``s = (1, 1, 1, 1/r, 1/r)`` (moments
        over the pitch radius ``r``), on the free DOFs.
    iterations : int
        Newton or trust-region iterations (global search: of the start that found it).
    held_dofs : tuple of str
        DOFs held at 0 because the bearing has no stiffness in them (seed 000 section 4).
    hold_reasons : tuple of str
        Why, one per held DOF.
    minima : tuple of EnergyMinimum
        Every distinct local minimum found by the global search, lowest energy first
        (empty for the local methods).
    search : dict
        Global search: number of starts, and how many converged to a minimum, stopped on a
        saddle, left the box or hit the iteration limit (empty for the local methods).
    notes : tuple of str
        Remarks on the solution (e.g. a singular stiffness at the equilibrium).
    options, stats, status, summary
        Options used, cost counters, status and a description of the bearing.
    """

    displacement: FloatArray
    load: FloatArray
    force: FloatArray
    method: str
    phi: float
    element_angles: FloatArray
    element_load: FloatArray
    contact_angle: FloatArray
    deflection: FloatArray
    stiffness: FloatArray
    energy: float
    strain_energy: float
    residual: float
    iterations: int
    held_dofs: tuple[str, ...] = ()
    hold_reasons: tuple[str, ...] = ()
    minima: tuple[EnergyMinimum, ...] = ()
    search: dict[str, int] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)

    @property
    def n_elements(self) -> int:
        return int(self.element_load.size)

    @property
    def loaded(self) -> NDArray[np.bool_]:
        """Rolling elements in contact, (N,).

        Loads below ``1e-12`` of the largest count as round-off (an element exactly at the
        edge of the load zone, e.g. at 90 deg from a radial load, gets ``cos(pi/2) ~ 6e-17``).
        """
        peak = float(self.element_load.max(initial=0.0))
        return np.asarray(self.element_load > 1e-12 * peak) if peak > 0 else np.zeros(
            self.element_load.shape, dtype=bool)

    @property
    def load_zone(self) -> IntArray:
        """Indices of the loaded rolling elements."""
        return np.flatnonzero(self.loaded).astype(np.int64)

    @property
    def load_zone_extent(self) -> float:
        """Angular extent of the load zone [rad], each loaded element counting one pitch.

        ``2 pi - (largest angular gap between loaded elements) + 2 pi / N``: ``2 pi`` when
        every element is loaded, one pitch for a single loaded element, 0 for none.
        """
        angles = np.sort(np.mod(self.element_angles[self.loaded], 2.0 * math.pi))
        if angles.size == 0:
            return 0.0
        gaps = np.diff(np.concatenate([angles, angles[:1] + 2.0 * math.pi]))
        pitch = 2.0 * math.pi / self.n_elements
        return float(min(2.0 * math.pi, 2.0 * math.pi - gaps.max() + pitch))

    @property
    def max_element_load(self) -> float:
        return float(self.element_load.max(initial=0.0))

    @property
    def free_dofs(self) -> tuple[str, ...]:
        return tuple(d for d in BEARING_DOFS if d not in self.held_dofs)

    def table(self) -> str:
        """Plain-text summary: displacement, load zone and stiffness matrix."""
        lines = [f"bearing equilibrium ({self.method}), residual {self.residual:.2e}"]
        for name, d, f in zip(BEARING_DOFS, self.displacement, self.load, strict=True):
            held = "  (held)" if name in self.held_dofs else ""
            lines.append(f"  {name:>2}: {d: .6e}   load {f: .6e}{held}")
        lines.append(f"  loaded elements {self.load_zone.size}/{self.n_elements}, "
                     f"zone {math.degrees(self.load_zone_extent):.1f} deg, "
                     f"Qmax {self.max_element_load:.6g} N")
        lines.append("  stiffness [N/m, N/rad, N m/rad]:")
        lines.extend("    " + " ".join(f"{v: .4e}" for v in row) for row in self.stiffness)
        return "\n".join(lines)


@dataclass(frozen=True, eq=False)
class StiffnessVariation:
    """Bearing displacement and stiffness over one element-pass period.

    The rolling elements are advanced together by the cage angle ``cage_angle`` in
    ``[0, 2 pi / N)``; ``position = cage_angle / (2 pi / N)`` is the normalised orbital
    position of seed 000 Figs 6c-d and 12.

    Attributes
    ----------
    position : array (P,)
        Normalised orbital position in ``[0, 1)``.
    cage_angle : array (P,)
        Rotation of the element set [rad].
    shaft_angle : array (P,)
        Shaft angle giving that cage angle, ``cage_angle / kappa`` [rad] (NaN for a
        fixed cage).
    displacement : array (P, 5)
        Equilibrium displacement under ``load`` (or the given displacement).
    force : array (P, 5)
        Bearing force at each position.
    stiffness : array (P, 5, 5)
        Stiffness matrix at each position.
    max_element_load : array (P,)
        Largest contact load [N].
    load : array (5,) or None
        Applied load, or None when the displacement was prescribed.
    held_dofs : tuple of str
        DOFs held at 0 (equilibrium under a load).
    options, stats, status, summary
    """

    position: FloatArray
    cage_angle: FloatArray
    shaft_angle: FloatArray
    displacement: FloatArray
    force: FloatArray
    stiffness: FloatArray
    max_element_load: FloatArray
    load: FloatArray | None
    held_dofs: tuple[str, ...] = ()
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)

    @property
    def mean_stiffness(self) -> FloatArray:
        """Average over the period (the positions are equally spaced), (5, 5)."""
        return np.asarray(self.stiffness.mean(axis=0))

    @property
    def stiffness_fluctuation(self) -> FloatArray:
        """Peak-to-peak variation of each coefficient over the period, (5, 5)."""
        return np.asarray(np.ptp(self.stiffness, axis=0))
