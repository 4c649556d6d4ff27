"""Result of a bearing rating: ISO 281 and ISO/TS 16281 lives and contact pressures."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import Status

FloatArray = NDArray[np.float64]

RACES = ("inner", "outer")


@dataclass(frozen=True, eq=False)
class BearingLifeResult:
    """Lives and contact pressures of one bearing under a load, a history or a duty cycle.

    Lives are in million revolutions of the inner ring relative to the outer ring.

    Attributes
    ----------
    kind : {"ball", "roller"}
    source : str
        What was rated: ``"equilibrium"``, ``"transient"``, ``"periodic"``,
        ``"duty_cycle"``.
    C, C0 : float
        Basic dynamic and static load ratings [N] (``C0`` NaN when unknown).
    rating_source : str
        ``"catalogue"`` or the ISO 281 geometry formula with its ``b_m`` and ``f_c``.
    load : array (5,)
        Load ``[Fx, Fy, Fz, Mx, My]`` on the inner ring [N, N m] (histories: NaN).
    P : float
        ISO 281 dynamic equivalent load from ``X, Y`` [N] (NaN for histories, and when no
        table applies).
    L10 : float
        ISO 281 basic rating life ``(C/P)^p`` (NaN without ``P``).
    L10r : float
        ISO/TS 16281 modified reference rating life from the internal load distribution
        (without ``a_ISO``).
    P_ref : float
        Dynamic equivalent reference load ``C L10r^(-1/p)`` [N], ``p`` the raceway
        exponent (3 balls, 4 rollers): ``P`` of ISO 281 in its reference case.
    ring_life : array (2,)
        Life of the inner and outer raceway.
    equivalent_load, reference_load : arrays (2,)
        ``Q_ei, Q_ee`` and the raceway reference loads ``Q_ci, Q_ce`` [N].
    a1, a_iso : float
        Reliability factor and life modification factor (1 when not requested).
    Lnmr, Lnm : float
        ``a1 a_ISO(P_ref) L10r`` and ``a1 a_ISO(P) L10``.
    max_pressure : array (N, 2)
        Largest Hertz pressure of each rolling element on the inner and outer race [Pa]
        (rollers: over the slices; histories: at each element's largest load).
    semi_major, semi_minor : arrays (N, 2)
        Ball contact-ellipse semi-axes ``a`` (across the groove), ``b`` [m]; rollers:
        ``semi_major`` NaN, ``semi_minor`` the largest half-width of the line contact.
    shoulder_margin : array (N, 2)
        ``theta_s - |alpha| - a / r`` [rad] (negative: the ellipse is truncated at the
        shoulder); NaN without shoulder heights or for rollers.
    slice_pressure : array (Z, K, 2)
        Rollers: pressure of every slice [Pa] (empty for balls).
    slice_xi : array (K,)
        Slice centres along the roller (fractions of the length; empty for balls).
    element_angles, element_load : arrays (N,)
        Angles [rad] and loads [N] of the elements the pressures belong to.
    row_life : array (2,) or None
        Double-row bearings: ``L10r`` of row 0 and row 1 (combined into ``L10r``,
        :mod:`rotorsim.analyses.statics.double_row_life`; per-element arrays list row 0
        first); None for a single row.
    options, stats, status, summary
    """

    kind: str
    source: str
    C: float
    C0: float
    rating_source: str
    load: FloatArray
    P: float
    L10: float
    L10r: float
    P_ref: float
    ring_life: FloatArray
    equivalent_load: FloatArray
    reference_load: FloatArray
    a1: float
    a_iso: float
    Lnmr: float
    Lnm: float
    max_pressure: FloatArray
    semi_major: FloatArray
    semi_minor: FloatArray
    shoulder_margin: FloatArray
    slice_pressure: FloatArray
    slice_xi: FloatArray
    element_angles: FloatArray
    element_load: FloatArray
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)
    row_life: FloatArray | None = None

    @property
    def peak_pressure(self) -> float:
        """Largest contact pressure of the bearing [Pa]."""
        return float(np.nanmax(self.max_pressure, initial=0.0))

    @property
    def truncated(self) -> bool:
        """True when a loaded ball's contact ellipse crosses a shoulder."""
        m = self.shoulder_margin
        return bool(np.any((m < 0) & (self.max_pressure > 0)))

    def hours(self, speed_rpm: float) -> float:
        """``L10r`` in operating hours at ``speed_rpm`` [rev/min] of the inner ring
        relative to the outer."""
        if not (math.isfinite(speed_rpm) and speed_rpm > 0):
            from rotorsim.errors import ModelError

            raise ModelError(f"speed must be positive [rpm], got {speed_rpm!r}",
                             "BearingLifeResult.hours")
        return float(self.L10r * 1e6 / (60.0 * speed_rpm))

    def pressure_table(self) -> str:
        """Plain-text table of every rolling element: angle, load, largest Hertz pressure on
        the inner and outer race and (balls) the inner-race ellipse and shoulder margin."""
        ball = self.slice_pressure.size == 0
        head = (f"{'element':>7} {'angle [deg]':>11} {'load [N]':>10} {'p_in [MPa]':>10} "
                f"{'p_out [MPa]':>11}")
        head += (f" {'a_in [mm]':>9} {'b_in [mm]':>9} {'margin [deg]':>12}" if ball
                 else f" {'b_in max [mm]':>13}")
        rows = [head, "-" * len(head)]
        for j in range(self.max_pressure.shape[0]):
            row = (f"{j:>7} {math.degrees(self.element_angles[j]) % 360.0:>11.1f} "
                   f"{self.element_load[j]:>10.2f} {self.max_pressure[j, 0] / 1e6:>10.1f} "
                   f"{self.max_pressure[j, 1] / 1e6:>11.1f}")
            if ball:
                margin = self.shoulder_margin[j, 0]
                row += (f" {self.semi_major[j, 0] * 1e3:>9.4f} {self.semi_minor[j, 0] * 1e3:>9.4f}"
                        f" {'-' if math.isnan(margin) else f'{math.degrees(margin):.2f}':>12}")
            else:
                row += f" {self.semi_minor[j, 0] * 1e3:>13.4f}"
            rows.append(row)
        return "\n".join(rows)

    def table(self) -> str:
        """Plain-text summary of the lives and the largest pressures."""
        def life(x: float) -> str:
            return "-" if not math.isfinite(x) else f"{x:.4g}"

        lines = [f"bearing life ({self.source}, {self.kind}): C = {self.C / 1e3:.4g} kN "
                 f"({self.rating_source})"]
        lines.append(f"  ISO 281:       P = {life(self.P)} N, L10 = {life(self.L10)} Mrev"
                     + (f", Lnm = {life(self.Lnm)}" if self.a_iso != 1 or self.a1 != 1
                        else ""))
        lines.append(f"  ISO/TS 16281:  L10r = {life(self.L10r)} Mrev, P_ref = "
                     f"{life(self.P_ref)} N, rings (inner, outer) {life(self.ring_life[0])}, "
                     f"{life(self.ring_life[1])} Mrev")
        if self.row_life is not None:
            lines.append("  rows:          L10r = " + ", ".join(life(x) for x in self.row_life)
                         + " Mrev (combined with the Weibull slope)")
        if self.a_iso != 1 or self.a1 != 1:
            lines.append(f"  a1 = {self.a1:.4g}, a_ISO = {self.a_iso:.4g}, Lnmr = "
                         f"{life(self.Lnmr)} Mrev")
        lines.append(f"  Q_e (inner, outer) = {self.equivalent_load[0]:.5g}, "
                     f"{self.equivalent_load[1]:.5g} N; Q_c = {self.reference_load[0]:.5g}, "
                     f"{self.reference_load[1]:.5g} N")
        p = self.max_pressure
        lines.append(f"  max Hertz pressure inner {np.nanmax(p[:, 0], initial=0) / 1e6:.1f}"
                     f" MPa, outer {np.nanmax(p[:, 1], initial=0) / 1e6:.1f} MPa"
                     + ("  (ellipse truncated at a shoulder)" if self.truncated else ""))
        return "\n".join(lines)
