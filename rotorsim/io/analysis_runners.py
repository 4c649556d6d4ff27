"""Run the analyses of a loaded model: :func:`run_analysis` and the function that runs
each analysis spec type (:data:`RUNNERS`).

A runner is ``runner(rotor, model, spec, fast, progress) -> result``, with a last
``restart`` argument (checkpoint keywords) for transients and periodic branches; analyses
are imported when they run, so importing this module stays light.
"""

from __future__ import annotations

import dataclasses
import functools
import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError
from rotorsim.io.analysis_spec import AnalysisSpec, Grid
from rotorsim.io.api_specs import ApiStabilitySpec, ApiUnbalanceSpec
from rotorsim.io.linear_specs import (
    CampbellSpec,
    CriticalSpeedMapSpec,
    CriticalSpeedsSpec,
    FrequencyResponseSpec,
    ModalSpec,
    StaticSpec,
    UnbalanceSpec,
)
from rotorsim.io.long_specs import (
    PeriodicParameterSpec,
    PeriodicSpec,
    RestartableSpec,
    SweepSpec,
    TransientSpec,
)
from rotorsim.io.restart import checkpoint_path, restart_options
from rotorsim.options import Checkpointing, Excitation, Harmonics, Output

if TYPE_CHECKING:
    from rotorsim.io.model import Model
    from rotorsim.model.rotor import Rotor

FAST_POINTS = 7
"""Grid size used by ``run_analysis(..., fast=True)``."""


def _grid(grid: Grid, fast: bool) -> FloatArray:
    return (grid.shrunk(FAST_POINTS) if fast else grid).array()


def _modal(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool) -> Any:
    from rotorsim.analyses.linear.modal import modal

    return modal(rotor, speed=spec.speed, num_modes=spec.num_modes)


def _campbell(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool) -> Any:
    from rotorsim.analyses.linear.campbell import campbell

    return campbell(rotor, _grid(spec.speeds, fast), num_modes=spec.num_modes,
                    progress=progress)


def _critical_speeds(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool) -> Any:
    from rotorsim.analyses.linear.critical_speeds import critical_speeds

    return critical_speeds(rotor, harmonic=spec.harmonic, num_modes=spec.num_modes,
                           whirl=spec.whirl, spool=spec.spool)


def _critical_speed_map(rotor: Rotor, model: Model, spec: Any, fast: bool,
                        progress: bool) -> Any:
    from rotorsim.analyses.linear.critical_speed_map import critical_speed_map

    speeds = None if spec.speeds is None else _grid(spec.speeds, fast)
    return critical_speed_map(rotor, stiffness=_grid(spec.stiffness, fast),
                              num_modes=spec.num_modes, harmonic=spec.harmonic,
                              bearings=spec.bearings, gyroscopic=spec.gyroscopic,
                              speeds=speeds)


def _unbalance(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool) -> Any:
    from rotorsim.analyses.linear.frequency_response import unbalance_response

    unbalance = model.loads.unbalance if spec.unbalance is None else spec.unbalance
    return unbalance_response(rotor, _grid(spec.speeds, fast), list(unbalance),
                              progress=progress)


def _frequency_response(rotor: Rotor, model: Model, spec: Any, fast: bool,
                        progress: bool) -> Any:
    from rotorsim.analyses.linear.frequency_response import frequency_response

    return frequency_response(rotor, _grid(spec.frequencies, fast), list(spec.inputs),
                              speed=spec.speed, progress=progress)


def _static(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool) -> Any:
    from rotorsim.analyses.statics.static import static

    loads = model.loads
    return static(rotor, gravity=loads.gravity, direction=loads.gravity_direction,
                  loads=list(loads.point_loads), speed=spec.speed)


def _transient(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool,
               restart: Checkpointing) -> Any:
    from rotorsim.analyses.transient.speed_profile import LinearSpeed
    from rotorsim.analyses.transient.transient import transient

    t_end = spec.t_end / 10.0 if fast else spec.t_end
    speed: Any = spec.speed
    if spec.drive is not None:
        from rotorsim.io.drive_build import torque_drive

        speed = torque_drive(spec.drive, spec.speed)
    elif spec.speed_stop is not None:
        ramp = spec.t_end if spec.ramp_time is None else spec.ramp_time
        speed = LinearSpeed(spec.speed, spec.speed_stop, 0.0, ramp)
    unbalance = model.loads.unbalance if spec.unbalance is None else spec.unbalance
    steady = None
    if spec.stop_when_steady:
        steady = spec.steady if spec.steady.nodes or spec.nodes is None else \
            dataclasses.replace(spec.steady, nodes=spec.nodes)
    return transient(rotor, t_end, spec.dt, speed=speed, unbalance=list(unbalance),
                     excitation=_excitation(model), method=spec.method, rtol=spec.rtol,
                     initial=spec.initial,
                     nodes=spec.nodes,
                     output=dataclasses.replace(spec.output, progress=progress),
                     on_failure=spec.on_failure, checkpoint=restart, steady=steady)


def _excitation(model: Model) -> Excitation:
    """Gravity and point loads of the model file (the unbalance is the analysis')."""
    loads = model.loads
    return Excitation(gravity=loads.gravity, direction=loads.gravity_direction,
                      loads=list(loads.point_loads))


def _branch_options(spec: Any, defaults: Any, fast: bool, progress: bool,
                    restart: Checkpointing) -> dict[str, Any]:
    """The option groups of a periodic branch from its spec (``fast``: at most 4 harmonics,
    the default samples and 10 points; ``defaults``: the verb's)."""
    harmonics, continuation = spec.harmonics, spec.continuation
    if fast:
        harmonics = Harmonics(min(harmonics.count, 4))
        points = continuation.resolved(defaults.continuation).max_points
        continuation = dataclasses.replace(continuation, max_points=min(points, 10))
    return {"harmonics": harmonics, "continuation": continuation,
            "stability": spec.stability, "nodes": spec.nodes,
            "output": Output(progress=progress), "checkpoint": restart}


def _periodic(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool,
              restart: Checkpointing) -> Any:
    from rotorsim.analyses.periodic.periodic import DEFAULTS, periodic

    unbalance = model.loads.unbalance if spec.unbalance is None else spec.unbalance
    return periodic(rotor, start=spec.start, stop=spec.stop, unbalance=list(unbalance),
                    excitation=_excitation(model), varying_compliance=spec.varying_compliance,
                    **_branch_options(spec, DEFAULTS, fast, progress, restart))


def _periodic_parameter(rotor: Rotor, model: Model, spec: Any, fast: bool,
                        progress: bool, restart: Checkpointing) -> Any:
    from rotorsim.analyses.periodic.parameter import DEFAULTS, periodic_parameter

    vary = spec.vary if spec.vary in ("loads", "forcing") else model.parameter(spec.vary)
    unbalance = model.loads.unbalance if spec.unbalance is None else spec.unbalance
    return periodic_parameter(
        rotor, vary, speed=spec.speed, start=spec.start, stop=spec.stop, name=spec.vary,
        unbalance=list(unbalance), excitation=_excitation(model),
        **_branch_options(spec, DEFAULTS, fast, progress, restart))


def _sweep(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool, *,
           store: Path | None) -> Any:
    from rotorsim.analyses.sweep.functions import (
        critical_speeds_eval,
        min_log_dec,
        set_bearing_stiffness,
    )
    from rotorsim.analyses.sweep.sweep import Grid as SweepGrid
    from rotorsim.analyses.sweep.sweep import sweep

    speeds = np.zeros(1) if spec.speeds is None else _grid(spec.speeds, fast)
    space = SweepGrid({"bearing_k": _grid(spec.stiffness, fast), "speed": speeds})
    bearings = list(range(len(rotor.bearing_elements))) if spec.bearings is None else list(
        spec.bearings)
    evaluate = (min_log_dec("speed", spec.num_modes) if spec.evaluate == "min_log_dec"
                else critical_speeds_eval(num_modes=spec.num_modes))
    return sweep(rotor, space, set_bearing_stiffness(bearings), evaluate, store=store,
                 resume=spec.resume, progress=progress)


def _api_stability(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool) -> Any:
    from rotorsim.analyses.standards.api_stability import ApiStage, api_level1

    stages = [ApiStage(s.node, s.power, s.diameter, s.flow_height, s.density_ratio, s.tag)
              for s in spec.stages]
    return api_level1(rotor, spec.mcs, stages, machine=spec.machine, apply_at=spec.apply_at,
                      density=spec.average_density, q_max=spec.q_max,
                      num=min(spec.num, FAST_POINTS) if fast else spec.num,
                      num_modes=spec.num_modes)


API_FAST_POINTS = 60
"""Speeds of an ``api_unbalance`` analysis with ``fast=True`` (a half-power band needs
more than :data:`FAST_POINTS`)."""


def _api_unbalance(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool) -> Any:
    from rotorsim.analyses.standards.api_unbalance import Clearance, api_unbalance

    speeds = (spec.speeds.shrunk(API_FAST_POINTS) if fast else spec.speeds).array()
    return api_unbalance(rotor, speeds, min_speed=spec.min_speed, mcs=spec.mcs,
                         num_modes=spec.num_modes, probes=spec.probes,
                         clearances=[Clearance(c.node, c.clearance, c.tag or "")
                                     for c in spec.clearances],
                         plane_mass=spec.plane_mass, factor=spec.factor, spool=spec.spool)


RUNNERS: dict[type[AnalysisSpec], Callable[..., Any]] = {
    ModalSpec: _modal, CampbellSpec: _campbell, CriticalSpeedsSpec: _critical_speeds,
    CriticalSpeedMapSpec: _critical_speed_map, UnbalanceSpec: _unbalance,
    FrequencyResponseSpec: _frequency_response, StaticSpec: _static,
    TransientSpec: _transient, PeriodicSpec: _periodic,
    PeriodicParameterSpec: _periodic_parameter, SweepSpec: _sweep,
    ApiStabilitySpec: _api_stability, ApiUnbalanceSpec: _api_unbalance,
}
"""The runner of each analysis spec type."""


def runner_for(spec: AnalysisSpec) -> Callable[..., Any]:
    """The runner of ``spec`` (of its class or the nearest base class in :data:`RUNNERS`).

    Raises
    ------
    TypeError
        ``spec`` is of no known analysis spec type.
    """
    for cls in type(spec).__mro__:
        if cls in RUNNERS:
            return RUNNERS[cls]
    raise TypeError(f"no runner for {type(spec).__name__}; the spec types are "
                    f"{', '.join(cls.__name__ for cls in RUNNERS)}")


def run_analysis(model: Model, name: str, *, fast: bool = False, progress: bool = False,
                 checkpoint_dir: str | os.PathLike[str] | None = None) -> Any:
    """Run the analysis ``name`` of a loaded model.

    Parameters
    ----------
    model : Model
        From :func:`rotorsim.io.model_file.load_model`.
    name : str
        Key of the analysis in ``model.analyses``.
    fast : bool
        Shrink every grid to at most :data:`FAST_POINTS` points, a transient to a tenth of
        its duration and a periodic branch to 10 points with at most 4 harmonics (tests,
        smoke runs).
    progress : bool
        Show progress bars on sweeps that support them.
    checkpoint_dir : path, optional
        Folder of the checkpoint file ``<name>.checkpoint.h5`` of an analysis with
        ``checkpoint`` or ``resume`` set (default ``results/<model name>``, where the
        command line writes its results), and of the store ``<name>.h5`` a ``sweep``
        writes point by point (kept in memory when neither ``checkpoint_dir`` nor
        ``resume`` is given).

    Returns
    -------
    result
        The analysis result (``ModalResult``, ``CampbellResult``, ``CriticalSpeeds``,
        ``CriticalSpeedMapResult``, ``FrequencyResponseResult``, ``StaticResult``,
        ``TransientResult`` or ``PeriodicResult``).

    Raises
    ------
    ModelError
        ``name`` is not an analysis of the model.

    Notes
    -----
    A model with rolling bearings is analysed on :meth:`Model.linearized` (the bearings
    linearised at their static loads, computed once per model and speed: the spec's
    ``speed`` for ``modal`` and ``static``, else 0); the result's ``options`` then hold
    ``rolling_bearings`` (tags, loads, iterations). A ``static`` analysis returns that
    nonlinear static equilibrium; a ``transient`` uses the full nonlinear bearings.
    """
    if name not in model.analyses:
        raise ModelError(f"no analysis {name!r}; the model has {sorted(model.analyses)}",
                         model.name)
    spec = model.analyses[name]
    runner = runner_for(spec)
    folder = Path("results") / model.name if checkpoint_dir is None else Path(checkpoint_dir)
    if isinstance(spec, RestartableSpec):
        return runner(model.rotor.with_nonlinear(model.rolling_bearings), model, spec, fast,
                      progress, restart_options(spec, checkpoint_path(folder, name)))
    if isinstance(spec, SweepSpec):  # its store is the results file (in memory unless asked)
        on_disk = checkpoint_dir is not None or spec.resume
        runner = functools.partial(runner, store=folder / f"{name}.h5" if on_disk else None)
    if not model.rolling_bearings:
        return runner(model.rotor, model, spec, fast, progress)
    linear = model.linearized(float(getattr(spec, "speed", None) or 0.0)
                              if spec.type in ("modal", "static") else 0.0)
    result = linear.static if spec.type == "static" else runner(linear.rotor, model, spec,
                                                                  fast, progress)
    return dataclasses.replace(result, options={**result.options,
                                                "rolling_bearings": linear.describe()})
