"""Pydantic schema of the named analyses of a model file.

Analyses are written as ``[analyses.<name>]`` tables or as an ``[[analyses]]`` array with a
``name`` key (default: the type). Each has a ``type`` (see :data:`TABLES`), the options of
that analysis and the common reporting options of :class:`AnalysisTable`. The keys of the
option groups of a transient or periodic branch (``harmonics``, ``max_points``, ``every``,
``checkpoint_every``, ...) are derived from the groups of :mod:`rotorsim.options`
(:func:`option_fields`), not written again here.
"""

from typing import Annotated, Any, Literal

from pydantic import Field, PlainValidator, create_model, model_validator

from rotorsim.errors import ModelError
from rotorsim.io.analysis_spec import AnalysisSpec, Grid
from rotorsim.io.drive_schema import DriveTable
from rotorsim.io.long_specs import (
    PeriodicParameterSpec,
    PeriodicSpec,
    TransientSpec,
    accuracy_problem,
)
from rotorsim.io.model_schema import UnbalanceTable
from rotorsim.io.schema_types import (
    Density,
    Dof,
    FrequencyGrid,
    Length,
    Located,
    Mass,
    Name,
    NodeIndex,
    PositiveRatio,
    PositiveSpeed,
    PositiveTime,
    Power,
    Speed,
    SpeedGrid,
    StiffnessGrid,
    Table,
    fail,
    fmt,
    format_path,
    show,
    suggest,
    validate_table,
)
from rotorsim.options.flat import flat_key, option_field

NumModes = Annotated[int, Field(ge=1, le=1000)]


def _bearing_refs(value: Any) -> tuple[int | str, ...]:
    """Bearings of a critical-speed map: indices into ``[[bearings]]`` or their tags."""
    if not isinstance(value, list) or not value:
        raise fail(f"expected a non-empty array of bearing indices or tags, got {show(value)}")
    for i, item in enumerate(value):
        ok_int = isinstance(item, int) and not isinstance(item, bool) and item >= 0
        if not (ok_int or (isinstance(item, str) and item)):
            raise fail(f"expected a bearing index (>= 0) or tag, got {show(item)}", f"[{i}]")
    return tuple(value)


def _lateral() -> list[Dof]:
    return ["ux", "uy"]


class AnalysisTable(Table):
    """Options common to every analysis: a name, a description and what to report."""

    type: str
    name: Name | None = None
    description: str = ""
    units: Literal["rpm", "Hz", "rad/s"] = "rpm"
    nodes: list[NodeIndex] | None = None
    dofs: Annotated[list[Dof], Field(min_length=1)] = Field(default_factory=_lateral)


class ModalTable(AnalysisTable):
    type: Literal["modal"]
    speed: Speed = 0.0
    num_modes: NumModes = 12


class CampbellTable(AnalysisTable):
    type: Literal["campbell"]
    speeds: SpeedGrid
    num_modes: NumModes = 12
    harmonics: Annotated[list[PositiveRatio], Field(min_length=1)] = Field(
        default_factory=lambda: [1.0])


class CriticalSpeedsTable(AnalysisTable):
    type: Literal["critical_speeds"]
    harmonic: PositiveRatio = 1.0
    num_modes: NumModes = 8
    whirl: Literal["forward", "backward"] | None = None
    spool: Annotated[str, Field(min_length=1)] | None = None


class CriticalSpeedMapTable(AnalysisTable):
    type: Literal["critical_speed_map"]
    stiffness: StiffnessGrid = Grid(1e5, 1e10, 30, "log")
    num_modes: NumModes = 4
    harmonic: PositiveRatio = 1.0
    bearings: Annotated[Any, PlainValidator(_bearing_refs)] = None
    gyroscopic: bool = True
    speeds: SpeedGrid = None


class UnbalanceAnalysisTable(AnalysisTable):
    type: Literal["unbalance"]
    speeds: SpeedGrid
    unbalance: Annotated[list[UnbalanceTable], Field(min_length=1)] | None = None


class InputTable(Located):
    dof: Dof


class FrequencyResponseTable(AnalysisTable):
    type: Literal["frequency_response"]
    frequencies: FrequencyGrid
    inputs: Annotated[list[InputTable], Field(min_length=1)]
    speed: Speed | None = None


class StaticTable(AnalysisTable):
    type: Literal["static"]
    speed: Speed = 0.0


class RestartableTable(AnalysisTable):
    """Checkpoint and resume of a long analysis (transient, periodic branch): ``checkpoint``
    writes ``<analysis>.checkpoint.h5`` beside the results every ``checkpoint_every``
    steps or points; ``resume`` continues from it when it exists. ``checkpoint_every`` and
    the other option keys come from the option groups of the spec (:func:`option_fields`)."""

    checkpoint: bool = False
    resume: bool = False


def option_fields(spec: type[AnalysisSpec]) -> dict[str, Any]:
    """Pydantic fields ``{flat key: (annotation, default)}`` of the option-group keys of a
    model-file analysis (``harmonics``, ``max_points``, ``checkpoint_every``, ...): the
    fields ``spec.FILE_OPTIONS`` names, with their type, bounds and default from the
    group's field metadata (:mod:`rotorsim.options.flat`). A default of None (the verb's
    default) makes the key optional."""
    groups = spec.option_groups()
    out: dict[str, Any] = {}
    for attr, names in spec.FILE_OPTIONS.items():
        for name in names:
            f = option_field(groups[attr], name)
            out[flat_key(groups[attr], name)] = _option_annotation(f.metadata, f.default)
    return out


def _option_annotation(meta: Any, default: Any) -> tuple[Any, Any]:
    kind, bounds = meta["file"], {k: meta[k] for k in ("ge", "gt", "le") if k in meta}
    annotation: Any
    if kind is list:  # a list of names among the choices
        annotation = list[Literal[meta["choices"]]]  # type: ignore[valid-type]
    elif "choices" in meta:
        annotation = Literal[(*meta["choices"], *([meta["none"]] if "none" in meta else []))]
    else:
        annotation = Annotated[kind, Field(**bounds)] if bounds else kind
    return (annotation | None, None) if default is None else (annotation, default)


class _TransientKeys(RestartableTable):
    type: Literal["transient"]
    t_end: PositiveTime
    dt: PositiveTime | None = None
    rtol: PositiveRatio | None = None  # the accuracy relative to the motion
    speed: Speed = 0.0
    speed_stop: Speed | None = None
    ramp_time: PositiveTime | None = None
    method: Literal["average_acceleration", "newmark", "linear_acceleration", "hht",
                    "generalized_alpha", "adams", "adaptive", "auto"] | None = None
    initial: Literal["static", "zero"] = "static"
    on_failure: Literal["stop", "raise"] = "stop"
    unbalance: Annotated[list[UnbalanceTable], Field(min_length=1)] | None = None
    drive: DriveTable | None = None
    stop_when_steady: bool = False

    @model_validator(mode="after")
    def _step_within_run(self) -> "_TransientKeys":
        if self.dt is not None and self.dt > self.t_end:
            raise fail(f"{fmt(self.dt, 'time')} exceeds t_end ({fmt(self.t_end, 'time')}): "
                       "check the units", ".dt")
        problem = accuracy_problem(self.dt, self.rtol, self.method)
        if problem is not None:
            raise fail(problem[0], f".{problem[1]}")
        if self.drive is not None and (self.speed_stop, self.ramp_time) != (None, None):
            raise fail("a drive sets the speed from torques: give no speed_stop or "
                       "ramp_time (speed is the initial speed)", ".drive")
        return self


TransientTable = create_model(
    "TransientTable", __base__=_TransientKeys, __module__=__name__,
    __doc__="A run at constant speed (``speed``), a linear run-up/coast-down from "
            "``speed`` to ``speed_stop`` over ``ramp_time`` (default the whole run), or a "
            "speed driven by the torques of a ``drive`` table from the initial ``speed``.",
    **option_fields(TransientSpec))


class _PeriodicKeys(RestartableTable):
    type: Literal["periodic"]
    start: Speed
    stop: Speed
    varying_compliance: bool | None = None
    unbalance: Annotated[list[UnbalanceTable], Field(min_length=1)] | None = None


PeriodicTable = create_model(
    "PeriodicTable", __base__=_PeriodicKeys, __module__=__name__,
    __doc__="A harmonic-balance branch over the speed range ``start`` .. ``stop``.",
    **option_fields(PeriodicSpec))


class _PeriodicParameterKeys(RestartableTable):
    type: Literal["periodic_parameter"]
    vary: Annotated[str, Field(min_length=1)]
    speed: PositiveSpeed
    start: float | str
    stop: float | str
    unbalance: Annotated[list[UnbalanceTable], Field(min_length=1)] | None = None


PeriodicParameterTable = create_model(
    "PeriodicParameterTable", __base__=_PeriodicParameterKeys, __module__=__name__,
    __doc__="A harmonic-balance branch at the fixed ``speed`` over a model parameter "
            "``vary``: a key path of the model file "
            "(``\"rolling_bearings.DE.radial_clearance\"``), ``\"loads\"`` (a factor on the "
            "point loads) or ``\"forcing\"`` (a factor on the unbalance), from ``start`` to "
            "``stop`` (numbers in SI, or strings with units).",
    **option_fields(PeriodicParameterSpec))


class SweepTable(AnalysisTable):
    """A parameter study (``rs.sweep``): the lateral support stiffness of ``bearings``
    (default all) over ``stiffness`` times the spin speeds ``speeds``, evaluating the least
    log decrement or the critical speeds at every point. Points are written to the results
    file as they finish; ``resume`` continues an interrupted study from it."""

    type: Literal["sweep"]
    stiffness: StiffnessGrid
    speeds: SpeedGrid = None
    bearings: Annotated[Any, PlainValidator(_bearing_refs)] = None
    evaluate: Literal["min_log_dec", "critical_speeds"] = "min_log_dec"
    num_modes: NumModes = 6
    resume: bool = False


class StageTable(Located):
    """Machine data of one stage for the anticipated cross-coupling Q_A."""

    power: Power
    diameter: Length
    flow_height: Length
    density_ratio: PositiveRatio = 1.0
    tag: str | None = None


class ApiStabilityTable(AnalysisTable):
    """API 617 Level I stability at the maximum continuous speed (``rs.api_level1``)."""

    type: Literal["api_stability"]
    mcs: PositiveSpeed
    stages: Annotated[list[StageTable], Field(min_length=1)]
    machine: Literal["compressor", "turbine"] = "compressor"
    apply_at: Literal["midspan", "stages"] = "midspan"
    average_density: Density | None = None
    q_max: Annotated[float, Field(gt=0)] | None = None
    num: Annotated[int, Field(ge=2, le=1000)] = 11
    num_modes: NumModes = 8


class ClearanceTable(Located):
    clearance: Length
    tag: str | None = None


class ApiUnbalanceTable(AnalysisTable):
    """API 617 unbalance response analysis (``rs.api_unbalance``)."""

    type: Literal["api_unbalance"]
    speeds: SpeedGrid
    min_speed: PositiveSpeed
    mcs: PositiveSpeed
    num_modes: NumModes = 3
    clearances: list[ClearanceTable] = Field(default_factory=list)
    probes: list[NodeIndex] | None = None
    plane_mass: Mass | None = None
    factor: PositiveRatio = 1.0
    spool: str | None = None


TABLES: dict[str, type[AnalysisTable]] = {
    "modal": ModalTable,
    "campbell": CampbellTable,
    "critical_speeds": CriticalSpeedsTable,
    "critical_speed_map": CriticalSpeedMapTable,
    "unbalance": UnbalanceAnalysisTable,
    "frequency_response": FrequencyResponseTable,
    "static": StaticTable,
    "transient": TransientTable,
    "periodic": PeriodicTable,
    "periodic_parameter": PeriodicParameterTable,
    "sweep": SweepTable,
    "api_stability": ApiStabilityTable,
    "api_unbalance": ApiUnbalanceTable,
}
"""Analysis types of model files and their tables."""


def validate_analyses(raw: Any) -> list[tuple[str, tuple[str | int, ...], AnalysisTable]]:
    """Validate the ``analyses`` section.

    Parameters
    ----------
    raw : dict, list or None
        ``{name: table}`` (from ``[analyses.<name>]``) or a list of tables with ``name``.

    Returns
    -------
    list of (name, key path, table)

    Raises
    ------
    ModelError
        Naming the key path of the first problem.
    """
    if raw is None:
        return []
    if isinstance(raw, dict):
        items: list[tuple[str | None, tuple[str | int, ...], Any]] = [
            (str(key), ("analyses", str(key)), body) for key, body in raw.items()]
    elif isinstance(raw, list):
        items = [(None, ("analyses", i), body) for i, body in enumerate(raw)]
    else:
        raise ModelError("expected named tables [analyses.<name>] or an array [[analyses]], "
                         f"got {show(raw)}", "analyses")
    out: list[tuple[str, tuple[str | int, ...], AnalysisTable]] = []
    for key, loc, body in items:
        table = _validate_one(body, loc)
        name = key if key is not None else (table.name or table.type)
        if key is not None and table.name is not None and table.name != key:
            raise ModelError(f"must match the table key '{key}', got {show(table.name)}",
                             format_path((*loc, "name")))
        if any(name == other for other, _, _ in out):
            raise ModelError(f"duplicate analysis name '{name}'", format_path((*loc, "name")))
        out.append((name, loc, table))
    return out


def _validate_one(body: Any, loc: tuple[str | int, ...]) -> AnalysisTable:
    where = format_path(loc)
    if not isinstance(body, dict):
        raise ModelError(f"expected a table, got {show(body)}", where)
    kind = body.get("type")
    if kind is None:
        raise ModelError(f"field required (one of {', '.join(TABLES)})", f"{where}.type")
    if not isinstance(kind, str) or kind not in TABLES:
        hint = suggest(kind, tuple(TABLES)) if isinstance(kind, str) else ""
        raise ModelError(f"unknown analysis type {show(kind)}{hint}; use one of "
                         f"{', '.join(TABLES)}", f"{where}.type")
    return validate_table(TABLES[kind], body, loc)
