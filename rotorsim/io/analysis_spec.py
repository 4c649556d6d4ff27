"""Typed analysis specifications read from model files.

A model file names analyses (``[analyses.campbell]`` with ``type = "campbell"``); the
loader turns each into one of the frozen specs below, in SI units with node numbers
resolved. :func:`~rotorsim.io.analysis_runners.run_analysis` maps a spec onto the
matching ``rotorsim`` call.

Examples
--------
>>> grid = Grid(start=0.0, stop=100.0, num=5)
>>> grid.array().tolist()
[0.0, 25.0, 50.0, 75.0, 100.0]
>>> grid.shrunk(3).num
3
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any, ClassVar, Literal

import numpy as np

from rotorsim.assembly.loads import STANDARD_GRAVITY
from rotorsim.elements.base import FloatArray


@dataclass(frozen=True)
class Grid:
    """Values of a swept quantity in SI: a range ``start..stop`` with ``num`` points, or
    explicit ``values``.

    Parameters
    ----------
    start, stop : float
        Ends of the range (SI).
    num : int
        Number of points (>= 1).
    spacing : {"linear", "log"}
        Linear or logarithmic spacing of the range.
    values : tuple of float, optional
        Explicit values; when given, the range fields are ignored.
    """

    start: float = 0.0
    stop: float = 0.0
    num: int = 1
    spacing: Literal["linear", "log"] = "linear"
    values: tuple[float, ...] | None = None

    def array(self) -> FloatArray:
        """The values as a float array."""
        if self.values is not None:
            return np.array(self.values, dtype=float)
        if self.spacing == "log":
            return np.geomspace(self.start, self.stop, self.num)
        return np.linspace(self.start, self.stop, self.num)

    def shrunk(self, num: int) -> Grid:
        """Copy with at most ``num`` points spanning the same range."""
        if self.values is not None:
            if len(self.values) <= num:
                return self
            index = np.unique(np.linspace(0, len(self.values) - 1, num).round().astype(int))
            return Grid(values=tuple(self.values[i] for i in index))
        return Grid(self.start, self.stop, min(self.num, num), self.spacing)

    def to_toml(self) -> dict[str, Any] | list[float]:
        """Model-file form: a table ``{start, stop, num, spacing}`` or a list of values."""
        if self.values is not None:
            return list(self.values)
        return {"start": self.start, "stop": self.stop, "num": self.num,
                "spacing": self.spacing}


Unbalance = tuple[tuple[int, float, float], ...]
"""``(node, magnitude [kg m], phase [rad])`` of each unbalance."""


@dataclass(frozen=True)
class Loads:
    """Loads of a model file.

    Parameters
    ----------
    gravity : float or None
        Acceleration of gravity [m/s^2]; ``None`` switches it off.
    gravity_direction : (3,) tuple
        Direction in which gravity acts (x, y, z).
    unbalance : tuple of (node, magnitude, phase)
        Unbalance distribution [kg m, rad].
    point_loads : tuple of (node, dof, value)
        Static forces [N] and moments [N m].
    """

    gravity: float | None = STANDARD_GRAVITY
    gravity_direction: tuple[float, float, float] = (0.0, -1.0, 0.0)
    unbalance: Unbalance = ()
    point_loads: tuple[tuple[int, str, float], ...] = ()


@dataclass(frozen=True, kw_only=True)
class AnalysisSpec:
    """Options shared by all analyses: a description and what to report.

    Parameters
    ----------
    description : str
        Free text.
    units : {"rpm", "Hz", "rad/s"}
        Unit of speeds and frequencies in printed summaries and figures.
    nodes : tuple of int, optional
        Nodes to report (responses, orbits); default chosen by the reporter.
    dofs : tuple of str
        DOFs to report at those nodes.
    """

    type: ClassVar[str] = ""
    description: str = ""
    units: str = "rpm"
    nodes: tuple[int, ...] | None = None
    dofs: tuple[str, ...] = ("ux", "uy")

    def to_toml(self) -> dict[str, Any]:
        """Model-file form in SI numbers (``None`` entries left out)."""
        out: dict[str, Any] = {"type": self.type}
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None or (f.name == "description" and not value):
                continue
            out[f.name] = _toml_value(f.name, value)
        return out


def _toml_value(name: str, value: Any) -> Any:
    if isinstance(value, Grid):
        return value.to_toml()
    if name == "unbalance":
        return [{"node": n, "magnitude": me, "phase": a} for n, me, a in value]
    if name == "inputs":
        return [{"node": n, "dof": dof} for n, dof in value]
    return list(value) if isinstance(value, tuple) else value


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


@dataclass(frozen=True, kw_only=True)
class CriticalSpeedMapSpec(AnalysisSpec):
    """Critical speeds against support stiffness [N/m]: :func:`rotorsim.critical_speed_map`.
    ``bearings`` are indices into the rotor's bearings (default all)."""

    type: ClassVar[str] = "critical_speed_map"
    stiffness: Grid = Grid(1e5, 1e10, 30, "log")
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


@dataclass(frozen=True, kw_only=True)
class RestartableSpec(AnalysisSpec):
    """Checkpoint options of a long analysis (a transient or a periodic branch).

    Parameters
    ----------
    checkpoint : bool
        Write a checkpoint file (``<out>/<model>/<analysis>.checkpoint.h5`` on the command
        line) every ``checkpoint_every`` steps or branch points and at the end.
    checkpoint_every : int, optional
        Steps (transient, default 1000) or branch points (periodic, default 25) between
        checkpoints.
    resume : bool
        Continue from that checkpoint when it exists (same model and options, else a
        :class:`~rotorsim.time_integration.checkpoint.CheckpointError`); the result equals
        that of an uninterrupted run.
    """

    checkpoint: bool = False
    checkpoint_every: int | None = None
    resume: bool = False


@dataclass(frozen=True, kw_only=True)
class TransientSpec(RestartableSpec):
    """Time integration: :func:`rotorsim.transient` over ``t_end`` [s] with step ``dt`` [s]
    at constant ``speed`` [rad/s], or a linear ramp to ``speed_stop`` over ``ramp_time``
    [s] (default ``t_end``); ``unbalance=None`` uses the model's ``[[loads.unbalance]]``;
    rolling bearings act with their full nonlinear force. ``on_failure="stop"`` (default)
    keeps the run up to a failed step with status ``NOT_CONVERGED``; ``"raise"`` raises."""

    type: ClassVar[str] = "transient"
    t_end: float
    dt: float
    speed: float = 0.0
    speed_stop: float | None = None
    ramp_time: float | None = None
    method: str = "average_acceleration"
    every: int = 1
    initial: str = "static"
    on_failure: str = "stop"
    unbalance: Unbalance | None = None


@dataclass(frozen=True, kw_only=True)
class PeriodicSpec(RestartableSpec):
    """Harmonic-balance branch over the speed range ``start`` .. ``stop`` [rad/s]:
    :func:`rotorsim.periodic` with ``harmonics`` harmonics, Floquet stability
    (``stability="none"`` skips it) and bifurcations; ``unbalance=None`` uses the model's
    ``[[loads.unbalance]]``; rolling bearings act with their full nonlinear force."""

    type: ClassVar[str] = "periodic"
    start: float
    stop: float
    harmonics: int = 10
    samples: int | None = None
    max_points: int = 500
    max_step: float = 0.02
    varying_compliance: bool | None = None
    stability: str = "auto"
    unbalance: Unbalance | None = None


@dataclass(frozen=True, kw_only=True)
class PeriodicParameterSpec(RestartableSpec):
    """Harmonic-balance branch at the fixed ``speed`` [rad/s] over the model parameter
    ``vary`` from ``start`` to ``stop`` (SI): :func:`rotorsim.periodic_parameter` with
    ``vary`` a key path of the model file
    (:class:`~rotorsim.io.model_parameter.ModelParameter`), ``"loads"`` (a factor on the
    model's point loads) or ``"forcing"`` (a factor on the unbalance)."""

    type: ClassVar[str] = "periodic_parameter"
    vary: str
    speed: float
    start: float
    stop: float
    harmonics: int = 10
    samples: int | None = None
    max_points: int = 200
    max_step: float = 0.05
    stability: str = "auto"
    unbalance: Unbalance | None = None


@dataclass(frozen=True, kw_only=True)
class SweepSpec(AnalysisSpec):
    """Parameter study :func:`rotorsim.sweep`: support stiffness [N/m] of ``bearings``
    (indices, default all) over ``stiffness`` times spin speeds [rad/s] over ``speeds``
    (default 0), evaluating ``"min_log_dec"`` or ``"critical_speeds"`` with ``num_modes``.
    Points go to the results file as they finish (the file is the checkpoint); ``resume``
    continues from it."""

    type: ClassVar[str] = "sweep"
    stiffness: Grid
    speeds: Grid | None = None
    bearings: tuple[int, ...] | None = None
    evaluate: str = "min_log_dec"
    num_modes: int = 6
    resume: bool = False


SPEC_TYPES: dict[str, type[AnalysisSpec]] = {
    cls.type: cls for cls in (ModalSpec, CampbellSpec, CriticalSpeedsSpec,
                              CriticalSpeedMapSpec, UnbalanceSpec, FrequencyResponseSpec,
                              StaticSpec, TransientSpec, PeriodicSpec, PeriodicParameterSpec,
                              SweepSpec)
}
"""Analysis ``type`` names of model files and their spec classes."""
