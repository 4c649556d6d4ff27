"""Results of the API 617 checks: Level I stability and the unbalance response analysis."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import Status

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]
RPM = 30.0 / np.pi
"""rpm per rad/s."""


@dataclass(frozen=True, eq=False)
class ApiLevel1Result:
    """API 617 Level I stability: the first forward mode at the maximum continuous speed
    against applied cross-coupled stiffness (:func:`rotorsim.api_level1`).

    Attributes
    ----------
    mcs : float
        Maximum continuous speed [rad/s].
    machine : str
        ``"compressor"`` or ``"turbine"``.
    stage_nodes : int array (S,)
        Node of each stage (impeller, turbine stage).
    stage_q : array (S,)
        Anticipated cross-coupling Q_A of each stage [N/m].
    q_a : float
        Q_A of the machine, the sum of ``stage_q`` [N/m].
    stations : int array (P,)
        Nodes where the cross-coupling is applied (mid-span, or the stages).
    station_share : array (P,)
        Fraction of the total applied cross-coupling at each station.
    applied : array (Q,)
        Total applied cross-coupling of the sweep [N/m] (``kxy = Q``, ``kyx = -Q``).
    log_dec, frequency : array (Q,)
        Log decrement [-] and damped natural frequency [rad/s] of the first forward mode
        at each ``applied``.
    log_dec_a : float
        Log decrement at Q_A.
    q0 : float
        Applied cross-coupling at which the log decrement reaches 0 [N/m] (``inf`` if it
        stays positive over the sweep and its extension; see ``notes``).
    q_ratio : float
        Q0 / Q_A.
    critical_speed_rigid : float
        First forward undamped critical speed on rigid supports [rad/s].
    csr : float
        Critical speed ratio ``mcs / critical_speed_rigid``.
    density : float
        Average gas density [kg/m^3] (NaN when not given).
    csr_limit : float
        CSR on the Region A/B boundary at ``density`` (NaN when not given).
    level2_required : bool
        The Level I screening asks for a Level II analysis.
    reasons : tuple of str
        Why (empty when not required).
    """

    mcs: float
    machine: str
    stage_nodes: IntArray
    stage_q: FloatArray
    q_a: float
    stations: IntArray
    station_share: FloatArray
    applied: FloatArray
    log_dec: FloatArray
    frequency: FloatArray
    log_dec_a: float
    q0: float
    q_ratio: float
    critical_speed_rigid: float
    csr: float
    density: float
    csr_limit: float
    level2_required: bool
    reasons: tuple[str, ...]
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()

    def table(self) -> list[tuple[str, str]]:
        """Rows ``(quantity, value)`` of the Level I summary, in the units engineers read
        (rpm, N/mm), traceable to the fields above."""
        rows = [("MCS [rpm]", f"{self.mcs * RPM:.1f}"),
                ("QA [N/mm]", f"{self.q_a / 1e3:.4g}"),
                ("log dec at QA", f"{self.log_dec_a:.4g}"),
                ("Q0 [N/mm]", f"{self.q0 / 1e3:.4g}"),
                ("Q0/QA", f"{self.q_ratio:.4g}"),
                ("first critical speed, rigid supports [rpm]",
                 f"{self.critical_speed_rigid * RPM:.1f}"),
                ("CSR", f"{self.csr:.4g}"),
                ("average gas density [kg/m^3]",
                 "-" if np.isnan(self.density) else f"{self.density:.4g}"),
                ("Level II required", "yes" if self.level2_required else "no")]
        return rows


@dataclass(frozen=True, eq=False)
class ApiUnbalanceResult:
    """API 617 unbalance response analysis of each mode in the analysed speed range
    (:func:`rotorsim.api_unbalance`). Per mode ``m`` (M modes), the unbalance is placed
    at the anti-nodes of its shape, and the response gives the amplification factor, the
    separation margins and the clearance ratios.

    Attributes
    ----------
    speeds : array (F,)
        Analysed spin speeds [rad/s].
    min_speed, mcs : float
        Operating speed range [rad/s].
    mode_speed, mode_log_dec : array (M,)
        Damped critical speed of each mode (crossing of the 1X line) [rad/s] and its log
        decrement there.
    unbalance_mode, unbalance_node : int array (K,)
        Mode and node of each unbalance plane.
    unbalance_magnitude, unbalance_phase : array (K,)
        Unbalance [kg m] and angle [rad] of each plane.
    response_node : int array (M,)
        Node at which the amplification factor is evaluated (the largest anti-node).
    major_pp : array (M, F, N)
        Peak-to-peak major axis of every node's orbit at every speed, per mode [m].
    peak_speed, peak_pp : array (M,)
        Speed [rad/s] and peak-to-peak major axis [m] of the resonance peak at
        ``response_node``.
    half_power_low, half_power_high : array (M,)
        Speeds where the major axis is ``peak / sqrt(2)`` [rad/s] (NaN outside the range).
    af : array (M,)
        Amplification factor ``peak_speed / (half_power_high - half_power_low)`` (NaN
        without a half-power band: ``notes`` says whether the mode counts as critically
        damped, ``pi / mode_log_dec < 2.5``, or the speeds are too short).
    required_margin, actual_margin : array (M,)
        Separation margins as fractions (of the minimum speed for a resonance below the
        operating range, of the MCS above it; negative inside it).
    margin_ok : bool array (M,)
    vibration_limit : float
        Av1 [m] peak-to-peak.
    probe_nodes : int array (R,)
        Nodes of the vibration probes (default: the bearings).
    probe_peak, scale_factor : array (M,)
        Largest probe response in the operating range [m] and Scc = Av1 / probe_peak,
        held within [0.5, 6].
    clearance_nodes : int array (C,)
    clearance : array (C,)
        Diametral running clearance [m].
    clearance_tags : tuple of str (C,)
    clearance_ratio : array (M, C)
        Scaled peak-to-peak response over the clearance (largest over the speeds).
    clearance_ok : bool array (M, C)
        ``clearance_ratio < 0.75``.
    passed : bool
        Every margin and clearance check passes.
    """

    speeds: FloatArray
    min_speed: float
    mcs: float
    mode_speed: FloatArray
    mode_log_dec: FloatArray
    unbalance_mode: IntArray
    unbalance_node: IntArray
    unbalance_magnitude: FloatArray
    unbalance_phase: FloatArray
    response_node: IntArray
    major_pp: FloatArray
    peak_speed: FloatArray
    peak_pp: FloatArray
    half_power_low: FloatArray
    half_power_high: FloatArray
    af: FloatArray
    required_margin: FloatArray
    actual_margin: FloatArray
    margin_ok: BoolArray
    vibration_limit: float
    probe_nodes: IntArray
    probe_peak: FloatArray
    scale_factor: FloatArray
    clearance_nodes: IntArray
    clearance: FloatArray
    clearance_tags: tuple[str, ...]
    clearance_ratio: FloatArray
    clearance_ok: BoolArray
    passed: bool
    nodes_pos: FloatArray
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()

    @property
    def num_modes(self) -> int:
        return int(self.mode_speed.size)

    def table(self) -> list[tuple[str, ...]]:
        """Rows of the API table, one per mode: mode, critical speed [rpm], AF, required
        and actual separation margin [%], pass/fail, largest clearance ratio."""
        rows: list[tuple[str, ...]] = []
        for m in range(self.num_modes):
            ratio = self.clearance_ratio[m]
            rows.append((str(m), f"{self.peak_speed[m] * RPM:.0f}", f"{self.af[m]:.3g}",
                         f"{100 * self.required_margin[m]:.1f}",
                         f"{100 * self.actual_margin[m]:.1f}",
                         "pass" if self.margin_ok[m] else "FAIL",
                         f"{ratio.max():.3g}" if ratio.size else "-"))
        return rows
