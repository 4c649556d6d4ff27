"""Model files (TOML): load a rotor with its loads and named analyses, and save one back.

A model file lists ``[model]``, ``[[materials]]``, ``[[shaft]]`` segments, ``[[disks]]``,
``[[bearings]]``, ``[[rolling_bearings]]``, ``[[point_masses]]``, ``[[fixed]]``, ``[loads]``
and named ``[analyses.<name>]``; the reference is ``docs/model_files.md``. Rolling bearings
stay out of ``Model.rotor``: the analyses run on :meth:`Model.linearized`, the rotor with
each rolling bearing linearised (by default at its static load). Values are SI numbers or
strings with units (``"50 mm"``, ``"1 MN/m"``, ``"3000 rpm"``).

Every problem in a file raises one :class:`~rotorsim.errors.ModelError` whose message
starts with the key path (``shaft[3].od: must be > id (0.06 m)``); TOML syntax errors give
the line and column.

pydantic (and pint, for unit strings) is imported when a file is read, so importing this
module stays light.

Examples
--------
>>> import tempfile, pathlib
>>> text = '''
... [[materials]]
... name = "steel"
... E = "211 GPa"
... G_s = "81.2 GPa"
... rho = "7810 kg/m^3"
...
... [[shaft]]
... length = "1.5 m"
... n_elements = 6
... od = "50 mm"
... material = "steel"
...
... [[bearings]]
... z = 0
... kxx = "1 MN/m"
...
... [[bearings]]
... z = "1.5 m"
... kxx = "1 MN/m"
...
... [analyses.modes]
... type = "modal"
... num_modes = 4
... '''
>>> path = pathlib.Path(tempfile.mkdtemp()) / "shaft.toml"
>>> _ = path.write_text(text)
>>> model = load_model(path)
>>> model.name, model.rotor.n_nodes, [b.n for b in model.rotor.bearing_elements]
('shaft', 7, [0, 6])
>>> result = run_analysis(model, "modes")
>>> result.wn.size
4
"""

from __future__ import annotations

import copy
import dataclasses
import os
import tempfile
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rotorsim.errors import ModelError
from rotorsim.io.analysis_spec import AnalysisSpec, Loads, run_analysis
from rotorsim.model.rotor import Rotor

if TYPE_CHECKING:
    from rotorsim.analyses.statics.linearized_rotor import LinearizationPoint, LinearizedRotor
    from rotorsim.elements.rolling.element import RollingBearing

__all__ = ["Model", "load_model", "model_from_dict", "run_analysis", "save_model"]


@dataclass(frozen=True, eq=False)
class Model:
    """A loaded model file: the rotor, its loads and its named analyses.

    Parameters
    ----------
    name : str
        ``[model] name``, or the file name without extension.
    rotor : Rotor
        The rotor (SI).
    loads : Loads
        Gravity, unbalance and static point loads.
    analyses : mapping of str to AnalysisSpec
        Named analyses in file order; run one with :func:`run_analysis`.
    description : str
        ``[model] description``.
    source : Path, optional
        The file the model was read from.
    rolling_bearings : tuple of RollingBearing
        Nonlinear rolling bearings (``[[rolling_bearings]]``); not part of ``rotor``.
    linearize : tuple of LinearizationPoint
        Where each rolling bearing is linearised for the linear analyses (default: all at
        their static loads).
    data : mapping, optional
        The parsed file the model was built from (:meth:`parameter` varies its values).
    """

    name: str
    rotor: Rotor
    loads: Loads = field(default_factory=Loads)
    analyses: Mapping[str, AnalysisSpec] = field(default_factory=dict)
    description: str = ""
    source: Path | None = None
    rolling_bearings: tuple[RollingBearing, ...] = ()
    linearize: tuple[LinearizationPoint, ...] = ()
    data: Mapping[str, Any] | None = field(default=None, repr=False)
    _linearized: dict[float, LinearizedRotor] = field(default_factory=dict, init=False,
                                                       repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "rolling_bearings", tuple(self.rolling_bearings))
        object.__setattr__(self, "linearize", tuple(self.linearize))
        if self.linearize and len(self.linearize) != len(self.rolling_bearings):
            raise ModelError(f"{len(self.rolling_bearings)} rolling bearings but "
                             f"{len(self.linearize)} linearisation points", self.name)

    def parameter(self, path: str) -> Any:
        """``vary(value) -> Rotor`` with ``value`` [SI] at the key path ``path`` of the model
        file (e.g. ``"bearings.B1.cxx"``, ``"rolling_bearings.DE.radial_clearance"``; a
        path into ``rolling_bearings`` gives the rolling bearings only), for
        :func:`rotorsim.periodic_parameter`; see :mod:`rotorsim.io.model_parameter`.

        Raises
        ------
        ModelError
            When the model was not read from a file or ``path`` names no value of it.
        """
        from rotorsim.io.model_parameter import ModelParameter

        if self.data is None:
            raise ModelError("the model was not built from a model file: vary the Rotor "
                             "with a function instead", self.name)
        return ModelParameter(self.data, path)

    def linearized(self, speed: float = 0.0) -> LinearizedRotor:
        """The rotor with its rolling bearings linearised (computed once per speed).

        Static bearings are linearised at the static equilibrium under ``loads`` (gravity
        and point loads) with speed-dependent linear bearings evaluated at ``speed``
        [rad/s]; see :func:`rotorsim.analyses.statics.linearized_rotor.linearize_rolling_bearings`.
        """
        from rotorsim.analyses.statics.linearized_rotor import linearize_rolling_bearings

        key = float(speed)
        if key not in self._linearized:
            self._linearized[key] = linearize_rolling_bearings(
                self.rotor, self.rolling_bearings, points=self.linearize or None,
                gravity=self.loads.gravity, direction=self.loads.gravity_direction,
                loads=self.loads.point_loads, speed=key)
        return self._linearized[key]


def load_model(path: str | os.PathLike[str]) -> Model:
    """Read a TOML model file.

    Parameters
    ----------
    path : str or path-like
        The ``.toml`` file.

    Returns
    -------
    Model

    Raises
    ------
    ModelError
        Missing or unreadable file, TOML syntax error (with line and column), or an invalid
        model; the message starts with the key path of the first problem.
    """
    path = Path(path)
    try:
        text = path.read_bytes().decode("utf-8")
    except OSError as err:
        raise ModelError(f"cannot read the file: {err.strerror or err}", str(path)) from None
    except UnicodeDecodeError as err:
        raise ModelError(f"not a UTF-8 text file ({err.reason} at byte {err.start})",
                         str(path)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ModelError(f"invalid TOML: {err}", str(path)) from None
    return model_from_dict(data, source=path)


def model_from_dict(data: Mapping[str, Any], *, source: str | os.PathLike[str] | None = None
                    ) -> Model:
    """Build a :class:`Model` from a parsed model file (the dict TOML gives).

    Parameters
    ----------
    data : mapping
        Model-file content.
    source : path, optional
        Where it came from; its stem is the default model name.

    Returns
    -------
    Model

    Raises
    ------
    ModelError
        Naming the key path of the first problem.
    """
    from rotorsim.io import model_build as build
    from rotorsim.io.analysis_schema import validate_analyses
    from rotorsim.io.model_schema import validate_model
    from rotorsim.io.rolling_schema import validate_rolling_bearings

    table = validate_model(dict(data) if isinstance(data, Mapping) else data)
    rolling_tables = validate_rolling_bearings(table.rolling_bearings)
    analyses = validate_analyses(table.analyses)
    build.check_unique_tags(table, rolling_tables)
    src = None if source is None else Path(source)
    name = table.model.name or (src.stem if src is not None else "rotor")
    rotor, nodes = build.build_rotor(table, name)
    rolling, points = build.build_rolling(rolling_tables, nodes)
    loads = build.build_loads(table, nodes)
    tags = tuple(rb.tag for rb in rolling)
    specs = {key: build.build_spec(t, loc, nodes, rotor, loads, tags)
             for key, loc, t in analyses}
    model = Model(name=name, rotor=rotor, loads=loads, analyses=specs,
                  description=table.model.description, source=src, rolling_bearings=rolling,
                  linearize=points, data=copy.deepcopy(dict(data)))
    return _parameter_ranges(model)


def _parameter_ranges(model: Model) -> Model:
    """``periodic_parameter`` analyses with their ``start`` and ``stop`` in SI (a key path
    resolved and its range checked against the key's dimension)."""
    from rotorsim.io.analysis_spec import PeriodicParameterSpec
    from rotorsim.io.model_parameter import parameter_range

    specs = dict(model.analyses)
    for key, spec in specs.items():
        if not isinstance(spec, PeriodicParameterSpec):
            continue
        try:
            start, stop = parameter_range(model, spec.vary, spec.start, spec.stop)
        except ModelError as err:
            raise ModelError(str(err), f"analyses.{key}") from None
        specs[key] = dataclasses.replace(spec, start=start, stop=stop)
    return dataclasses.replace(model, analyses=specs)


def save_model(model: Model | Rotor, path: str | os.PathLike[str]) -> Path:
    """Write a rotor or a model as a TOML model file in SI numbers.

    Shaft elements are written as one ``[[shaft]]`` segment per run of identical
    consecutive elements (tapered elements one by one), disks with ``m, Id, Ip``, bearings
    with every coefficient that differs from its default and their tables over
    ``frequency``. Loading the file rebuilds identical element matrices, loads and analyses.
    The file is written to a temporary name and renamed, so it is never left half-written.

    Parameters
    ----------
    model : Model or Rotor
        What to write; a bare Rotor gets default loads and no analyses.
    path : str or path-like
        Output file; missing folders are created.

    Returns
    -------
    Path
        ``path``.
    """
    from rotorsim.io.model_writer import model_to_dict, toml_text

    if isinstance(model, Rotor):
        model = Model(name=model.tag, rotor=model)
    if not isinstance(model, Model):
        raise ModelError(f"expected a Model or Rotor, got {type(model).__name__}", "save_model")
    from rotorsim.io.output_folder import prepare_folder

    path = Path(path)
    text = toml_text(model_to_dict(model))
    prepare_folder(path, "save_model")
    handle, tmp = tempfile.mkstemp(dir=path.parent or ".", prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as stream:
            stream.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path
