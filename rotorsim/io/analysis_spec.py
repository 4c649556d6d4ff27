"""What every analysis spec of a model file shares: swept grids, the model's loads and the
:class:`AnalysisSpec` base with its model-file (TOML) form.

A model file names analyses (``[analyses.campbell]`` with ``type = "campbell"``); the
loader turns each into a frozen spec, in SI units with node numbers resolved: the
analyses run on the linearised rotor in :mod:`rotorsim.io.linear_specs`, the long,
resumable ones in :mod:`rotorsim.io.long_specs`, the names of all in
:mod:`rotorsim.io.spec_registry`. Specs are plain data and import no analysis;
:func:`~rotorsim.io.analysis_runners.run_analysis` maps a spec onto the matching
``rotorsim`` call.

Examples
--------
>>> grid = Grid(start=0.0, stop=100.0, num=5)
>>> grid.array().tolist()
[0.0, 25.0, 50.0, 75.0, 100.0]
>>> grid.shrunk(3).num
3
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Any, ClassVar, Literal

import numpy as np

from rotorsim.assembly.loads import STANDARD_GRAVITY
from rotorsim.elements.base import FloatArray
from rotorsim.options.flat import flat_key, group_from_flat, to_flat
from rotorsim.options.group import OptionGroup


@dataclass(frozen=True)
class Grid:
    """Values of a swept quantity in SI: a range ``start..stop`` with ``num`` points, or
    explicit ``values``.

    Parameters
    ----------
    start, stop : float
        Ends of the range (SI).
    num : int
        Number of points (>= 1).
    spacing : {"linear", "log"}
        Linear or logarithmic spacing of the range.
    values : tuple of float, optional
        Explicit values; when given, the range fields are ignored.
    """

    start: float = 0.0
    stop: float = 0.0
    num: int = 1
    spacing: Literal["linear", "log"] = "linear"
    values: tuple[float, ...] | None = None

    def array(self) -> FloatArray:
        """The values as a float array."""
        if self.values is not None:
            return np.array(self.values, dtype=float)
        if self.spacing == "log":
            return np.geomspace(self.start, self.stop, self.num)
        return np.linspace(self.start, self.stop, self.num)

    def shrunk(self, num: int) -> Grid:
        """Copy with at most ``num`` points spanning the same range."""
        if self.values is not None:
            if len(self.values) <= num:
                return self
            index = np.unique(np.linspace(0, len(self.values) - 1, num).round().astype(int))
            return Grid(values=tuple(self.values[i] for i in index))
        return Grid(self.start, self.stop, min(self.num, num), self.spacing)

    def to_toml(self) -> dict[str, Any] | list[float]:
        """Model-file form: a table ``{start, stop, num, spacing}`` or a list of values."""
        if self.values is not None:
            return list(self.values)
        return {"start": self.start, "stop": self.stop, "num": self.num,
                "spacing": self.spacing}


Unbalance = tuple[tuple[int, float, float], ...]
"""``(node, magnitude [kg m], phase [rad])`` of each unbalance."""


@dataclass(frozen=True)
class Loads:
    """Loads of a model file.

    Parameters
    ----------
    gravity : float or None
        Acceleration of gravity [m/s^2]; ``None`` switches it off.
    gravity_direction : (3,) tuple
        Direction in which gravity acts (x, y, z).
    unbalance : tuple of (node, magnitude, phase)
        Unbalance distribution [kg m, rad].
    point_loads : tuple of (node, dof, value)
        Static forces [N] and moments [N m].
    """

    gravity: float | None = STANDARD_GRAVITY
    gravity_direction: tuple[float, float, float] = (0.0, -1.0, 0.0)
    unbalance: Unbalance = ()
    point_loads: tuple[tuple[int, str, float], ...] = ()


GroupClass = type[OptionGroup]


@dataclass(frozen=True, kw_only=True)
class AnalysisSpec:
    """Options shared by all analyses: a description and what to report.

    A spec may hold option groups of :mod:`rotorsim.options` (the groups of its
    ``rotorsim`` verb); ``FILE_OPTIONS`` names, per group attribute, the group fields a
    model file gives as flat keys (``harmonics = 6`` for ``Harmonics.count``;
    :mod:`rotorsim.options.flat`). :meth:`from_flat`, :meth:`with_flat` and
    :meth:`to_toml` convert between the two forms.

    Parameters
    ----------
    description : str
        Free text.
    units : {"rpm", "Hz", "rad/s"}
        Unit of speeds and frequencies in printed summaries and figures.
    nodes : tuple of int, optional
        Nodes to report (responses, orbits); default chosen by the reporter.
    dofs : tuple of str
        DOFs to report at those nodes.
    """

    type: ClassVar[str] = ""
    FILE_OPTIONS: ClassVar[dict[str, tuple[str, ...]]] = {}
    description: str = ""
    units: str = "rpm"
    nodes: tuple[int, ...] | None = None
    dofs: tuple[str, ...] = ("ux", "uy")

    @classmethod
    def option_groups(cls) -> dict[str, GroupClass]:
        """``{attribute: group class}`` of the groups a model file sets by flat keys."""
        defaults: dict[str, Any] = {f.name: f.default for f in fields(cls)}
        return {attr: defaults[attr].__class__ for attr in cls.FILE_OPTIONS}

    @classmethod
    def flat_keys(cls) -> dict[str, tuple[str, str]]:
        """``{flat key: (group attribute, field)}`` of the group fields in model files."""
        groups = cls.option_groups()
        return {flat_key(groups[attr], name): (attr, name)
                for attr, names in cls.FILE_OPTIONS.items() for name in names}

    @classmethod
    def option_keys(cls) -> tuple[str, ...]:
        """The keys of a model-file table of this analysis besides the common ones: the
        spec's own fields and the flat keys of its groups."""
        return (*(f.name for f in fields(cls) if f.name not in cls.FILE_OPTIONS),
                *cls.flat_keys())

    @classmethod
    def from_flat(cls, **values: Any) -> AnalysisSpec:
        """The spec from its own fields and flat group keys (``harmonics=6``, ...)."""
        return cls._split(None, values)

    def with_flat(self, **changes: Any) -> AnalysisSpec:
        """A copy with spec fields or flat group keys changed."""
        return type(self)._split(self, changes)

    @classmethod
    def _split(cls, base: AnalysisSpec | None, values: dict[str, Any]) -> AnalysisSpec:
        keys, groups = cls.flat_keys(), cls.option_groups()
        plain = {k: v for k, v in values.items() if k not in keys}
        for attr, group in groups.items():
            mine = {k: v for k, v in values.items() if keys.get(k, ("",))[0] == attr}
            if mine:
                start = getattr(base, attr) if base is not None else None
                plain[attr] = group_from_flat(group, mine, start)
        return replace(base, **plain) if base is not None else cls(**plain)

    def to_toml(self) -> dict[str, Any]:
        """Model-file form in SI numbers (``None`` entries left out; the groups' fields
        as flat keys when not at their defaults)."""
        out: dict[str, Any] = {"type": self.type}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in self.FILE_OPTIONS:
                out.update(to_flat(value, self.FILE_OPTIONS[f.name]))
                continue
            if value is None or (f.name == "description" and not value):
                continue
            out[f.name] = _toml_value(f.name, value)
        return out


def _toml_value(name: str, value: Any) -> Any:
    if isinstance(value, Grid) or hasattr(value, "to_toml"):  # also a transient's drive
        return value.to_toml()
    if name == "unbalance":
        return [{"node": n, "magnitude": me, "phase": a} for n, me, a in value]
    if name == "inputs":
        return [{"node": n, "dof": dof} for n, dof in value]
    return list(value) if isinstance(value, tuple) else value
