"""API 617 Level I stability analysis: the log decrement of the first forward mode at the
maximum continuous speed against applied cross-coupled stiffness.

The anticipated cross-coupling Q_A of the stages (:func:`~rotorsim.analyses.standards.
api_formulas.anticipated_cross_coupling`) is applied as a linear bearing element with
``kxy = Q``, ``kyx = -Q`` (destabilising for forward whirl: the force ``(-Q y, Q x)``
pushes a forward orbit along its motion), at the mid-span of the bearing span (rotors
between bearings, API 617 7th ed. 2.6.5.6) or distributed over the stages in proportion to
their Q_A (overhung stages). The applied total is swept from 0 to ``q_max`` (API 684
SP6.8.5.8: to 10 Q_A); Q0, where the log decrement crosses 0, is bracketed on that grid
(extended by doubling when the log decrement stays positive) and found by Brent's method.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.analyses.linear.modal import modal
from rotorsim.analyses.standards.api_formulas import (
    anticipated_cross_coupling,
    csr_limit,
    level1_screening,
)
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.results.api import ApiLevel1Result
from rotorsim.solvers.stats import Stats

EXTENSIONS = 6
"""Doublings of the swept range tried when the log decrement stays positive."""


@dataclass(frozen=True)
class ApiStage:
    """Machine data of one stage (impeller or turbine stage) for Q_A.

    Parameters
    ----------
    node : int
        Node of the stage.
    power : float
        Stage power [W], > 0.
    diameter : float
        Impeller (or blade pitch) diameter [m], > 0.
    flow_height : float
        Flow-path height [m], > 0: the smaller of the diffuser and impeller discharge
        widths (compressor), the effective blade height (turbine).
    density_ratio : float
        Discharge over suction gas density of the stage (>= 1 for a compressor).
    tag : str, optional
        Name used in messages.
    """

    node: int
    power: float
    diameter: float
    flow_height: float
    density_ratio: float = 1.0
    tag: str | None = None

    def __post_init__(self) -> None:
        where = f"ApiStage '{self.tag}'" if self.tag else f"ApiStage(node={self.node})"
        if isinstance(self.node, bool) or not isinstance(self.node, int | np.integer) \
                or self.node < 0:
            raise ModelError(f"node must be a non-negative integer, got {self.node!r}", where)
        for name in ("power", "diameter", "flow_height", "density_ratio"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float | np.number) \
                    or not math.isfinite(value) or value <= 0:
                raise ModelError(f"{name} must be a finite number > 0, got {value!r}", where)


@checked_keywords
def api_level1(
    rotor: Rotor,
    mcs: float,
    stages: Sequence[ApiStage],
    *,
    machine: str = "compressor",
    apply_at: str = "midspan",
    density: float | None = None,
    q_max: float | None = None,
    num: int = 11,
    num_modes: int = 8,
    rtol: float = 1e-8,
) -> ApiLevel1Result:
    """API 617 Level I stability analysis of ``rotor`` at the maximum continuous speed.

    Parameters
    ----------
    rotor : Rotor
        The rotor on its bearings (Level I: bearings only, no seal coefficients).
    mcs : float
        Maximum continuous speed [rad/s], > 0.
    stages : list of ApiStage
        Machine data of each stage (at least one).
    machine : {"compressor", "turbine"}
    apply_at : {"midspan", "stages"}
        Apply the cross-coupling at the node nearest the middle of the bearing span, or
        at the stage nodes in proportion to their Q_A (overhung rotors).
    density : float, optional
        Average gas density [kg/m^3] for the Region A/B screening of compressors.
    q_max : float, optional
        End of the swept total cross-coupling [N/m]; default 10 Q_A.
    num : int
        Points of the sweep (>= 2).
    num_modes : int
        Modes computed at each point (the first forward mode is taken among them).
    rtol : float
        Relative tolerance of Q0.

    Returns
    -------
    ApiLevel1Result

    Raises
    ------
    ModelError
        No stages, a non-positive machine datum, ``mcs`` not > 0, an unknown ``machine`` or
        ``apply_at``, a rotor without bearings or of several shaft lines.

    References
    ----------
    API Standard 617, 7th ed. (2002), 2.6.5 (Level I); API RP 684, 2nd ed. (2005),
    SP6.8.5; Wachel, J.C., von Nimitz, W.W. (1981), "Ensuring the reliability of offshore
    gas compression systems", J. Petroleum Technology 33(11) (the Q_A estimate).

    Examples
    --------
    >>> import rotorsim as rs
    >>> disk = rs.DiskElement(n=0, m=100.0, Id=1.0, Ip=1.5)
    >>> bearing = rs.BearingElement(n=0, kxx=1e7, cxx=2e3, kzz=1e7, krr=1e6)
    >>> rotor = rs.Rotor([], [disk], [bearing]).without_axial_torsion()
    >>> stage = ApiStage(node=0, power=5e4, diameter=0.3, flow_height=0.02)
    >>> r = api_level1(rotor, 1000.0, [stage], apply_at="stages")
    >>> round(r.q0 / (2e3 * (1e7 / 100.0) ** 0.5), 6)   # Jeffcott: Q0 = c wn
    1.0
    """
    where = "api_level1"
    check_one_line(rotor, where)
    if isinstance(mcs, bool) or not isinstance(mcs, int | float | np.number) \
            or not math.isfinite(mcs) or mcs <= 0:
        raise ModelError(f"mcs must be a finite speed > 0 [rad/s], got {mcs!r}", where)
    if not stages:
        raise ModelError("no stages given: Q_A needs the machine data (power, diameter, "
                         "flow_height, density_ratio) of at least one stage", where)
    if not all(isinstance(s, ApiStage) for s in stages):
        raise ModelError("stages must be ApiStage objects", where)
    if not rotor.bearing_elements:
        raise ModelError("the rotor has no bearings", where)
    if num < 2:
        raise ModelError(f"num must be >= 2, got {num}", where)
    for s in stages:
        if s.node >= rotor.n_nodes:
            raise ModelError(f"stage node {s.node} outside 0..{rotor.n_nodes - 1}", where)
    stage_q = anticipated_cross_coupling(
        [s.power for s in stages], float(mcs), [s.diameter for s in stages],
        [s.flow_height for s in stages], [s.density_ratio for s in stages], machine)
    q_a = float(stage_q.sum())
    stations, share = _stations(rotor, stages, stage_q, apply_at)
    stats = Stats()
    first = _FirstForward(rotor, float(mcs), stations, share, num_modes, stats)
    top = 10.0 * q_a if q_max is None else float(q_max)
    if not math.isfinite(top) or top <= 0:
        raise ModelError(f"q_max must be a finite value > 0 [N/m], got {q_max!r}", where)
    applied = np.linspace(0.0, top, num)
    log_dec, freq = np.array([first(q) for q in applied]).T
    q0, applied, log_dec, freq, notes = _zero_crossing(first, applied, log_dec, freq, rtol)
    log_dec_a = first(q_a)[0]
    crit = _rigid_critical_speed(rotor)
    csr = float(mcs) / crit
    if math.isnan(crit):
        notes += ("no forward critical speed on rigid supports (a rigid rotor): the CSR "
                  "is undefined and the Region A/B test is skipped",)
    required, reasons = level1_screening(q0 / q_a, log_dec_a, csr, density, machine)
    return ApiLevel1Result(
        mcs=float(mcs), machine=machine, stage_nodes=np.array([s.node for s in stages]),
        stage_q=stage_q, q_a=q_a, stations=stations, station_share=share, applied=applied,
        log_dec=log_dec, frequency=freq, log_dec_a=float(log_dec_a), q0=q0,
        q_ratio=q0 / q_a, critical_speed_rigid=crit, csr=csr,
        density=math.nan if density is None else float(density),
        csr_limit=math.nan if density is None else csr_limit(float(density)),
        level2_required=required, reasons=reasons,
        options={"apply_at": apply_at, "q_max": top, "num": num, "num_modes": num_modes,
                 "rtol": rtol, "stage_tags": [s.tag or "" for s in stages]},
        stats=stats.finish(), summary=rotor.summary(), notes=notes)


def check_one_line(rotor: Rotor, where: str) -> None:
    """Refuse anything but a :class:`Rotor` of one shaft line: API 617's mid-span, anti-nodes
    and critical speed ratio are those of one rotor on its bearings."""
    if not isinstance(rotor, Rotor):
        raise ModelError(f"expected a Rotor, got {type(rotor).__name__}", where)
    lines = rotor.layout.lines
    if len(lines) > 1:
        raise ModelError(
            f"API 617 Level I takes a rotor of one shaft line; this machine has {len(lines)} "
            f"({', '.join(line.name for line in lines)}), whose first forward mode, bearing "
            "mid-span and rigid-support critical speed mix the spools and the casing: check "
            "each spool as its own Rotor on its bearings", where)


def _stations(rotor: Rotor, stages: Sequence[ApiStage], stage_q: NDArray[np.float64],
              apply_at: str) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Nodes of the applied cross-coupling and the share of the total at each."""
    if apply_at == "midspan":
        span = rotor.nodes_pos[[b.n for b in rotor.bearing_elements]]
        middle = 0.5 * (span.min() + span.max())
        return np.array([int(np.argmin(np.abs(rotor.nodes_pos - middle)))]), np.ones(1)
    if apply_at == "stages":
        nodes, index = np.unique([s.node for s in stages], return_inverse=True)
        share = np.bincount(index, weights=stage_q) / stage_q.sum()
        return nodes.astype(np.int64), share
    raise ModelError(f"apply_at must be 'midspan' or 'stages', got {apply_at!r}",
                     "api_level1")


class _FirstForward:
    """``q -> (log dec, damped frequency)`` of the first forward mode at the MCS with the
    total cross-coupling ``q`` applied at the stations."""

    def __init__(self, rotor: Rotor, speed: float, stations: NDArray[np.int64],
                 share: NDArray[np.float64], num_modes: int, stats: Stats) -> None:
        self.rotor, self.speed, self.stations, self.share = rotor, speed, stations, share
        self.num_modes, self.stats = num_modes, stats

    def __call__(self, q: float) -> tuple[float, float]:
        extra = [BearingElement(n=int(n), kxy=q * s, kyx=-q * s, tag=f"api_q_{n}")
                 for n, s in zip(self.stations, self.share, strict=True)]
        rotor = self.rotor.with_bearings([*self.rotor.bearing_elements, *extra])
        m = modal(rotor, speed=self.speed, num_modes=self.num_modes, stats=self.stats)
        forward = [j for j in range(m.num_modes)
                   if m.kind[j] == "lateral" and m.whirl_ratio[j] > 0]
        if not forward:
            raise ConvergenceError(f"no forward lateral mode among the {m.num_modes} modes "
                                   f"at Q = {q:.6g} N/m: raise num_modes", "api_level1")
        j = min(forward, key=lambda i: m.wn[i])
        return float(m.log_dec[j]), float(m.wd[j])


def _zero_crossing(first: _FirstForward, applied: NDArray[np.float64],
                   log_dec: NDArray[np.float64], freq: NDArray[np.float64], rtol: float
                   ) -> tuple[float, NDArray, NDArray, NDArray, tuple[str, ...]]:
    """Q0 by Brent's method on the first grid interval where the log decrement changes
    sign, the grid extended by doubling while it stays positive."""
    from scipy.optimize import brentq

    notes: list[str] = []
    if log_dec[0] <= 0:
        notes.append("the first forward mode is unstable without applied cross-coupling")
        return 0.0, applied, log_dec, freq, tuple(notes)
    for _ in range(EXTENSIONS + 1):
        below = np.flatnonzero(log_dec <= 0)
        if below.size:
            i = int(below[0])
            q0 = brentq(lambda q: first(q)[0], applied[i - 1], applied[i],
                        xtol=rtol * applied[i], rtol=max(rtol, 4 * np.finfo(float).eps))
            return float(q0), applied, log_dec, freq, tuple(notes)
        more = applied[-1] * np.linspace(1.0, 2.0, applied.size)[1:]
        extra = np.array([first(q) for q in more]).T
        applied = np.concatenate([applied, more])
        log_dec = np.concatenate([log_dec, extra[0]])
        freq = np.concatenate([freq, extra[1]])
    notes.append(f"the log decrement stays > 0 up to Q = {applied[-1]:.6g} N/m: Q0 = inf")
    return math.inf, applied, log_dec, freq, tuple(notes)


def _rigid_critical_speed(rotor: Rotor) -> float:
    """First forward undamped critical speed with the bearing nodes held (rigid supports),
    the speed the CSR of API 617 refers to [rad/s]."""
    held = sorted({b.n for b in rotor.bearing_elements if b.n_link is None})
    rigid = rotor.with_fixed([(n, d) for n in held for d in ("ux", "uy")])
    cs = critical_speeds(rigid, num_modes=1, whirl="forward")
    return float(cs.speed[0]) if len(cs) else math.nan
