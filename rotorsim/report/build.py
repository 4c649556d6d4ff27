"""Write the report of a model file: run its analyses, save the results to ``report.h5``
and write ``report.html`` beside it (:func:`write_report`)."""

from __future__ import annotations

import dataclasses
import os
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from rotorsim.report import page
from rotorsim.report.bearing_life import history_lives, static_lives

HDF5_NAME = "report.h5"
HTML_NAME = "report.html"


def write_report(model: Any, out: str | os.PathLike[str] = "results", *, fast: bool = False,
                 units: str = "rpm", plots: bool = True) -> Path:
    """Run every analysis a model file names and write its HTML report.

    Parameters
    ----------
    model : Model or path
        A loaded model file (:func:`rotorsim.load_model`) or the path of one.
    out : path
        Output folder; the report goes to ``out/<model name>/report.html`` with the
        results in ``report.h5`` (one group per analysis, ``/results/<name>``).
    fast : bool
        Coarse grids and short runs (as ``run_analysis(..., fast=True)``).
    units : {"rpm", "Hz", "rad/s"}
        Units of speeds in the summaries and figures.
    plots : bool
        Embed the figures (False: tables and summaries only).

    Returns
    -------
    Path
        The HTML file. It embeds every figure (base64 PNG) and needs no network.
    """
    from rotorsim.io.hdf5 import save
    from rotorsim.io.model_file import load_model
    from rotorsim.io.output_folder import prepare_folder

    if not hasattr(model, "analyses"):
        model = load_model(model)
    folder = Path(out) / model.name
    prepare_folder(folder / HTML_NAME, "out")
    results: dict[str, Any] = {}
    sections = [_model_section(model, plots)]
    if model.rolling_bearings:
        sections.append(_rolling_section(model, results, plots))
    for name in model.analyses:
        sections.append(_analysis_section(model, name, folder, fast, units, results,
                                          plots))
    storable = _storable(results)
    if storable:
        save(storable, folder / HDF5_NAME)
    skipped = sorted(set(results) - set(storable))
    body = [*_header(model, skipped), *sections]
    path = folder / HTML_NAME
    path.write_text(page.document(f"rotorsim report: {model.name}", body), encoding="utf-8")
    return path


def _header(model: Any, skipped: list[str]) -> list[str]:
    import rotorsim

    parts = [page.heading(1, f"Rotordynamic report: {model.name}")]
    if model.description:
        parts.append(page.paragraph(model.description))
    parts.append(page.paragraph(
        f"Model file {model.source or '(built in Python)'}; rotorsim "
        f"{rotorsim.__version__}; written {datetime.now(UTC).isoformat(timespec='seconds')}. "
        f"Every number on this page comes from the results in {HDF5_NAME} beside it: each "
        "section names its group (rotorsim.load reads them back).", "source"))
    if skipped:
        parts.append(page.paragraph(f"Not stored in {HDF5_NAME} (a type without an HDF5 "
                                    f"layout): {', '.join(skipped)}", "warn"))
    names = ["model", *(["rolling-bearings"] if model.rolling_bearings else []),
             *model.analyses]
    items = "".join(f'<li><a href="#{page.text(n)}">{page.text(n)}</a></li>' for n in names)
    parts.append(f"<ul>{items}</ul>")
    return parts


def _model_section(model: Any, plots: bool) -> str:
    from rotorsim.elements.linear_bearing import BearingElement
    from rotorsim.plotting import plot

    rows = [(k, f"{v:.4g}" if isinstance(v, float) else v)
            for k, v in model.rotor.summary().items()]
    extra = [BearingElement(n=int(rb.n), n_link=rb.n_link, tag=rb.tag)
             for rb in model.rolling_bearings]  # drawn as supports
    drawn = model.rotor.with_bearings([*model.rotor.bearing_elements, *extra])
    return "".join([page.heading(2, "Model", "model"),
                    page.table(rows, ("quantity", "value")), _lines_table(model.rotor),
                    page.figure(plot(drawn), "layout of the rotor (to scale)") if plots
                    else ""])


def _lines_table(rotor: Any) -> str:
    """The shaft lines of a machine (spools and casing): speed ratio, nodes, mass and
    where their API unbalance checks are (one per spool, ``spool = "<line>"``)."""
    layout = rotor.layout
    if len(layout.lines) < 2:
        return ""
    rows = []
    for i, line in enumerate(layout.lines):
        first = int(layout.first_node[i])
        on = range(first, first + line.n_nodes)
        mass = sum(el.mass for el in line.elements) + sum(
            d.m for d in rotor.disk_elements if d.n in on)
        rows.append((line.name, f"{line.speed_ratio:g}", f"{first}-{on[-1]}",
                     f"{mass:.4g}", "spool" if line.speed_ratio else "not rotating"))
    return (page.paragraph("A machine of several shaft lines; speeds are the reference "
                           "speed unless a section names a spool (API checks are made per "
                           "spool, in its own speeds).")
            + page.table(rows, ("line", "speed ratio", "nodes", "mass [kg]", "kind")))


def _rolling_section(model: Any, results: dict[str, Any], plots: bool) -> str:
    from rotorsim.cli.summaries import bearing_summary, linearization_summary
    from rotorsim.plotting import plot

    linear = model.linearized()
    parts = [page.heading(2, "Rolling bearings", "rolling-bearings"),
             page.preformatted(linearization_summary(linear))]
    for tag, equilibrium in zip(linear.tags, linear.equilibria, strict=True):
        key = f"bearing_{tag}"
        results[key] = equilibrium
        parts += [page.heading(3, f"bearing {tag}"),
                  page.paragraph(f"HDF5: {HDF5_NAME}, group /results/{key}", "source"),
                  page.preformatted(bearing_summary(equilibrium, tag))]
        if plots:
            parts.append(page.figure(plot(equilibrium), f"load distribution of bearing {tag}"))
    parts.append(static_lives(model, linear, results))
    return "".join(parts)


def _analysis_section(model: Any, name: str, folder: Path, fast: bool, units: str,
                      results: dict[str, Any], plots: bool) -> str:
    from rotorsim.cli.completeness import incomplete_reason
    from rotorsim.cli.outputs import figures_of
    from rotorsim.cli.summaries import summarize
    from rotorsim.errors import RotorsimError
    from rotorsim.io.model_file import run_analysis

    spec = model.analyses[name]
    parts = [page.heading(2, f"{name} ({spec.type})", name)]
    if spec.description:
        parts.append(page.paragraph(spec.description))
    try:
        result = run_analysis(model, name, fast=fast, checkpoint_dir=folder)
    except RotorsimError as err:
        parts.append(page.paragraph(f"failed: {err}", "warn"))
        return "".join(parts)
    results[name] = result
    parts.append(page.paragraph(f"HDF5: {HDF5_NAME}, group /results/{name}", "source"))
    why = incomplete_reason(result)
    if why:
        parts.append(page.paragraph(f"incomplete: {why}", "warn"))
    summary_options, figure_options = _display_options(spec, units)
    parts.append(_tables(result) or page.preformatted(summarize(result, **summary_options)))
    figures = figures_of(result, name, units, figure_options) if plots else {}
    for file_name, fig in figures.items():
        parts.append(page.figure(fig, file_name.removesuffix(".png").replace("_", " ")))
    parts.append(history_lives(model, name, result, results))
    return "".join(parts)


def _tables(result: Any) -> str | None:
    """HTML tables of the API results (the others are printed as the command line does)."""
    kind = type(result).__name__
    notes = "".join(page.paragraph(f"note: {n}", "warn") for n in result.notes) \
        if hasattr(result, "notes") else ""
    if kind == "ApiLevel1Result":
        reasons = "".join(page.paragraph(f"Level II required: {r}", "warn")
                          for r in result.reasons)
        stages = [(str(n), f"{q / 1e3:.4g}") for n, q in zip(
            result.stage_nodes.tolist(), result.stage_q, strict=True)]
        return (page.table(result.table(), ("API 617 Level I", "value")) + reasons
                + page.table(stages, ("stage node", "QA [N/mm]")) + notes)
    if kind == "ApiUnbalanceResult":
        clearances = [(tag, str(n), f"{c * 1e3:.3g}", *(f"{r:.3g}" for r in ratio))
                      for tag, n, c, *ratio in zip(
                          result.clearance_tags, result.clearance_nodes.tolist(),
                          result.clearance, *result.clearance_ratio, strict=True)]
        head = ("clearance", "node", "diametral [mm]",
                *(f"ratio, mode {m}" for m in range(result.num_modes)))
        verdict = page.paragraph("API 617 margins and clearance ratios: "
                                 + ("pass" if result.passed else "FAIL"))
        return (page.table(result.table(), ("mode", "critical [rpm]", "AF", "SM req. [%]",
                                             "SM actual [%]", "margin",
                                             "max clearance ratio"))
                + (page.table(clearances, head) if clearances else "") + verdict + notes)
    return None


def _display_options(spec: Any, units: str) -> tuple[dict[str, Any], dict[str, Any]]:
    """Summary and figure options of an analysis, as the command line chooses them."""
    summary: dict[str, Any] = {"units": units} if spec.type != "static" else {}
    figure: dict[str, Any] = {}
    if spec.type == "campbell":
        summary["harmonics"] = figure["harmonics"] = spec.harmonics
    if spec.type in ("unbalance", "frequency_response"):
        figure["dofs"] = tuple(spec.dofs)
        if spec.nodes:
            figure["node"] = spec.nodes[0]
            summary["nodes"] = tuple(spec.nodes)
    if spec.type == "transient" and spec.nodes:
        figure["node"] = spec.nodes[0]
    return summary, figure


def _storable(results: dict[str, Any]) -> dict[str, Any]:
    """The results the HDF5 layout can hold (a sweep keeps its own store)."""
    from rotorsim.io.serialize import RESULT_TYPES

    return {k: v for k, v in results.items()
            if type(v).__name__ in RESULT_TYPES and dataclasses.is_dataclass(v)}
