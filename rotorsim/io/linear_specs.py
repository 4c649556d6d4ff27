"""Specs of the analyses that run once on the rotor with its rolling bearings linearised
(:meth:`~rotorsim.io.model.Model.linearized`): modes, Campbell diagram, critical speeds
and their map, unbalance and frequency responses, and the static deflection (the
equilibrium at which the bearings are linearised).

Each spec holds the options of one ``rotorsim`` verb in SI units; the common reporting
options are those of :class:`~rotorsim.io.analysis_spec.AnalysisSpec`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from rotorsim.io.analysis_spec import AnalysisSpec, Grid, Unbalance


@dataclass(frozen=True, kw_only=True)
class ModalSpec(AnalysisSpec):
    """Modes at one speed: :func:`rotorsim.modal`."""

    type: ClassVar[str] = "modal"
    speed: float = 0.0
    num_modes: int = 12


@dataclass(frozen=True, kw_only=True)
class CampbellSpec(AnalysisSpec):
    """Campbell diagram over ``speeds`` [rad/s]: :func:`rotorsim.campbell`; ``harmonics``
    are the excitation orders whose critical speeds are reported."""

    type: ClassVar[str] = "campbell"
    speeds: Grid
    num_modes: int = 12
    harmonics: tuple[float, ...] = (1.0,)


@dataclass(frozen=True, kw_only=True)
class CriticalSpeedsSpec(AnalysisSpec):
    """Exact undamped critical speeds: :func:`rotorsim.critical_speeds`."""

    type: ClassVar[str] = "critical_speeds"
    harmonic: float = 1.0
    num_modes: int = 8
    whirl: str | None = None
    spool: str | None = None


@dataclass(frozen=True, kw_only=True)
class CriticalSpeedMapSpec(AnalysisSpec):
    """Critical speeds against support stiffness [N/m]: :func:`rotorsim.critical_speed_map`.
    ``bearings`` are indices into the rotor's bearings (default all)."""

    type: ClassVar[str] = "critical_speed_map"
    stiffness: Grid = Grid(1e5, 1e10, 30, "log")  # noqa: RUF009  (Grid is frozen)
    num_modes: int = 4
    harmonic: float = 1.0
    bearings: tuple[int, ...] | None = None
    gyroscopic: bool = True
    speeds: Grid | None = None


@dataclass(frozen=True, kw_only=True)
class UnbalanceSpec(AnalysisSpec):
    """Unbalance response over ``speeds`` [rad/s]: :func:`rotorsim.unbalance_response`;
    ``unbalance=None`` uses the model's ``[[loads.unbalance]]``."""

    type: ClassVar[str] = "unbalance"
    speeds: Grid
    unbalance: Unbalance | None = None


@dataclass(frozen=True, kw_only=True)
class FrequencyResponseSpec(AnalysisSpec):
    """Receptances over ``frequencies`` [rad/s]: :func:`rotorsim.frequency_response`;
    ``speed=None`` is synchronous excitation."""

    type: ClassVar[str] = "frequency_response"
    frequencies: Grid
    inputs: tuple[tuple[int, str], ...]
    speed: float | None = None


@dataclass(frozen=True, kw_only=True)
class StaticSpec(AnalysisSpec):
    """Static deflection under the model's gravity and point loads: :func:`rotorsim.static`."""

    type: ClassVar[str] = "static"
    speed: float = 0.0
