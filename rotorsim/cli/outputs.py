"""Files written by the command line for one analysis: HDF5 result and PNG figures."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from rotorsim.io.output_folder import prepare_folder

MODE_FIGURES = 4
"""Number of mode-shape figures written for a modal analysis."""


def write_outputs(result: Any, folder: Path, name: str, *, units: str = "rpm",
                  plots: bool = True, figure_options: dict[str, Any] | None = None
                  ) -> list[Path]:
    """Save ``result`` to ``folder/name.h5`` and, with ``plots``, its figures as PNG.

    ``figure_options`` are passed to :func:`rotorsim.plotting.plot` (e.g. ``harmonics`` of a
    Campbell diagram, ``node`` and ``dofs`` of a response). Returns the paths written.
    """
    from rotorsim.io.hdf5 import save

    prepare_folder(folder / name, "--out")
    target = folder / f"{name}.h5"
    stored = type(result).__name__ == "SweepResult" and result.options.get("store") == str(
        target)  # a sweep wrote its points there as they finished
    written = [target if stored else save(result, target)]
    if plots:
        written += _figures(result, folder, name, units, figure_options or {})
    return written


def _figures(result: Any, folder: Path, name: str, units: str,
             options: dict[str, Any]) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    for file_name, fig in figures_of(result, name, units, options).items():
        path = folder / file_name
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        paths.append(path)
    return paths


def figures_of(result: Any, name: str, units: str = "rpm",
               options: dict[str, Any] | None = None) -> dict[str, Any]:
    """The standard figures of ``result`` as ``{file name: matplotlib Figure}`` (none for a
    type without a figure): the first :data:`MODE_FIGURES` mode shapes of a modal result,
    Bode and polar plots of a response, one figure otherwise."""
    import matplotlib

    matplotlib.use("Agg")
    from rotorsim.plotting import plot
    from rotorsim.plotting.figures import DRAWERS

    options = options or {}
    kind = type(result).__name__
    if kind not in DRAWERS:
        return {}
    figures: dict[str, Any] = {}
    if kind == "ModalResult":
        for j in range(min(MODE_FIGURES, result.num_modes)):
            figures[f"{name}_mode_{j}.png"] = plot(result, mode=j, units="Hz")
    elif kind in ("StaticResult", "BearingEquilibriumResult", "StiffnessVariation",
                  "BearingLifeResult"):
        figures[f"{name}.png"] = plot(result)
    elif kind == "FrequencyResponseResult":
        figures[f"{name}.png"] = plot(result, units=units, **options)
        figures[f"{name}_polar.png"] = plot(result, polar=True, **options)
    else:
        figures[f"{name}.png"] = plot(result, units=units, **options)
    return figures


def write_layout(rotor: Any, folder: Path) -> Path:
    """Draw the rotor layout to ``folder/layout.png``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rotorsim.plotting import plot

    prepare_folder(folder / "layout.png", "--out")
    fig = plot(rotor)
    path = folder / "layout.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def _bearing_life(rolling: Any, equilibrium: Any, rating: Any) -> Any:
    """Print the lives and pressures of one bearing equilibrium; None (with a note) when the
    bearing cannot be rated (e.g. no groove factors, a thrust bearing without ``C``)."""
    from rotorsim.analyses.statics.bearing_life import bearing_life
    from rotorsim.errors import ModelError

    try:
        life = bearing_life(rolling, equilibrium=equilibrium, options=rating)
    except ModelError as err:
        print(f"life and contact pressures: not rated ({err})")
        return None
    print(life.table())
    print(life.pressure_table())
    return life


def write_bearing_outputs(rolling: Any, equilibrium: Any, tag: str, folder: Path, *,
                          plots: bool = True, n_points: int = 24,
                          rating: Any = None) -> list[Path]:
    """Print and write one rolling bearing at its linearisation point.

    Writes ``bearing_<tag>.h5`` (the ``BearingEquilibriumResult``),
    ``bearing_<tag>_pass.h5`` (its ``StiffnessVariation`` over one element pass at the same
    load) and ``bearing_<tag>_life.h5`` (lives and contact pressures,
    :func:`rotorsim.bearing_life` with the options ``rating``), with their figures as PNG.
    Returns the paths written.
    """
    from rotorsim.analyses.statics.bearing_statics import stiffness_over_pass
    from rotorsim.cli.summaries import bearing_summary, stiffness_variation_summary
    from rotorsim.errors import ConvergenceError

    print(f"\n== bearing {tag} ==")
    print(bearing_summary(equilibrium, tag))
    try:
        variation = stiffness_over_pass(rolling.bearing, equilibrium.load, n_points)
    except ConvergenceError:  # Newton may stall in very soft directions; energy does not
        variation = stiffness_over_pass(rolling.bearing, equilibrium.load, n_points,
                                        method="energy")
    print(stiffness_variation_summary(variation))
    name = f"bearing_{tag}"
    files = write_outputs(equilibrium, folder, name, plots=plots)
    files += write_outputs(variation, folder, f"{name}_pass", plots=plots)
    life = _bearing_life(rolling, equilibrium, rating)
    if life is not None:
        files += write_outputs(life, folder, f"{name}_life", plots=plots)
    print("wrote " + ", ".join(str(f) for f in files))
    return files
