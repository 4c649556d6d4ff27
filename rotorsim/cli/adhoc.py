"""The analysis a subcommand such as ``rotorsim modal`` runs: the model's first analysis of
that type (or a default one) with the command-line overrides applied."""

from __future__ import annotations

import argparse
from typing import Any

from rotorsim.cli.parser import BRANCH_OPTIONS, SUBCOMMAND_TYPES, option_dest


def adhoc_job(model: Any, args: argparse.Namespace) -> tuple[str, Any]:
    """The model's first analysis of the subcommand's type (or a default one) with the
    command-line overrides applied."""
    from rotorsim.io.analysis_spec import Grid
    from rotorsim.io.spec_registry import SPEC_TYPES
    from rotorsim.units import to_si

    kind = SUBCOMMAND_TYPES[args.command]
    name, spec = next(((n, s) for n, s in model.analyses.items() if s.type == kind),
                      (kind, None))
    cls = SPEC_TYPES[kind]
    changes: dict[str, Any] = {}
    if getattr(args, "num_modes", None) is not None:
        changes["num_modes"] = args.num_modes
    for group, field in BRANCH_OPTIONS:
        option = option_dest(group, field)
        if getattr(args, option, None) is not None:
            changes[option] = _count(str(getattr(args, option)))
    if getattr(args, "no_stability", False):
        changes["stability"] = "none"
    if kind == "transient":
        changes.update(_run_control_changes(args))
        changes.update(_step_changes(spec, args))
    if getattr(args, "speed", None) is not None:
        changes["speed"] = to_si(args.speed, "speed", "--speed")
    ranges = () if kind == "periodic_parameter" else (("start", "start", "speed"),
                                                      ("stop", "stop", "speed"))
    for option, key, kind_of in (("t_end", "t_end", "time"), ("dt", "dt", "time"),
                                 ("speed_stop", "speed_stop", "speed"), *ranges):
        if getattr(args, option, None) is not None:
            changes[key] = to_si(getattr(args, option), kind_of,
                                 f"--{option.replace('_', '-')}")
    if getattr(args, "speeds", None) is not None:
        start, stop, num = args.speeds
        changes["speeds"] = Grid(to_si(start, "speed", "--speeds START"),
                                 to_si(stop, "speed", "--speeds STOP"), _count(num))
    if getattr(args, "stiffness", None) is not None:
        kmin, kmax, num = args.stiffness
        changes["stiffness"] = Grid(to_si(kmin, "stiffness", "--stiffness KMIN"),
                                    to_si(kmax, "stiffness", "--stiffness KMAX"),
                                    _count(num), "log")
    if spec is None:
        if kind in ("campbell", "unbalance") and "speeds" not in changes:
            from rotorsim.errors import ModelError

            raise ModelError("the model has no such analysis; give --speeds START STOP NUM",
                             args.command)
        if kind == "transient" and ("t_end" not in changes or (
                changes.get("dt") is None and changes.get("rtol") is None)):
            from rotorsim.errors import ModelError

            raise ModelError("the model has no transient analysis; give --t-end and --dt "
                             "(or --rtol)", args.command)
        if kind == "periodic" and not {"start", "stop"} <= set(changes):
            from rotorsim.errors import ModelError

            raise ModelError("the model has no periodic analysis; give --start and --stop",
                             args.command)
    if kind == "periodic_parameter":
        changes.update(_parameter_changes(model, spec, args))
    spec = cls.from_flat(**changes) if spec is None else spec.with_flat(**changes)
    return name, spec


def _parameter_changes(model: Any, spec: Any, args: argparse.Namespace) -> dict[str, Any]:
    """``vary``, ``start`` and ``stop`` (SI) of ``rotorsim periodic-parameter``."""
    from rotorsim.errors import ModelError
    from rotorsim.io.model_parameter import parameter_range

    given = {k: getattr(args, k) for k in ("vary", "start", "stop")
             if getattr(args, k) is not None}
    if spec is None and not {"vary", "start", "stop", "speed"} <= {*given, *(
            ["speed"] if args.speed is not None else [])}:
        raise ModelError("the model has no periodic_parameter analysis; give --vary, "
                         "--speed, --start and --stop", args.command)
    vary = str(given.get("vary", getattr(spec, "vary", "")))
    if not given.keys() & {"vary", "start", "stop"}:
        return {}
    start, stop = parameter_range(model, vary, given.get("start", getattr(spec, "start", 0)),
                                  given.get("stop", getattr(spec, "stop", 0)))
    return {"vary": vary, "start": start, "stop": stop}


def _step_changes(spec: Any, args: argparse.Namespace) -> dict[str, Any]:
    """``--rtol`` runs the error-controlled method ``auto`` in place of the model's fixed
    ``dt``; ``--dt`` runs a fixed step in place of the model's ``rtol`` (its method then
    reverts to the default when it was ``auto``). Both at once are refused."""
    from rotorsim.errors import ModelError

    if args.rtol is not None and args.dt is not None:
        raise ModelError("give --dt (a fixed step) or --rtol (error-controlled), not both",
                         args.command)
    method = getattr(spec, "method", None)
    if args.rtol is not None:
        return {"rtol": args.rtol, "dt": None,
                **({"method": None} if method not in (None, "auto") else {})}
    if args.dt is not None and spec is not None and (spec.rtol is not None or
                                                     method == "auto"):
        return {"rtol": None, **({"method": None} if method == "auto" else {})}
    return {}


def _run_control_changes(args: argparse.Namespace) -> dict[str, Any]:
    """Flat keys of ``--every``, ``--velocities``, ``--reducers``, ``--stop-when-steady``,
    ``--steady-rtol`` and ``--steady-revolutions``."""
    from rotorsim.options import Output, SteadyStop

    changes: dict[str, Any] = {}
    for group, field in ((Output, "every"), (SteadyStop, "rtol"), (SteadyStop, "revolutions")):
        value = getattr(args, option_dest(group, field), None)
        if value is not None:
            changes[option_dest(group, field)] = value
    if args.velocities:
        changes["velocities"] = True
    if args.reducers is not None:
        changes["reducers"] = tuple(r.strip() for r in args.reducers.split(",") if r.strip())
    if args.stop_when_steady:
        changes["stop_when_steady"] = True
    return changes


def _count(text: str) -> int:
    from rotorsim.errors import ModelError

    try:
        value = int(text)
    except ValueError:
        raise ModelError(f"NUM must be an integer, got {text!r}", "command line") from None
    if value < 1:
        raise ModelError(f"NUM must be >= 1, got {value}", "command line")
    return value
