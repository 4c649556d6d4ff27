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

from dataclasses import dataclass, fields
from typing import Any, ClassVar, Literal

import numpy as np

from rotorsim.assembly.loads import STANDARD_GRAVITY
from rotorsim.elements.base import FloatArray


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


@dataclass(frozen=True, kw_only=True)
class AnalysisSpec:
    """Options shared by all analyses: a description and what to report.

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
    description: str = ""
    units: str = "rpm"
    nodes: tuple[int, ...] | None = None
    dofs: tuple[str, ...] = ("ux", "uy")

    def to_toml(self) -> dict[str, Any]:
        """Model-file form in SI numbers (``None`` entries left out)."""
        out: dict[str, Any] = {"type": self.type}
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None or (f.name == "description" and not value):
                continue
            out[f.name] = _toml_value(f.name, value)
        return out


def _toml_value(name: str, value: Any) -> Any:
    if isinstance(value, Grid):
        return value.to_toml()
    if name == "unbalance":
        return [{"node": n, "magnitude": me, "phase": a} for n, me, a in value]
    if name == "inputs":
        return [{"node": n, "dof": dof} for n, dof in value]
    return list(value) if isinstance(value, tuple) else value
