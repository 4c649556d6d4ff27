"""The function that runs each analysis type of a model file (used by
:func:`rotorsim.io.analysis_spec.run_analysis`): ``runner(rotor, model, spec, fast,
progress) -> result``, with a last ``restart`` argument (checkpoint keywords) for
transients and periodic branches; analyses are imported when they run."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorsim.elements.base import FloatArray
from rotorsim.io.analysis_spec import FAST_POINTS, Grid
from rotorsim.options import (
    Checkpointing,
    ContinuationOptions,
    Excitation,
    Harmonics,
    Output,
)

if TYPE_CHECKING:
    from rotorsim.io.model_file import Model
    from rotorsim.model.rotor import Rotor


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
                           whirl=spec.whirl)


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
               restart: dict[str, Any]) -> Any:
    from rotorsim.analyses.transient.speed_profile import LinearSpeed
    from rotorsim.analyses.transient.transient import transient

    t_end = spec.t_end / 10.0 if fast else spec.t_end
    speed: Any = spec.speed
    if spec.speed_stop is not None:
        ramp = spec.t_end if spec.ramp_time is None else spec.ramp_time
        speed = LinearSpeed(spec.speed, spec.speed_stop, 0.0, ramp)
    unbalance = model.loads.unbalance if spec.unbalance is None else spec.unbalance
    return transient(rotor, t_end, spec.dt, speed=speed, unbalance=list(unbalance),
                     excitation=_excitation(model), method=spec.method, initial=spec.initial,
                     nodes=spec.nodes, output=Output(every=spec.every, progress=progress),
                     on_failure=spec.on_failure, checkpoint=_checkpointing(restart))


def _excitation(model: Model) -> Excitation:
    """Gravity and point loads of the model file (the unbalance is the analysis')."""
    loads = model.loads
    return Excitation(gravity=loads.gravity, direction=loads.gravity_direction,
                      loads=list(loads.point_loads))


def _checkpointing(restart: dict[str, Any]) -> Checkpointing:
    return Checkpointing(path=restart.get("checkpoint"), every=restart.get("checkpoint_every"),
                         resume=restart.get("resume"))


def _branch_options(spec: Any, fast: bool, progress: bool, restart: dict[str, Any]
                    ) -> dict[str, Any]:
    """Harmonics, continuation, stability, output and checkpoint keywords of a periodic
    branch (``fast``: at most 4 harmonics and 10 points)."""
    return {
        "harmonics": Harmonics(min(spec.harmonics, 4) if fast else spec.harmonics,
                               samples=None if fast else spec.samples),
        "continuation": ContinuationOptions(
            max_points=min(spec.max_points, 10) if fast else spec.max_points,
            max_step=spec.max_step),
        "stability": None if spec.stability == "none" else spec.stability,
        "nodes": spec.nodes, "output": Output(progress=progress),
        "checkpoint": _checkpointing(restart),
    }


def _periodic(rotor: Rotor, model: Model, spec: Any, fast: bool, progress: bool,
              restart: dict[str, Any]) -> Any:
    from rotorsim.analyses.periodic.periodic import periodic

    unbalance = model.loads.unbalance if spec.unbalance is None else spec.unbalance
    return periodic(rotor, start=spec.start, stop=spec.stop, unbalance=list(unbalance),
                    excitation=_excitation(model), varying_compliance=spec.varying_compliance,
                    **_branch_options(spec, fast, progress, restart))


def _periodic_parameter(rotor: Rotor, model: Model, spec: Any, fast: bool,
                        progress: bool, restart: dict[str, Any]) -> Any:
    from rotorsim.analyses.periodic.parameter import periodic_parameter

    vary = spec.vary if spec.vary in ("loads", "forcing") else model.parameter(spec.vary)
    unbalance = model.loads.unbalance if spec.unbalance is None else spec.unbalance
    return periodic_parameter(
        rotor, vary, speed=spec.speed, start=spec.start, stop=spec.stop, name=spec.vary,
        unbalance=list(unbalance), excitation=_excitation(model),
        **_branch_options(spec, fast, progress, restart))


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


RUNNERS: dict[str, Callable[..., Any]] = {
    "modal": _modal, "campbell": _campbell, "critical_speeds": _critical_speeds,
    "critical_speed_map": _critical_speed_map, "unbalance": _unbalance,
    "frequency_response": _frequency_response, "static": _static, "transient": _transient,
    "periodic": _periodic, "periodic_parameter": _periodic_parameter, "sweep": _sweep,
}
