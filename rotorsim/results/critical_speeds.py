"""Critical speeds and the critical-speed map (undamped critical speeds vs support stiffness)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.assembly.dof_map import DofMap
from rotorsim.errors import ModelError, Status

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
StrArray = NDArray[np.str_]
ComplexArray = NDArray[np.complex128]

WHIRL_FILTERS = (None, "forward", "backward")


def check_whirl_filter(whirl: str | None, where: str) -> None:
    """Raise :class:`ModelError` unless ``whirl`` is ``None``, ``"forward"`` or ``"backward"``."""
    if whirl not in WHIRL_FILTERS:
        raise ModelError(f"whirl must be one of {WHIRL_FILTERS}, got {whirl!r}", where)


def check_harmonic(harmonic: float, where: str) -> float:
    """Validate the excitation order ``harmonic`` (> 0, finite) and return it as float."""
    try:
        value = float(harmonic)
    except (TypeError, ValueError) as exc:
        raise ModelError(f"harmonic must be a number, got {harmonic!r}", where) from exc
    if not np.isfinite(value) or value <= 0:
        raise ModelError(f"harmonic must be finite and > 0, got {harmonic!r}", where)
    return value


@dataclass(frozen=True, eq=False)
class CriticalSpeeds:
    """Spin speeds at which a mode's frequency equals ``harmonic`` times the spin speed.

    Entries are sorted by speed.

    Attributes
    ----------
    speed : array (n,)
        Critical spin speed ``W`` [rad/s].
    frequency : array (n,)
        Whirl frequency at the crossing, ``harmonic * speed`` [rad/s].
    mode : int array (n,)
        Campbell track index, or rank of the mode among the exact critical speeds.
    whirl : str array (n,)
        ``"forward"``, ``"backward"``, ``"mixed"`` (lateral) or ``"none"`` (axial, torsional).
    kind : str array (n,)
        ``"lateral"``, ``"axial"`` or ``"torsional"``.
    log_dec : array (n,)
        Logarithmic decrement at the crossing [-]; ``NaN`` where damping was not computed
        (exact undamped analysis).
    harmonic : float
        Excitation order ``k`` of the line ``w = k W`` (1 for unbalance).
    mode_shapes : complex array (ndof, n), optional
        Mode shapes at the critical speeds (exact analysis only).
    dof_map : DofMap, optional
        DOF numbering of ``mode_shapes``.
    excitation : array (n,), optional
        With a spool named (machines of several lines): how strongly that spool's unbalance
        drives each mode, from 0 (not at all) to 1
        (:func:`~rotorsim.analyses.linear.critical_speeds.spool_excitation`).

    Examples
    --------
    >>> cs = CriticalSpeeds(speed=np.array([100.0, 120.0]), frequency=np.array([100.0, 120.0]),
    ...                     mode=np.array([0, 1]), whirl=np.array(["backward", "forward"]),
    ...                     kind=np.array(["lateral", "lateral"]), log_dec=np.full(2, np.nan),
    ...                     harmonic=1.0)
    >>> len(cs), cs.select("forward").speed.tolist(), round(float(cs.rpm[0]), 2)
    (2, [120.0], 954.93)
    """

    speed: FloatArray
    frequency: FloatArray
    mode: IntArray
    whirl: StrArray
    kind: StrArray
    log_dec: FloatArray
    harmonic: float
    mode_shapes: ComplexArray | None = None
    dof_map: DofMap | None = None
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)
    excitation: FloatArray | None = None

    def __len__(self) -> int:
        return int(self.speed.size)

    @property
    def rpm(self) -> FloatArray:
        """Critical speeds in revolutions per minute."""
        return self.speed * 30.0 / np.pi

    def select(self, whirl: str | None = None, kind: str | None = None) -> CriticalSpeeds:
        """Copy keeping only entries of the given whirl direction and/or mode kind."""
        check_whirl_filter(whirl, "CriticalSpeeds.select")
        keep = np.ones(self.speed.size, dtype=bool)
        if whirl is not None:
            keep &= self.whirl == whirl
        if kind is not None:
            keep &= self.kind == kind
        return self.subset(np.flatnonzero(keep))

    def subset(self, index: IntArray) -> CriticalSpeeds:
        """Copy keeping the entries ``index`` (in that order)."""
        index = np.asarray(index, dtype=np.int64)
        shapes = None if self.mode_shapes is None else self.mode_shapes[:, index]
        excitation = None if self.excitation is None else self.excitation[index]
        return CriticalSpeeds(
            speed=self.speed[index], frequency=self.frequency[index], mode=self.mode[index],
            whirl=self.whirl[index], kind=self.kind[index], log_dec=self.log_dec[index],
            harmonic=self.harmonic, mode_shapes=shapes, dof_map=self.dof_map,
            options=self.options, stats=self.stats, status=self.status, summary=self.summary,
            excitation=excitation,
        )


@dataclass(frozen=True, eq=False)
class MapIntersections:
    """Crossings of the real bearings' stiffness curves with the critical-speed curves.

    Each entry is an estimate of a critical speed of the rotor on its actual
    (speed-dependent) bearings.

    Attributes
    ----------
    bearing : int array (n,)
        Index of the bearing in ``rotor.bearing_elements``.
    coefficient : str array (n,)
        ``"kxx"`` or ``"kyy"``: which stiffness curve crossed.
    mode : int array (n,)
        Column of ``CriticalSpeedMapResult.critical_speeds`` that was crossed.
    stiffness : array (n,)
        Bearing stiffness at the crossing [N/m].
    speed : array (n,)
        Spin speed at the crossing [rad/s].
    """

    bearing: IntArray
    coefficient: StrArray
    mode: IntArray
    stiffness: FloatArray
    speed: FloatArray

    def __len__(self) -> int:
        return int(self.speed.size)

    @classmethod
    def empty(cls) -> MapIntersections:
        """A record with no intersections."""
        return cls.from_rows([])

    @classmethod
    def from_rows(cls, rows: list[tuple[int, str, int, float, float]]) -> MapIntersections:
        """Record from ``(bearing, coefficient, mode, stiffness, speed)`` tuples, sorted by
        speed."""
        rows = sorted(rows, key=lambda r: r[4])
        columns = list(zip(*rows, strict=True)) if rows else [()] * 5
        return cls(bearing=np.array(columns[0], dtype=np.int64),
                   coefficient=np.array(columns[1], dtype="<U3"),
                   mode=np.array(columns[2], dtype=np.int64),
                   stiffness=np.array(columns[3], dtype=float),
                   speed=np.array(columns[4], dtype=float))


@dataclass(frozen=True, eq=False)
class CriticalSpeedMapResult:
    """Undamped critical speeds as a function of the support stiffness.

    Attributes
    ----------
    stiffness : array (P,)
        Lateral support stiffness ``kxx = kyy`` given to the mapped bearings [N/m].
    critical_speeds : array (P, num_modes)
        Lowest forward undamped critical speeds [rad/s] at each stiffness (natural
        frequencies at zero speed divided by ``harmonic`` when ``gyroscopic`` is off);
        ``NaN`` where fewer modes were found or the point failed.
    harmonic : float
        Excitation order of the critical speeds.
    gyroscopic : bool
        Whether the gyroscopic coupling was included.
    bearings : int array (B,)
        Indices of the bearings whose stiffness was replaced.
    speeds : array (Q,)
        Spin speeds [rad/s] at which the speed-dependent bearing curves are sampled
        (empty when no mapped bearing depends on speed).
    curve_bearings : int array (C,)
        Indices of the speed-dependent mapped bearings whose curves are stored.
    bearing_kxx, bearing_kyy : array (C, Q)
        Their stiffness ``kxx(W)``, ``kyy(W)`` [N/m].
    intersections : MapIntersections
        Where those curves cross the critical-speed curves.
    status : int array (P,)
        :class:`~rotorsim.errors.Status` of every stiffness point.

    Examples
    --------
    >>> res = CriticalSpeedMapResult(
    ...     stiffness=np.array([1e6, 1e7]), critical_speeds=np.array([[100.0], [250.0]]),
    ...     harmonic=1.0, gyroscopic=True, bearings=np.array([0, 1]), speeds=np.zeros(0),
    ...     curve_bearings=np.zeros(0, np.int64), bearing_kxx=np.zeros((0, 0)),
    ...     bearing_kyy=np.zeros((0, 0)), intersections=MapIntersections.empty(),
    ...     status=np.zeros(2, np.int64))
    >>> res.num_modes, res.curve(0).tolist()
    (1, [100.0, 250.0])
    """

    stiffness: FloatArray
    critical_speeds: FloatArray
    harmonic: float
    gyroscopic: bool
    bearings: IntArray
    speeds: FloatArray
    curve_bearings: IntArray
    bearing_kxx: FloatArray
    bearing_kyy: FloatArray
    intersections: MapIntersections
    status: IntArray
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    summary: dict[str, Any] = field(default_factory=dict)

    @property
    def num_modes(self) -> int:
        return int(self.critical_speeds.shape[1])

    def curve(self, mode: int) -> FloatArray:
        """Critical speed of column ``mode`` at every stiffness [rad/s]."""
        if not 0 <= mode < self.num_modes:
            raise ModelError(f"mode {mode} outside 0..{self.num_modes - 1}",
                             "CriticalSpeedMapResult")
        return self.critical_speeds[:, mode]
