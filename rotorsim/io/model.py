"""A loaded model file (:class:`Model`: rotor, loads, named analyses, rolling bearings)
and building one from the parsed file (:func:`model_from_dict`).

The tables of the file are validated by the schema modules (:mod:`rotorsim.io.model_schema`,
:mod:`rotorsim.io.rolling_schema`, :mod:`rotorsim.io.analysis_schema`) and resolved by
:mod:`rotorsim.io.model_build`; pydantic is imported only when a model is built, so
importing this module stays light. Reading and writing files:
:mod:`rotorsim.io.model_file`.
"""

from __future__ import annotations

import copy
import dataclasses
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rotorsim.errors import ModelError
from rotorsim.io.analysis_spec import AnalysisSpec, Loads
from rotorsim.io.long_specs import PeriodicParameterSpec
from rotorsim.io.model_parameter import ModelParameter, parameter_range
from rotorsim.model.rotor import Rotor

if TYPE_CHECKING:
    from rotorsim.analyses.statics.linearized_rotor import LinearizationPoint, LinearizedRotor
    from rotorsim.elements.rolling.element import RollingBearing

__all__ = ["Model", "model_from_dict"]


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
        Named analyses in file order; run one with
        :func:`~rotorsim.io.analysis_runners.run_analysis`.
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
    ratings : tuple of RatingOptions or None
        Rating options of each rolling bearing (``[rolling_bearings.rating]``; None: the
        ISO 281 geometry formulas), used by ``rotorsim bearing`` for lives and pressures.
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
    ratings: tuple[Any, ...] = ()
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
        if self.data is None:
            raise ModelError("the model was not built from a model file: vary the Rotor "
                             "with a function instead", self.name)
        return ModelParameter(self.data, path, model_from_dict)

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
    from rotorsim.io.rating_build import rating_options
    from rotorsim.io.rolling_schema import validate_rolling_bearings
    from rotorsim.io.spec_build import build_spec

    table = validate_model(dict(data) if isinstance(data, Mapping) else data)
    rolling_tables = validate_rolling_bearings(table.rolling_bearings)
    analyses = validate_analyses(table.analyses)
    build.check_unique_tags(table, rolling_tables)
    src = None if source is None else Path(source)
    name = table.model.name or (src.stem if src is not None else "rotor")
    rotor, nodes = build.build_rotor(table, name, None if src is None else src.parent)
    rolling, points = build.build_rolling(rolling_tables, nodes)
    loads = build.build_loads(table, nodes)
    tags = tuple(rb.tag for rb in rolling)
    specs = {key: build_spec(t, loc, nodes, rotor, loads, tags)
             for key, loc, t in analyses}
    model = Model(name=name, rotor=rotor, loads=loads, analyses=specs,
                  description=table.model.description, source=src, rolling_bearings=rolling,
                  linearize=points, data=copy.deepcopy(dict(data)),
                  ratings=rating_options(rolling_tables))
    return _parameter_ranges(model)


def _parameter_ranges(model: Model) -> Model:
    """``periodic_parameter`` analyses with their ``start`` and ``stop`` in SI (a key path
    resolved and its range checked against the key's dimension)."""
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
