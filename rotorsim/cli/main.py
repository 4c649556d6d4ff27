"""``rotorsim`` command line: thin subcommands over model files, analyses and result I/O.

Every analysis writes ``<out>/<model>/<analysis>.h5`` (see docs/results_format.md) and a
PNG figure, and prints a summary. Bad input ends with one line on stderr and exit code 2
(``--debug`` shows the traceback instead); a failed solve with exit code 1; an analysis
that stopped short (status not OK) writes its partial results and ends with exit code 3.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from rotorsim.cli.adhoc import adhoc_job
from rotorsim.cli.parser import RESTARTABLE, build_parser, parse

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_BAD_INPUT = 2
EXIT_INCOMPLETE = 3
EXIT_INTERRUPTED = 130
"""Exit codes (also in ``rotorsim --help``): OK, a failed solve, bad input, an analysis
that stopped short with its partial results written, and Ctrl-C (128 + SIGINT)."""

__all__ = ["EXIT_BAD_INPUT", "EXIT_FAILED", "EXIT_INCOMPLETE", "EXIT_INTERRUPTED", "EXIT_OK",
           "build_parser", "main"]


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``rotorsim`` command; returns the exit code."""
    from rotorsim.errors import ConvergenceError, RotorsimError

    args = parse(argv)
    try:
        return _dispatch(args)
    except KeyboardInterrupt:
        if args.debug:
            raise
        print("rotorsim: interrupted (rerun with --resume to continue from the last "
              "checkpoint, if one was written with --checkpoint)", file=sys.stderr)
        return EXIT_INTERRUPTED
    except (RotorsimError, FileNotFoundError, IsADirectoryError) as exc:
        if args.debug:
            raise
        code = EXIT_FAILED if isinstance(exc, ConvergenceError) else EXIT_BAD_INPUT
        print(f"rotorsim: error: {exc}", file=sys.stderr)
        return code


def _dispatch(args: argparse.Namespace) -> int:
    from rotorsim.cli.preflight import transient_notes
    from rotorsim.io.model_file import load_model

    if args.command == "import-ross":
        from rotorsim.io.ross_import import from_ross, import_ross, table_note

        speeds = None if args.speed_range is None else tuple(args.speed_range)
        print(f"model file: {import_ross(args.model, args.out, speed_range=speeds)}")
        note = table_note(from_ross(args.model, speed_range=speeds))
        if note:
            print(f"note: {note}")
        return 0
    model = load_model(args.model)
    if args.command == "info":
        print(_info(model))
        _print_notes(transient_notes(model, [(name, None) for name in model.analyses]))
        return 0
    if args.command == "bearing":
        return _bearing(model, args)
    if args.command == "report":
        from rotorsim.report.build import write_report

        path = write_report(model, args.out, fast=args.fast, units=args.units,
                            plots=not args.no_plots)
        print(f"report: {path}")
        return 0
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
    elif args.command == "api":
        jobs = [(name, None) for name, spec in model.analyses.items()
                if spec.type in ("api_stability", "api_unbalance")]
        if not jobs:
            from rotorsim.errors import ModelError

            raise ModelError("the model file names no API check: add [analyses.<name>] "
                             "tables of type api_stability or api_unbalance", model.name)
    else:
        jobs = [adhoc_job(model, args)]
    from rotorsim.io.output_folder import prepare_folder

    notes = transient_notes(model, jobs)  # checks before any analysis runs
    prepare_folder(args.out / model.name / "any", "--out")  # before any long work
    print(_info(model))
    _print_notes(notes)
    if model.rolling_bearings:
        from rotorsim.cli.summaries import linearization_summary

        print(linearization_summary(model.linearized()))
    if not args.no_plots:
        from rotorsim.cli.outputs import write_layout

        print(f"layout drawing: {write_layout(_drawn_rotor(model), args.out / model.name)}")
    t0 = time.perf_counter()
    incomplete = [(name, why) for name, spec in jobs
                  if (why := _run_one(model, name, spec, args)) is not None]
    print(f"\n{len(jobs)} analyses in {time.perf_counter() - t0:.2f} s; results in "
          f"{args.out / model.name}/")
    for name, why in incomplete:
        print(f"rotorsim: incomplete: {name}: {why} (partial results written)",
              file=sys.stderr)
    return EXIT_INCOMPLETE if incomplete else EXIT_OK


def _print_notes(notes: list[str]) -> None:
    for note in notes:
        print(f"note: {note}")


def _info(model: Any) -> str:
    from rotorsim.cli.summaries import preload_rows, table

    s = model.rotor.summary()
    rows = [(k, f"{v:.4g}" if isinstance(v, float) else v) for k, v in s.items()]
    if model.rolling_bearings:
        tags = [rb.tag or str(i) for i, rb in enumerate(model.rolling_bearings)]
        rows.append(("rolling_bearings", ", ".join(tags)))
        rows.extend(preload_rows(model.rolling_bearings))
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
                              n_points=6 if args.fast else 24,
                              rating=model.ratings[i] if model.ratings else None)
    print(f"\n{len(chosen)} bearings in {time.perf_counter() - t0:.2f} s; results in "
          f"{args.out / model.name}/")
    return 0


def _run_one(model: Any, name: str, spec: Any, args: argparse.Namespace) -> str | None:
    """Run, summarise and write one analysis; why it is incomplete (None when OK)."""
    from rotorsim.cli.completeness import incomplete_reason
    from rotorsim.cli.outputs import write_outputs
    from rotorsim.cli.summaries import summarize
    from rotorsim.io.model_file import run_analysis

    spec = _with_restart(model.analyses[name] if spec is None else spec, name, args,
                         args.out / model.name)
    model = dataclasses.replace(model, analyses={**model.analyses, name: spec})
    units = args.units or spec.units
    print(f"\n== {name} ({spec.type}) ==")
    t0 = time.perf_counter()
    progress = not args.no_progress and sys.stderr.isatty()
    result = run_analysis(model, name, fast=args.fast, progress=progress,
                          checkpoint_dir=args.out / model.name)
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
    return incomplete_reason(result)


def _with_restart(spec: Any, name: str, args: argparse.Namespace, folder: Path) -> Any:
    """The spec with ``--checkpoint``, ``--checkpoint-every`` and ``--resume`` applied
    (transients and periodic branches; ``--resume`` for sweeps, whose results file is their
    store); says where the checkpoint is."""
    from rotorsim.io.restart import checkpoint_path

    if spec.type == "sweep":  # its points go to <name>.h5 as they finish
        if getattr(args, "resume", False):
            spec = dataclasses.replace(spec, resume=True)
        store = folder / f"{name}.h5"
        if spec.resume:
            print(f"resuming the sweep stored in {store}" if store.is_file() else
                  f"no sweep store {store} yet: starting from the beginning")
        return spec
    if spec.type not in RESTARTABLE:
        return spec
    every = getattr(args, "checkpoint_every", None)
    if every is not None and every < 1:
        from rotorsim.errors import ModelError

        raise ModelError(f"must be >= 1, got {every}", "--checkpoint-every")
    changes = {key: True for key in ("checkpoint", "resume") if getattr(args, key, False)}
    if every is not None:
        changes.update(checkpoint=True, checkpoint_every=every)
    spec = spec.with_flat(**changes)
    path = checkpoint_path(folder, name)
    if spec.checkpoint or spec.resume:
        from rotorsim.io.output_folder import prepare_folder

        prepare_folder(path, "--checkpoint")
    if spec.resume:
        print(f"resuming from {path}" if path.is_file() else
              f"no checkpoint {path} yet: starting from the beginning")
    elif spec.checkpoint:
        print(f"checkpoints in {path}")
    return spec


if __name__ == "__main__":
    raise SystemExit(main())
