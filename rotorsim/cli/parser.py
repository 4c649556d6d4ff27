"""The ``rotorsim`` argument parser: subcommands, their options and exit codes."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

from rotorsim.options import Checkpointing, ContinuationOptions, Harmonics, Output, SteadyStop
from rotorsim.options.flat import flat_key, option_field
from rotorsim.options.group import OptionGroup

RESTARTABLE = ("transient", "periodic", "periodic_parameter")
"""Analysis types with checkpoints (``--checkpoint``, ``--resume``)."""
BRANCH_OPTIONS: tuple[tuple[type[OptionGroup], str], ...] = (
    (Harmonics, "count"), (ContinuationOptions, "max_points"))
"""Option-group fields of a periodic branch on the command line (``--harmonics``,
``--max-points``): name, type and help come from the group's field."""

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
SUBCOMMAND_TYPES = {
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


EPILOG = """exit codes:
  0  every analysis finished with status OK
  1  an analysis failed (a single solve did not converge); nothing written for it
  2  bad input: model file, option or value (one line on stderr)
  3  incomplete: an analysis stopped short (a periodic branch ended before its bound, a
     transient step failed, sweep points failed); its partial results are written and
     the reason is printed on stderr
  130  interrupted (Ctrl-C); continue with --resume when --checkpoint was given"""


class OneLineParser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line on stderr (exit code 2), like
    every other bad input, with a pointer to ``--help`` instead of the usage block."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"rotorsim: error: {message} (see '{self.prog} --help')\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``rotorsim`` (all subcommands; they share its class)."""
    parser = OneLineParser(
        prog="rotorsim", description="Rotordynamics with finite elements.", epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    info = sub.add_parser("info", help="summary table of a model file")
    info.add_argument("model", type=Path)

    run = sub.add_parser("run", help="run the analyses a model file names")
    run.add_argument("model", type=Path)
    run.add_argument("analyses", nargs="*", help="names of analyses (default: all)")
    _add_output_options(run)
    _add_restart_options(run)

    for name, kind in SUBCOMMAND_TYPES.items():
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
            p.add_argument("--rtol", type=float,
                           help="accuracy relative to the motion, e.g. 1e-5: runs the "
                                "error-controlled method 'auto' instead of a fixed dt")
            p.add_argument("--speed", help='spin speed (start of a ramp), e.g. "3000 rpm"')
            p.add_argument("--speed-stop", help="end speed of a linear run-up/coast-down")
            _add_run_control_options(p)
        if kind == "periodic":
            p.add_argument("--start", help='first speed of the branch, e.g. "1000 rpm"')
            p.add_argument("--stop", help="last speed of the branch")
        if kind == "periodic_parameter":
            p.add_argument("--vary", help="key path of the parameter, e.g. "
                           "rolling_bearings.DE.radial_clearance, or loads or forcing")
            p.add_argument("--speed", help='the fixed spin speed, e.g. "3000 rpm"')
            p.add_argument("--start", help='first value, e.g. "5 um" (numbers are SI)')
            p.add_argument("--stop", help="last value")
        if kind in RESTARTABLE:
            _add_restart_options(p)
        if kind in ("periodic", "periodic_parameter"):
            for group, field in BRANCH_OPTIONS:
                add_option(p, group, field)
            p.add_argument("--no-stability", action="store_true",
                           help="skip the Floquet stability analysis")
        if kind == "critical_speed_map":
            p.add_argument("--stiffness", nargs=3, metavar=("KMIN", "KMAX", "NUM"),
                           help='support stiffness range, e.g. "0.1 MN/m" "1 GN/m" 40')

    api = sub.add_parser("api", help="the API 617 checks a model file names (analyses of "
                         "type api_stability and api_unbalance): Level I stability, "
                         "unbalance response, separation margins, clearance ratios")
    api.add_argument("model", type=Path)
    _add_output_options(api)

    report = sub.add_parser("report", help="run every analysis of a model file and write "
                            "one self-contained HTML report (figures embedded) beside its "
                            "HDF5 results")
    report.add_argument("model", type=Path)
    report.add_argument("--out", type=Path, default=Path("results"),
                        help="output folder (default: results)")
    report.add_argument("--units", choices=("rpm", "Hz", "rad/s"), default="rpm",
                        help="units of speeds in the summaries and figures")
    report.add_argument("--no-plots", action="store_true",
                        help="leave the figures out (tables and summaries only)")
    report.add_argument("--fast", action="store_true", help="coarse grids (smoke runs)")

    ross = sub.add_parser("import-ross", help="write the rotorsim model file of a ROSS rotor "
                          "file (ross.Rotor.save, .toml or .json)")
    ross.add_argument("model", type=Path, help="the ROSS file")
    ross.add_argument("--out", type=Path, help="model file to write (default: "
                      "<name>_rotorsim.toml beside the ROSS file)")
    ross.add_argument("--speed-range", nargs=2, type=float, metavar=("MIN", "MAX"),
                      help="speeds [rad/s] the bearing tables must cover (extended by "
                      "ROSS's linear extrapolation)")

    bearing = sub.add_parser("bearing", help=_BEARING_HELP)
    bearing.add_argument("model", type=Path)
    bearing.add_argument("--tag", help="only the rolling bearing with this tag (or index)")
    bearing.add_argument("--out", type=Path, default=Path("results"),
                         help="output folder (default: results)")
    bearing.add_argument("--no-plots", action="store_true", help="do not write PNG figures")
    bearing.add_argument("--fast", action="store_true",
                         help="6 instead of 24 positions over one element pass (smoke runs)")
    return parser


def _add_run_control_options(p: argparse.ArgumentParser) -> None:
    """What a transient keeps and when it stops (``rs.Output``, ``rs.SteadyStop``)."""
    add_option(p, Output, "every", metavar="N")
    p.add_argument("--velocities", action="store_true",
                   help=option_field(Output, "velocities").metadata["help"])
    p.add_argument("--reducers", metavar="NAMES",
                   help="comma-separated reductions over every step: max_abs, peak_to_peak "
                        "(per revolution), max_amplitude (radial), rms")
    p.add_argument("--stop-when-steady", action="store_true",
                   help="stop once the peak-to-peak per revolution has settled")
    add_option(p, SteadyStop, "rtol")
    add_option(p, SteadyStop, "revolutions", metavar="N")


def _add_output_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("results"),
                   help="output folder (default: results)")
    p.add_argument("--units", choices=("rpm", "Hz", "rad/s"),
                   help="units of speeds and frequencies in summaries and figures")
    p.add_argument("--no-plots", action="store_true", help="do not write PNG figures")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bars (they are off anyway when stderr is not a terminal)")
    p.add_argument("--fast", action="store_true", help="coarse grids (smoke runs)")


def _add_restart_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--checkpoint", action="store_true",
                   help="write <out>/<model>/<analysis>.checkpoint.h5 while a transient or "
                        "periodic branch runs")
    add_option(p, Checkpointing, "every", metavar="N")
    p.add_argument("--resume", action="store_true",
                   help="continue from that checkpoint when it exists (and keep writing it)")


def add_option(p: argparse.ArgumentParser, group: type[OptionGroup], field: str,
               **extra: str) -> None:
    """The option ``--<flat key>`` of an option-group field, with its type and help."""
    meta = option_field(group, field).metadata
    p.add_argument("--" + flat_key(group, field).replace("_", "-"), type=meta["file"],
                   help=meta["help"], **extra)  # type: ignore[arg-type]


def option_dest(group: type[OptionGroup], field: str) -> str:
    """The ``argparse`` attribute of :func:`add_option`'s option (its flat key)."""
    return flat_key(group, field)


def parse(argv: Sequence[str] | None) -> argparse.Namespace:
    """Parse a command line; options may come before or after the analysis names of
    ``run`` and ``--debug`` anywhere."""
    parser = build_parser()
    tokens = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in tokens
    tokens = [t for t in tokens if t != "--debug"]
    args, extras = parser.parse_known_args(tokens)
    if args.command == "run":
        args.analyses = [*args.analyses, *(e for e in extras if not e.startswith("-"))]
        extras = [e for e in extras if e.startswith("-")]
    if extras:
        parser.error(f"unrecognized arguments: {' '.join(extras)}")
    args.debug = debug
    return args
