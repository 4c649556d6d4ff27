"""API 617 unbalance response analysis: for each mode whose critical speed lies in the
analysed speed range, the unbalance U = 6350 W / N (per plane) is placed at the anti-nodes
of the mode shape, and the response gives the amplification factor (half-power method on
the orbit's major axis), the separation margins against the operating speed range, and
the scaled response at the close clearances (API 617 7th ed. 2.6.2.7-2.6.2.11; API 684
SP6.8.2).

The modes are the forward (or mixed, predominantly forward) lateral crossings of the 1X
line of a Campbell diagram over the analysed speeds (damped, with the bearing coefficients
at each speed); each mode's shape is the complex mode at its critical speed.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.linear.campbell import campbell
from rotorsim.analyses.linear.frequency_response import unbalance_response
from rotorsim.analyses.linear.modal import modal
from rotorsim.analyses.standards.api_formulas import (
    AF_CRITICALLY_DAMPED,
    CLEARANCE_LIMIT,
    required_separation_margin,
    residual_unbalance,
    vibration_limit,
)
from rotorsim.analyses.standards.half_power import HalfPower, half_power
from rotorsim.analyses.standards.spool import Spool, spool_of
from rotorsim.elements.base import as_float_array
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.results.api import RPM, ApiUnbalanceResult
from rotorsim.results.frequency_response import FrequencyResponseResult
from rotorsim.results.orbits import ellipse

FloatArray = NDArray[np.float64]
ANTINODE_FRACTION = 0.5
"""A local maximum of a mode's orbit size is an anti-node (an unbalance plane) when it is
at least this fraction of the largest one."""
CAMPBELL_POINTS = 41
"""Speeds of the Campbell diagram that locates the critical speeds."""


@dataclass(frozen=True)
class Clearance:
    """A close clearance (seal, bearing) checked against the scaled response.

    Parameters
    ----------
    node : int
        Node of the clearance.
    clearance : float
        Diametral running clearance [m], > 0.
    tag : str
        Name in the tables.
    """

    node: int
    clearance: float
    tag: str = ""

    def __post_init__(self) -> None:
        if not (isinstance(self.clearance, int | float) and math.isfinite(self.clearance)
                and self.clearance > 0):
            raise ModelError(f"clearance must be a finite length > 0 [m], got "
                             f"{self.clearance!r}", f"Clearance '{self.tag or self.node}'")


@checked_keywords
def api_unbalance(
    rotor: Rotor,
    speeds: ArrayLike,
    *,
    min_speed: float,
    mcs: float,
    num_modes: int = 3,
    clearances: Sequence[Clearance] = (),
    probes: Sequence[int] | None = None,
    plane_mass: float | None = None,
    factor: float = 1.0,
    spool: str | None = None,
) -> ApiUnbalanceResult:
    """API 617 unbalance response analysis of the modes in the analysed speed range.

    Parameters
    ----------
    rotor : Rotor
        The rotor on its bearings.
    speeds : array (F,)
        Increasing spin speeds of the spool [rad/s]; they must cover the operating range
        (API: from 0 to the trip speed) and resolve each resonance peak (a few points within its
        half-power band): the peak and the band are refined on the response, but a peak
        the grid misses (e.g. one of two close peaks on anisotropic supports) is not.
    min_speed, mcs : float
        Minimum operating and maximum continuous speeds of the spool [rad/s].
    num_modes : int
        At most this many modes (the lowest critical speeds in the range).
    clearances : list of Clearance
        Close clearances to check.
    probes : list of int, optional
        Nodes of the vibration probes for the scale factor (default: the bearing nodes).
    plane_mass : float, optional
        W of ``U = 6350 W / N`` for each plane [kg]; default the rotor (spool) mass over
        the number of planes of the mode (the sum of the journal loads for a one-plane
        mode, each journal's load for two planes of a symmetric rotor).
    factor : float
        Multiple of U applied (API 617 editions and purchasers differ: 1 or 2).
    spool : str, optional
        On a machine of several lines (required there): the line checked. Its speeds,
        critical speeds and margins are its own (``r W`` for the reference speed ``W``),
        its unbalance goes to the anti-nodes of each mode on it, and the default probes
        are its bearing nodes (inter-shaft bearings included)
        (:mod:`~rotorsim.analyses.standards.spool`).

    Returns
    -------
    ApiUnbalanceResult

    Raises
    ------
    ModelError
        Speeds not covering ``min_speed .. mcs`` (the MCS outside the analysed range),
        ``min_speed > mcs``, non-positive speeds, factor or plane mass, a node out of
        range, no mode in the range, or on a machine of several lines a missing, unknown,
        non-rotating or counter-rotating ``spool``.

    References
    ----------
    API Standard 617, 7th ed. (2002), 2.6.2.7-2.6.2.11; API RP 684, 2nd ed. (2005),
    SP6.8.2 (amplification factor by the half-power method, separation margins).

    Examples
    --------
    >>> import numpy as np, rotorsim as rs
    >>> disk = rs.DiskElement(n=0, m=50.0, Id=0.01, Ip=0.02)
    >>> rotor = rs.Rotor([], [disk], [rs.BearingElement(n=0, kxx=5e6, cxx=1581.14)])
    >>> rotor = rotor.with_fixed([(0, d) for d in ("uz", "rx", "ry", "rz")])
    >>> r = api_unbalance(rotor, np.linspace(30.0, 800.0, 241), min_speed=500.0, mcs=630.0)
    >>> round(float(r.af[0]), 2), bool(r.margin_ok[0])   # zeta = 0.05: AF ~ 1/(2 zeta)
    (9.9, True)
    """
    sp = spool_of(rotor, spool, "api_unbalance")
    w, probes_arr = _check(rotor, speeds, min_speed, mcs, factor, plane_mass, probes,
                           clearances, sp)
    crit, crit_log_dec = _critical_speeds(rotor, w, num_modes, sp)
    mcs_rpm = mcs * RPM
    av1 = vibration_limit(mcs_rpm)
    rows: list[tuple[int, FloatArray, HalfPower]] = []
    planes: list[tuple[int, int, float, float]] = []
    notes: list[str] = [] if not sp.machine else [
        f"spool {sp.name} (speed ratio {sp.ratio:g}): speeds, critical speeds and margins "
        f"are the spool's own ({sp.ratio:g} times the reference speed); unbalance on the "
        "spool only"]
    for m, wc in enumerate(crit):
        nodes, phases, response_node = _antinodes(rotor, wc, num_modes, sp)
        mass = sp.mass / nodes.size if plane_mass is None else plane_mass
        u = factor * residual_unbalance(mass, mcs_rpm)[0]
        plan = [(int(n), float(u), float(a)) for n, a in zip(nodes, phases, strict=True)]
        planes += [(m, *p) for p in plan]
        major_pp, hp = _mode_response(rotor, w, plan, response_node, wc, sp.ratio)
        if math.isnan(hp.af):  # no band: the resonance is taken at the crossing
            near = int(np.argmin(np.abs(w - wc)))
            hp = HalfPower(float(wc), float(major_pp[near, response_node]), hp.low, hp.high)
            notes.append(_no_band_note(m, wc, crit_log_dec[m], w))
        rows.append((response_node, major_pp, hp))
    return _result(rotor, w, min_speed, mcs, (crit, crit_log_dec), planes, rows, av1,
                   probes_arr, clearances, notes, factor, sp)


def _mode_response(rotor: Rotor, w: FloatArray, plan: list[tuple[int, float, float]],
                   node: int, wc: float, ratio: float) -> tuple[FloatArray, HalfPower]:
    """Peak-to-peak major axes (F, N) of the response to the unbalance ``plan`` over the
    spool speeds ``w`` (reference speeds ``w / ratio``) and the half-power band of the peak
    nearest ``wc`` at ``node`` (refined on the response)."""
    major_pp = _major_pp(unbalance_response(rotor, w / ratio, plan))
    index = _peak_index(w, major_pp[:, node], wc)
    if index in (0, w.size - 1):  # no resonance peak inside the speeds
        return major_pp, HalfPower(float(wc), math.nan, math.nan, math.nan)

    def response(speed: float) -> float:
        return float(_major_pp(unbalance_response(rotor, [speed / ratio], plan))[0, node])

    return major_pp, half_power(w, major_pp[:, node], index, response)


def _no_band_note(m: int, wc: float, log_dec: float, w: FloatArray) -> str:
    estimate = math.pi / log_dec if log_dec > 0 else math.inf
    if estimate < AF_CRITICALLY_DAMPED:
        return (f"mode {m} ({wc * RPM:.0f} rpm): no half-power band; log dec {log_dec:.3g} "
                f"at the crossing (AF ~ pi/log dec = {estimate:.2g} < 2.5): critically "
                "damped, no separation margin required")
    return (f"mode {m} ({wc * RPM:.0f} rpm): a half-power point lies outside the analysed "
            f"speeds ({w[0] * RPM:.0f}-{w[-1] * RPM:.0f} rpm); AF undefined: extend them")


def _check(rotor: Rotor, speeds: ArrayLike, min_speed: float, mcs: float, factor: float,
           plane_mass: float | None, probes: Sequence[int] | None,
           clearances: Sequence[Clearance], sp: Spool) -> tuple[FloatArray, NDArray[np.int64]]:
    where = "api_unbalance"
    w = np.atleast_1d(as_float_array(speeds, "speeds", where))
    if w.ndim != 1 or w.size < 3 or not np.all(np.isfinite(w)) or np.any(w < 0) \
            or np.any(np.diff(w) <= 0):
        raise ModelError("speeds must be >= 3 finite, non-negative, increasing values "
                         "[rad/s]", where)
    for name, value in (("min_speed", min_speed), ("mcs", mcs), ("factor", factor),
                        *([("plane_mass", plane_mass)] if plane_mass is not None else [])):
        if isinstance(value, bool) or not isinstance(value, int | float | np.number) \
                or not math.isfinite(value) or value <= 0:
            raise ModelError(f"{name} must be a finite number > 0, got {value!r}", where)
    if min_speed > mcs:
        raise ModelError(f"min_speed {min_speed:.6g} rad/s exceeds mcs {mcs:.6g} rad/s",
                         where)
    if w[0] > min_speed or w[-1] < mcs:
        raise ModelError(
            f"the analysed speeds {w[0] * RPM:.6g}-{w[-1] * RPM:.6g} rpm do not cover the "
            f"operating range {min_speed * RPM:.6g}-{mcs * RPM:.6g} rpm (MCS outside the "
            "analysed range)", where)
    default = sp.bearing_nodes(rotor) if sp.machine else sorted(
        {b.n for b in rotor.bearing_elements})
    probe_nodes = np.array(default if probes is None else list(probes), dtype=np.int64)
    for n in (*probe_nodes.tolist(), *(c.node for c in clearances)):
        if not 0 <= n < rotor.n_nodes:
            raise ModelError(f"node {n} outside 0..{rotor.n_nodes - 1}", where)
    if probe_nodes.size == 0:
        raise ModelError("no probe nodes (the rotor has no bearings): give probes", where)
    return w, probe_nodes


def _critical_speeds(rotor: Rotor, w: FloatArray, num_modes: int, sp: Spool
                     ) -> tuple[FloatArray, FloatArray]:
    """Forward lateral crossings of the spool's 1X line within its speeds ``w``, lowest
    first (in spool speed), and their log decrements."""
    grid = np.linspace(w[0], w[-1], CAMPBELL_POINTS) / sp.ratio
    extra = 4 * len(rotor.layout.lines)  # a machine's other lines add modes below
    diagram = campbell(rotor, grid, num_modes=num_modes + extra)
    cs = diagram.critical_speeds(harmonic=1, spool=sp.name if sp.machine else None)
    cs = dataclasses.replace(cs, speed=cs.speed * sp.ratio) if sp.machine else cs
    keep = np.flatnonzero((cs.kind == "lateral") & (cs.whirl != "backward"))
    if keep.size == 0:
        raise ModelError(f"no forward critical speed between {w[0] * RPM:.6g} and "
                         f"{w[-1] * RPM:.6g} rpm: extend the speeds", "api_unbalance")
    order = keep[np.argsort(cs.speed[keep], kind="stable")][:num_modes]
    return cs.speed[order], cs.log_dec[order]


def _antinodes(rotor: Rotor, wc: float, num_modes: int, sp: Spool
               ) -> tuple[NDArray[np.int64], FloatArray, int]:
    """Unbalance planes of the mode at the spool's critical speed ``wc`` (the mode whirls
    at ``wc``; the machine turns at ``wc / ratio``): the local maxima of the orbit size
    along the spool (at least :data:`ANTINODE_FRACTION` of the largest), with the angle of
    the forward component there; and the node of the largest."""
    extra = 4 * len(rotor.layout.lines)
    m = modal(rotor, speed=wc / sp.ratio, num_modes=num_modes + extra)
    lateral = [j for j in range(m.num_modes) if m.kind[j] == "lateral"
               and m.whirl_ratio[j] > 0]
    j = min(lateral, key=lambda i: abs(m.wd[i] - wc))
    ux, uy = (u[sp.nodes] for u in m.lateral_shape(j))
    size = ellipse(ux, uy).major
    padded = np.concatenate([[-np.inf], size, [-np.inf]])
    peaks = np.flatnonzero((size >= padded[:-2]) & (size > padded[2:])
                           & (size >= ANTINODE_FRACTION * size.max()))
    phases = np.angle(ux[peaks] + 1j * uy[peaks])
    nodes = sp.nodes[peaks]
    return nodes, phases, int(nodes[np.argmax(size[peaks])])


def _major_pp(result: FrequencyResponseResult) -> FloatArray:
    """Peak-to-peak major axis (F, n_nodes) of every node's orbit [m]."""
    nodes = result.response[:, :, 0].reshape(result.frequencies.size, -1, 6)
    return 2.0 * ellipse(nodes[:, :, 0], nodes[:, :, 1]).major


def _peak_index(w: FloatArray, amp: FloatArray, wc: float) -> int:
    """The sampled local maximum nearest the critical speed ``wc``."""
    inner = np.flatnonzero((amp[1:-1] >= amp[:-2]) & (amp[1:-1] >= amp[2:])) + 1
    if inner.size == 0:
        return int(np.argmax(amp))
    return int(inner[np.argmin(np.abs(w[inner] - wc))])


def _margins(peak: FloatArray, af: FloatArray, log_dec: FloatArray, min_speed: float,
             mcs: float) -> tuple[FloatArray, FloatArray, NDArray[np.bool_]]:
    """Required and actual separation margins and the pass flags of each resonance. A
    resonance without a half-power band counts as critically damped when its log
    decrement at the crossing gives ``AF ~ pi / log dec < 2.5`` (API 684 SP6.8.2.1)."""
    below = peak < 0.5 * (min_speed + mcs)
    actual = np.where(peak < min_speed, (min_speed - peak) / min_speed,
                      np.where(peak > mcs, (peak - mcs) / mcs,
                               -np.minimum((peak - min_speed) / min_speed,
                                           (mcs - peak) / mcs)))
    with np.errstate(divide="ignore"):
        estimate = np.where(log_dec > 0, np.pi / log_dec, np.inf)
    damped = np.where(np.isnan(af), estimate, af) < AF_CRITICALLY_DAMPED
    required = np.where(damped, 0.0, required_separation_margin(af, below))
    required = np.where(np.isnan(af) & ~damped, np.nan, required)
    return required, actual, damped | (actual >= required)


def _result(rotor: Rotor, w: FloatArray, min_speed: float, mcs: float,
            crossings: tuple[FloatArray, FloatArray],
            planes: list[tuple[int, int, float, float]],
            rows: list[tuple[int, FloatArray, HalfPower]], av1: float,
            probes: NDArray[np.int64], clearances: Sequence[Clearance], notes: list[str],
            factor: float, sp: Spool) -> ApiUnbalanceResult:
    major = np.stack([r[1] for r in rows])                       # (M, F, N)
    hps = [r[2] for r in rows]
    peak = np.array([h.peak_speed for h in hps])
    af = np.array([h.af for h in hps])
    crit, crit_log_dec = crossings
    required, actual, margin_ok = _margins(peak, af, crit_log_dec, min_speed, mcs)
    operating = (w >= min_speed) & (w <= mcs)
    probe_peak = major[:, operating][:, :, probes].max(axis=(1, 2))
    scale = np.clip(av1 / probe_peak, 0.5, 6.0)
    c_nodes = np.array([c.node for c in clearances], dtype=np.int64)
    c_values = np.array([c.clearance for c in clearances], dtype=float)
    worst = major[:, :, c_nodes].max(axis=1) if c_nodes.size else np.zeros((len(rows), 0))
    ratio = scale[:, None] * worst / c_values[None, :] if c_nodes.size else worst
    c_ok = ratio < CLEARANCE_LIMIT
    k = np.array(planes, dtype=float).reshape(-1, 4)
    return ApiUnbalanceResult(
        speeds=w, min_speed=float(min_speed), mcs=float(mcs), mode_speed=crit,
        mode_log_dec=crit_log_dec,
        unbalance_mode=k[:, 0].astype(np.int64), unbalance_node=k[:, 1].astype(np.int64),
        unbalance_magnitude=k[:, 2], unbalance_phase=k[:, 3],
        response_node=np.array([r[0] for r in rows], dtype=np.int64), major_pp=major,
        peak_speed=peak, peak_pp=np.array([h.peak for h in hps]),
        half_power_low=np.array([h.low for h in hps]),
        half_power_high=np.array([h.high for h in hps]), af=af, required_margin=required,
        actual_margin=actual, margin_ok=margin_ok, vibration_limit=av1, probe_nodes=probes,
        probe_peak=probe_peak, scale_factor=scale, clearance_nodes=c_nodes,
        clearance=c_values, clearance_tags=tuple(c.tag or str(c.node) for c in clearances),
        clearance_ratio=ratio, clearance_ok=c_ok,
        passed=bool(margin_ok.all() and c_ok.all()), nodes_pos=rotor.nodes_pos,
        options={"factor": factor, "antinode_fraction": ANTINODE_FRACTION,
                 **({"spool": sp.name, "speed_ratio": sp.ratio} if sp.machine else {})},
        summary=rotor.summary(), notes=tuple(notes))
