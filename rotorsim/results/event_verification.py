"""Result of :func:`rotorsim.verify_events`: each bifurcation of a periodic branch checked
by time integration of the full model on both sides of it."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.results.periodic import PeriodicBifurcation

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class SideCheck:
    """Time integration at one branch point next to an event.

    Attributes
    ----------
    point : int
        Branch point (index into the periodic result).
    parameter : float
        Its speed [rad/s].
    floquet : float
        ``max |mu|`` of the branch's Floquet multipliers there.
    unstable : int
        Floquet multipliers with ``|mu| > 1 + margin`` there.
    local : float
        ``max |mu|`` measured by power iteration on the period map of the full model
        linearised at the harmonic-balance state (:func:`.period_map.linearised_growth`).
    trajectory : float
        Growth per period of a perturbation along a free transient from that state
        (:func:`.period_map.trajectory_growth`); NaN when not run.
    local_factors, trajectory_factors : arrays
        Growth of every period (the estimates are their geometric mean over the second
        half).
    defect : float
        One-period defect ``|q(T) - q(0)|`` of the transient started on the harmonic-balance
        orbit, relative to the orbit's peak-to-peak, at the DOF that moves most (``ux`` or
        ``uy``): the truncation error of harmonic balance seen by the integrator.
    drift : float
        Largest ``|q(kT) - q(0)|`` over the free transient at that DOF, relative to the
        peak-to-peak [-] (NaN when not run).
    agrees : bool
        The measurements agree with Floquet (module :mod:`rotorsim.verification.periodic_events`).
    message : str
        Why not, or the failure of a transient.
    mode : complex
        ``measure="floquet"``: Floquet multiplier of the critical mode followed on this side
        (NaN otherwise; :mod:`rotorsim.verification.mode_growth`).
    measured : complex
        ``measure="floquet"``: multiplier per period of that mode's coordinate along the
        free transients (NaN otherwise).
    coordinates : complex array or None
        ``measure="floquet"``: the mode's coordinate ``c_k / c_0`` at ``t = k T`` (None
        otherwise or when not integrated).
    accuracy : float
        ``measure="shooting"``: the error allowed on ``measured``, half its change between
        the two step sizes (NaN otherwise). With ``measure="shooting"``, ``mode`` and
        ``measured`` are the multipliers of the event's kind of harmonic balance's Floquet
        and of the full model's orbit, ``local`` is ``|measured|`` and ``defect`` the
        largest distance of that orbit from the harmonic-balance state, relative to the
        largest lateral peak-to-peak.
    """

    point: int
    parameter: float
    floquet: float
    unstable: int
    local: float
    trajectory: float
    local_factors: FloatArray
    trajectory_factors: FloatArray
    defect: float
    drift: float
    agrees: bool
    message: str = ""
    mode: complex = float("nan")
    measured: complex = float("nan")
    coordinates: NDArray[np.complex128] | None = None
    accuracy: float = float("nan")


@dataclass(frozen=True, eq=False)
class EventCheck:
    """Verdict on one bifurcation.

    Attributes
    ----------
    event : PeriodicBifurcation
        The event checked.
    number : int
        Its index in ``result.bifurcations``.
    before, after : SideCheck or None
        The branch points checked on each side (None when the event has no branch point
        on that side).
    confirmed : bool
        True when the Floquet multipliers at ``before`` and ``after`` cross ``|mu| = 1``
        by more than the margin and the time integration agrees with them on both sides
        (and, for a fold, the two orbits stay apart).
    reason : str
        What was found, in words: always set, confirmed or not.
    separation : float
        Fold: distance between the two sides' harmonic-balance states at the most moving
        DOF, relative to the peak-to-peak (NaN for other kinds).
    """

    event: PeriodicBifurcation
    number: int
    before: SideCheck | None
    after: SideCheck | None
    confirmed: bool
    reason: str
    separation: float = float("nan")


@dataclass(frozen=True, eq=False)
class EventVerification:
    """All events of a branch checked by time integration (:func:`rotorsim.verify_events`).

    Attributes
    ----------
    checks : tuple of EventCheck
        One per event checked, in the order of ``result.bifurcations``.
    options : dict
        Options used (steps per period, iterations, margin, tolerance...).
    stats : dict
        Periods integrated and wall time [s].
    notes : tuple of str
        What else was found: with ``trace=True``, the full model's branch traced (its span,
        points and every event on it).
    """

    checks: tuple[EventCheck, ...]
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    notes: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.checks)

    @property
    def all_confirmed(self) -> bool:
        """Every event checked was confirmed (False when none was checked)."""
        return bool(self.checks) and all(c.confirmed for c in self.checks)

    def summary(self) -> str:
        """One line per event: kind, speed, verdict and reason."""
        lines = []
        for c in self.checks:
            verdict = "confirmed" if c.confirmed else "NOT confirmed"
            lines.append(f"{c.number}: {c.event.kind} at {c.event.parameter:.6g} rad/s: "
                         f"{verdict}: {c.reason}")
        return "\n".join([*lines, *self.notes])
