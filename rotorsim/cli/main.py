"""``rotorsim`` command line: thin subcommands over model files, analyses and result I/O.

Every analysis writes ``<out>/<model>/<analysis>.h5`` (see docs/results_format.md) and a
PNG figure, and prints a summary. Bad input ends with one line on stderr and exit code 2
(``--debug`` shows the traceback instead).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NoReturn

EXIT_BAD_INPUT = 2
EXIT_FAILED = 1

_SUBCOMMAND_HELP = {
    "modal": "modes at one speed",
    "campbell": "Campbell diagram and its critical speeds",
    "critical-speeds": "exact undamped critical speeds",
    "map": "undamped critical-speed map against support stiffness",
    "unbalance": "unbalance response",
    "static": "static deflection, bearing reactions and section forces",
    "transient": "time integration on the nonlinear bearings (run-up, orbits, bearing loads)",
    "periodic": "harmonic-balance branch over speed with Floquet stability and bifurcations",
    "periodic-parameter": "harmonic-balance branch at a fixed speed over a model parameter "
                          "(a key path such as bearings.B1.cxx, 'loads' or 'forcing')",
}
_BEARING_HELP = "load distribution and stiffness matrix of each rolling bearing"
_SUBCOMMAND_TYPES = {
    "modal": "modal",
    "campbell": "campbell",
    "critical-speeds": "critical_speeds",
    "map": "critical_speed_map",
    "unbalance": "unbalance",
    "static": "static",
    "transient": "transient",
    "periodic": "periodic",
    "periodic-parameter": "periodic_parameter",
}


class OneLineParser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line on stderr (exit code 2), like
    every other bad input, with a pointer to ``--help`` instead of the usage block."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_BAD_INPUT, f"rotorsim: error: {message} (see '{self.prog} --help')\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``rotorsim`` (all subcommands)."""
    parser = OneLineParser(
        prog="rotorsim", description="Rotordynamics with finite elements.")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    info = sub.add_parser("info", help="summary table of a model file")
    info.add_argument("model", type=Path)

    run = sub.add_parser("run", help="run the analyses a model file names")
    run.add_argument("model", type=Path)
    run.add_argument("analyses", nargs="*", help="names of analyses (default: all)")
    _add_output_options(run)

    for name, kind in _SUBCOMMAND_TYPES.items():
        p = sub.add_parser(name, help=_SUBCOMMAND_HELP[name])
        p.add_argument("model", type=Path)
        _add_output_options(p)
        if kind in ("modal", "campbell", "critical_speeds", "critical_speed_map"):
            p.add_argument("--num-modes", type=int, help="number of modes")
        if kind == "modal":
            p.add_argument("--speed", help='spin speed, e.g. "3000 rpm" (default 0)')
        if kind in ("campbell", "unbalance"):
            p.add_argument("--speeds", nargs=3, metavar=("START", "STOP", "NUM"),
                           help='speed range, e.g. 0 "4500 rpm" 91 (numbers are rad/s)')
        if kind == "transient":
            p.add_argument("--t-end", help='duration, e.g. "0.5 s"')
            p.add_argument("--dt", help='time step, e.g. "20 us"')
            p.add_argument("--speed", help='spin speed (start of a ramp), e.g. "3000 rpm"')
            p.add_argument("--speed-stop", help="end speed of a linear run-up/coast-down")
        if kind == "periodic":
            p.add_argument("--start", help='first speed of the branch, e.g. "1000 rpm"')
            p.add_argument("--stop", help="last speed of the branch")
        if kind == "periodic_parameter":
            p.add_argument("--vary", help="key path of the parameter, e.g. "
                           "rolling_bearings.DE.radial_clearance, or loads or forcing")
            p.add_argument("--speed", help='the fixed spin speed, e.g. "3000 rpm"')
            p.add_argument("--start", help='first value, e.g. "5 um" (numbers are SI)')
            p.add_argument("--stop", help="last value")
        if kind in ("periodic", "periodic_parameter"):
            p.add_argument("--harmonics", type=int, help="number of harmonics H")
            p.add_argument("--max-points", type=int, help="largest number of branch points")
            p.add_argument("--no-stability", action="store_true",
                           help="skip the Floquet stability analysis")
        if kind == "critical_speed_map":
            p.add_argument("--stiffness", nargs=3, metavar=("KMIN", "KMAX", "NUM"),
                           help='support stiffness range, e.g. "0.1 MN/m" "1 GN/m" 40')

    bearing = sub.add_parser("bearing", help=_BEARING_HELP)
    bearing.add_argument("model", type=Path)
    bearing.add_argument("--tag", help="only the rolling bearing with this tag (or index)")
    bearing.add_argument("--out", type=Path, default=Path("results"),
                         help="output folder (default: results)")
    bearing.add_argument("--no-plots", action="store_true", help="do not write PNG figures")
    bearing.add_argument("--fast", action="store_true",
                         help="6 instead of 24 positions over one element pass (smoke runs)")
    return parser


def _add_output_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("results"),
                   help="output folder (default: results)")
    p.add_argument("--units", choices=("rpm", "Hz", "rad/s"),
                   help="units of speeds and frequencies in summaries and figures")
    p.add_argument("--no-plots", action="store_true", help="do not write PNG figures")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bars (they are off anyway when stderr is not a terminal)")
    p.add_argument("--fast", action="store_true", help="coarse grids (smoke runs)")


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``rotorsim`` command; returns the exit code."""
    from rotorsim.errors import ConvergenceError, RotorsimError

    args = build_parser().parse_args(argv)
    try:
        return _dispatch(args)
    except (RotorsimError, FileNotFoundError, IsADirectoryError) as exc:
        if args.debug:
            raise
        code = EXIT_FAILED if isinstance(exc, ConvergenceError) else EXIT_BAD_INPUT
        print(f"rotorsim: error: {exc}", file=sys.stderr)
        return code


def _dispatch(args: argparse.Namespace) -> int:
    from rotorsim.io.model_file import load_model

    model = load_model(args.model)
    if args.command == "info":
        print(_info(model))
        return 0
    if args.command == "bearing":
        return _bearing(model, args)
    if args.command == "run":
        names = list(args.analyses) or list(model.analyses)
        if not names:
            print(f"{model.name}: the model file names no analyses", file=sys.stderr)
            return EXIT_BAD_INPUT
        unknown = [n for n in names if n not in model.analyses]
        if unknown:
            from rotorsim.errors import ModelError

            raise ModelError(f"no analysis {unknown[0]!r}; the model has "
                             f"{', '.join(model.analyses)}", model.name)
        jobs = [(name, None) for name in names]
    else:
        jobs = [_adhoc_job(model, args)]
    print(_info(model))
    if model.rolling_bearings:
        from rotorsim.cli.summaries import linearization_summary

        print(linearization_summary(model.linearized()))
    if not args.no_plots:
        from rotorsim.cli.outputs import write_layout

        print(f"layout drawing: {write_layout(_drawn_rotor(model), args.out / model.name)}")
    t0 = time.perf_counter()
    for name, spec in jobs:
        _run_one(model, name, spec, args)
    print(f"\n{len(jobs)} analyses in {time.perf_counter() - t0:.2f} s; results in "
          f"{args.out / model.name}/")
    return 0


def _info(model: Any) -> str:
    from rotorsim.cli.summaries import table

    s = model.rotor.summary()
    rows = [(k, f"{v:.4g}" if isinstance(v, float) else v) for k, v in s.items()]
    if model.rolling_bearings:
        tags = [rb.tag or str(i) for i, rb in enumerate(model.rolling_bearings)]
        rows.append(("rolling_bearings", ", ".join(tags)))
    rows.append(("analyses", ", ".join(model.analyses) or "-"))
    head = f"model '{model.name}'" + (f": {model.description}" if model.description else "")
    return head + "\n" + table(rows, ("quantity", "value"))


def _drawn_rotor(model: Any) -> Any:
    """The rotor with a zero-stiffness placeholder at each rolling bearing (drawing only)."""
    from rotorsim.elements.linear_bearing import BearingElement

    extra = [BearingElement(n=int(rb.n), n_link=rb.n_link, tag=rb.tag)
             for rb in model.rolling_bearings]
    return model.rotor.with_bearings([*model.rotor.bearing_elements, *extra])


def _bearing(model: Any, args: argparse.Namespace) -> int:
    """``rotorsim bearing``: each rolling bearing at its linearisation point."""
    from rotorsim.cli.outputs import write_bearing_outputs
    from rotorsim.cli.summaries import linearization_summary
    from rotorsim.errors import ModelError

    if not model.rolling_bearings:
        raise ModelError("the model has no [[rolling_bearings]]", model.name)
    linear = model.linearized()
    chosen = list(range(len(model.rolling_bearings)))
    if args.tag is not None:
        chosen = [i for i, tag in enumerate(linear.tags) if tag == args.tag]
        if not chosen:
            raise ModelError(f"no rolling bearing tagged {args.tag!r}; the model has "
                             f"{', '.join(linear.tags)}", "--tag")
    print(_info(model))
    print(linearization_summary(linear))
    t0 = time.perf_counter()
    for i in chosen:
        write_bearing_outputs(model.rolling_bearings[i], linear.equilibria[i], linear.tags[i],
                              args.out / model.name, plots=not args.no_plots,
                              n_points=6 if args.fast else 24)
    print(f"\n{len(chosen)} bearings in {time.perf_counter() - t0:.2f} s; results in "
          f"{args.out / model.name}/")
    return 0


def _adhoc_job(model: Any, args: argparse.Namespace) -> tuple[str, Any]:
    """The model's first analysis of the subcommand's type (or a default one) with the
    command-line overrides applied."""
    from rotorsim.io.analysis_spec import SPEC_TYPES, Grid
    from rotorsim.units import to_si

    kind = _SUBCOMMAND_TYPES[args.command]
    name, spec = next(((n, s) for n, s in model.analyses.items() if s.type == kind),
                      (kind, None))
    cls = SPEC_TYPES[kind]
    changes: dict[str, Any] = {}
    if getattr(args, "num_modes", None) is not None:
        changes["num_modes"] = args.num_modes
    for option in ("harmonics", "max_points"):
        if getattr(args, option, None) is not None:
            changes[option] = _count(str(getattr(args, option)))
    if getattr(args, "no_stability", False):
        changes["stability"] = "none"
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
        if kind == "transient" and not {"t_end", "dt"} <= set(changes):
            from rotorsim.errors import ModelError

            raise ModelError("the model has no transient analysis; give --t-end and --dt",
                             args.command)
        if kind == "periodic" and not {"start", "stop"} <= set(changes):
            from rotorsim.errors import ModelError

            raise ModelError("the model has no periodic analysis; give --start and --stop",
                             args.command)
    if kind == "periodic_parameter":
        changes.update(_parameter_changes(model, spec, args))
    spec = cls(**changes) if spec is None else dataclasses.replace(spec, **changes)
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


def _count(text: str) -> int:
    from rotorsim.errors import ModelError

    try:
        value = int(text)
    except ValueError:
        raise ModelError(f"NUM must be an integer, got {text!r}", "command line") from None
    if value < 1:
        raise ModelError(f"NUM must be >= 1, got {value}", "command line")
    return value


def _run_one(model: Any, name: str, spec: Any, args: argparse.Namespace) -> None:
    from rotorsim.cli.outputs import write_outputs
    from rotorsim.cli.summaries import summarize
    from rotorsim.io.analysis_spec import run_analysis

    if spec is not None:
        model = dataclasses.replace(model, analyses={**model.analyses, name: spec})
    spec = model.analyses[name]
    units = args.units or spec.units
    print(f"\n== {name} ({spec.type}) ==")
    t0 = time.perf_counter()
    progress = not args.no_progress and sys.stderr.isatty()
    result = run_analysis(model, name, fast=args.fast, progress=progress)
    elapsed = time.perf_counter() - t0
    summary_options: dict[str, Any] = {"units": units} if spec.type != "static" else {}
    figure_options: dict[str, Any] = {}
    if spec.type == "campbell":
        summary_options["harmonics"] = spec.harmonics
        figure_options["harmonics"] = spec.harmonics
    if spec.type in ("unbalance", "frequency_response"):
        figure_options["dofs"] = tuple(spec.dofs)
        if spec.nodes:
            figure_options["node"] = spec.nodes[0]
            summary_options["nodes"] = tuple(spec.nodes)
    print(summarize(result, **summary_options))
    if spec.type == "transient":
        units = "Hz"  # the figure's spectrum axis; the summary keeps the speed units
        if spec.nodes:
            figure_options["node"] = spec.nodes[0]
    files = write_outputs(result, args.out / model.name, name, units=units,
                          plots=not args.no_plots, figure_options=figure_options)
    print(f"[{elapsed:.2f} s] wrote " + ", ".join(str(f) for f in files))


if __name__ == "__main__":
    raise SystemExit(main())
