"""Parameter spaces of a sweep and its result.

A sweep evaluates a model at the points of a :class:`Grid` (cartesian product of
parameter values) or of a :class:`Sample` (random draws from :class:`Normal` or
:class:`Uniform` distributions, seeded). Every point is a mapping ``name -> float``;
the points are numbered ``0 .. n_points - 1`` in a fixed order, and the results of
point ``i`` are stored in row ``i`` of every output of :class:`SweepResult`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError, Status

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@runtime_checkable
class Distribution(Protocol):
    """A distribution a :class:`Sample` can draw from."""

    def draw(self, rng: np.random.Generator, n: int) -> FloatArray: ...

    def describe(self) -> dict[str, Any]: ...


def _finite(value: float, name: str, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.number) \
            or not math.isfinite(float(value)):
        raise ModelError(f"{name} must be a finite number, got {value!r}", where)
    return float(value)


@dataclass(frozen=True)
class Normal:
    """Normal (Gaussian) distribution of mean ``mean`` and standard deviation ``std`` >= 0."""

    mean: float
    std: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "mean", _finite(self.mean, "mean", "Normal"))
        object.__setattr__(self, "std", _finite(self.std, "std", "Normal"))
        if self.std < 0:
            raise ModelError(f"std must be >= 0, got {self.std}", "Normal")

    def draw(self, rng: np.random.Generator, n: int) -> FloatArray:
        return rng.normal(self.mean, self.std, n)

    def describe(self) -> dict[str, Any]:
        return {"distribution": "normal", "mean": self.mean, "std": self.std}


@dataclass(frozen=True)
class Uniform:
    """Uniform distribution on ``[low, high)``, ``low < high``."""

    low: float
    high: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "low", _finite(self.low, "low", "Uniform"))
        object.__setattr__(self, "high", _finite(self.high, "high", "Uniform"))
        if not self.low < self.high:
            raise ModelError(f"need low < high, got [{self.low}, {self.high}]", "Uniform")

    def draw(self, rng: np.random.Generator, n: int) -> FloatArray:
        return rng.uniform(self.low, self.high, n)

    def describe(self) -> dict[str, Any]:
        return {"distribution": "uniform", "low": self.low, "high": self.high}


def _check_names(names: tuple[str, ...], where: str) -> None:
    if not names:
        raise ModelError("needs at least one parameter", where)
    for name in names:
        if not isinstance(name, str) or not name or "/" in name:
            raise ModelError(f"parameter names must be non-empty strings without '/',"
                             f" got {name!r}", where)


def _frozen(array: NDArray[Any]) -> NDArray[Any]:
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class Grid:
    """Cartesian product of parameter values; the last parameter varies fastest.

    Parameters
    ----------
    parameters : mapping of str to 1-D array_like
        Values of each parameter (SI units), at least one each, finite.

    Examples
    --------
    >>> g = Grid({"bearing_k": [1e6, 1e7], "speed": [0.0, 100.0, 200.0]})
    >>> g.shape, g.n_points, g.point(4)
    ((2, 3), 6, {'bearing_k': 10000000.0, 'speed': 100.0})
    """

    parameters: Mapping[str, ArrayLike]
    names: tuple[str, ...] = field(init=False)
    axes: tuple[FloatArray, ...] = field(init=False)
    kind = "grid"

    def __post_init__(self) -> None:
        if not isinstance(self.parameters, Mapping):
            raise ModelError("parameters must be a mapping name -> values", "Grid")
        names = tuple(self.parameters)
        _check_names(names, "Grid")
        axes = []
        for name in names:
            try:
                axis = np.array(self.parameters[name], dtype=float)
            except (TypeError, ValueError) as exc:
                raise ModelError(f"values must be numbers: {exc}", f"Grid['{name}']") from exc
            if axis.ndim != 1 or axis.size == 0 or not np.all(np.isfinite(axis)):
                raise ModelError("values must be a non-empty 1-D array of finite numbers,"
                                 f" got {self.parameters[name]!r}", f"Grid['{name}']")
            axes.append(_frozen(axis))
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "axes", tuple(axes))
        object.__setattr__(self, "parameters", dict(zip(names, self.axes, strict=True)))

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(a.size for a in self.axes)

    @property
    def n_points(self) -> int:
        return math.prod(self.shape)

    @cached_property
    def values(self) -> FloatArray:
        """Parameter values of every point, ``(n_points, n_params)``."""
        mesh = np.meshgrid(*self.axes, indexing="ij")
        return _frozen(np.stack([m.ravel() for m in mesh], axis=1))

    def point(self, index: int) -> dict[str, float]:
        """Parameters of point ``index`` as ``{name: value}``."""
        return dict(zip(self.names, (float(v) for v in self.values[index]), strict=True))

    def describe(self) -> dict[str, Any]:
        """JSON-ready definition (used in the sweep fingerprint)."""
        return {"kind": "grid", "names": list(self.names),
                "axes": [a.tolist() for a in self.axes]}


@dataclass(frozen=True, eq=False)
class Sample:
    """``n`` random points, each parameter drawn independently from its distribution.

    Draws come from ``numpy.random.default_rng(seed)``, parameter by parameter in the
    order given, so the same ``(n, distributions, seed)`` gives the same points.

    Parameters
    ----------
    n : int
        Number of points (>= 1).
    distributions : mapping of str to Normal or Uniform
    seed : int
        Non-negative integer seed (required: a sweep must be reproducible to be resumed).

    Examples
    --------
    >>> s = Sample(4, {"k": Normal(1e6, 5e4), "m": Uniform(9.0, 11.0)}, seed=1)
    >>> s.values.shape, s.shape, bool(np.all((s.values[:, 1] >= 9) & (s.values[:, 1] < 11)))
    ((4, 2), None, True)
    """

    n: int
    distributions: Mapping[str, Distribution]
    seed: int
    names: tuple[str, ...] = field(init=False)
    values: FloatArray = field(init=False, repr=False)
    kind = "sample"
    shape = None

    def __post_init__(self) -> None:
        if isinstance(self.n, bool) or not isinstance(self.n, int | np.integer) or self.n < 1:
            raise ModelError(f"n must be an integer >= 1, got {self.n!r}", "Sample.n")
        if isinstance(self.seed, bool) or not isinstance(self.seed, int | np.integer) \
                or self.seed < 0:
            raise ModelError(f"seed must be a non-negative integer, got {self.seed!r}",
                             "Sample.seed")
        if not isinstance(self.distributions, Mapping):
            raise ModelError("distributions must be a mapping name -> distribution", "Sample")
        names = tuple(self.distributions)
        _check_names(names, "Sample")
        for name, dist in self.distributions.items():
            if not isinstance(dist, Distribution):
                raise ModelError(f"unknown distribution {dist!r}; use Normal(mean, std) or"
                                 " Uniform(low, high)", f"Sample['{name}']")
        rng = np.random.default_rng(int(self.seed))
        values = np.stack([np.asarray(self.distributions[k].draw(rng, int(self.n)), dtype=float)
                           for k in names], axis=1)
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "values", _frozen(values))
        object.__setattr__(self, "distributions", dict(self.distributions))

    @property
    def n_points(self) -> int:
        return int(self.n)

    def point(self, index: int) -> dict[str, float]:
        """Parameters of point ``index`` as ``{name: value}``."""
        return dict(zip(self.names, (float(v) for v in self.values[index]), strict=True))

    def describe(self) -> dict[str, Any]:
        """JSON-ready definition (used in the sweep fingerprint)."""
        return {"kind": "sample", "n": int(self.n), "seed": int(self.seed),
                "distributions": {k: self.distributions[k].describe() for k in self.names}}


ParameterSpace = Grid | Sample


@dataclass(frozen=True, eq=False)
class PointRecord:
    """Outcome of one sweep point, as sent from a worker to the process that stores it.

    ``outputs`` is ``None`` when the point failed; ``message`` then says why.
    ``wall_time`` is the time spent on the point [s].
    """

    index: int
    outputs: dict[str, NDArray[Any]] | None
    status: Status
    message: str = ""
    wall_time: float = 0.0


@dataclass(frozen=True, eq=False)
class SweepResult:
    """Outputs of a model evaluated at every point of a parameter space.

    Attributes
    ----------
    kind : {"grid", "sample"}
        Kind of parameter space.
    names : tuple of str
        Parameter names.
    values : array (n_points, n_params)
        Parameter values of every point (SI).
    shape : tuple of int or None
        Grid shape (one entry per parameter) for a grid, ``None`` for a sample.
    outputs : dict of str to array (n_points, ...)
        Every output of the evaluate function; NaN where a point failed or was not run.
    point_status : int array (n_points,)
        :class:`~rotorsim.errors.Status` of every point (``SKIPPED``: not run yet).
    messages : tuple of str
        Failure message of every point (empty when OK).
    point_time : array (n_points,)
        Wall time spent on every point [s].
    fingerprint : str
        Hash of the sweep definition (space, model, apply and evaluate functions).

    Examples
    --------
    >>> r = SweepResult(kind="grid", names=("a", "b"),
    ...                 values=Grid({"a": [1.0, 2.0], "b": [0.0, 1.0, 2.0]}).values,
    ...                 shape=(2, 3), outputs={"y": np.arange(6.0)},
    ...                 point_status=np.zeros(6, dtype=np.int64))
    >>> r.reshape("y")[1].tolist(), r.axis("b").tolist()
    ([3.0, 4.0, 5.0], [0.0, 1.0, 2.0])
    """

    kind: str
    names: tuple[str, ...]
    values: FloatArray
    shape: tuple[int, ...] | None
    outputs: dict[str, NDArray[Any]]
    point_status: IntArray
    messages: tuple[str, ...] = ()
    point_time: FloatArray | None = None
    fingerprint: str = ""
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)

    @property
    def n_points(self) -> int:
        return int(self.values.shape[0])

    @property
    def ok(self) -> NDArray[np.bool_]:
        """Mask of the points that ran and succeeded."""
        return np.asarray(self.point_status == int(Status.OK))

    def parameter(self, name: str) -> FloatArray:
        """Values ``(n_points,)`` of parameter ``name``."""
        return self.values[:, self._column(name)]

    def axis(self, name: str) -> FloatArray:
        """Grid values of parameter ``name`` (its 1-D axis); grids only."""
        shape = self._grid_shape("axis")
        k = self._column(name)
        index = tuple(slice(None) if j == k else 0 for j in range(len(shape)))
        return self.values.reshape(*shape, len(self.names))[index][..., k]

    def reshape(self, name: str) -> NDArray[Any]:
        """Output ``name`` reshaped to ``grid shape + output shape``; grids only."""
        shape = self._grid_shape("reshape")
        if name not in self.outputs:
            raise ModelError(f"no output {name!r}; outputs are {sorted(self.outputs)}",
                             "SweepResult.reshape")
        data = self.outputs[name]
        return data.reshape(*shape, *data.shape[1:])

    def to_dict(self) -> dict[str, Any]:
        """Plain dictionary of the result (numpy arrays kept as arrays)."""
        return {
            "kind": self.kind, "names": list(self.names), "values": self.values,
            "shape": None if self.shape is None else list(self.shape),
            "outputs": dict(self.outputs), "point_status": self.point_status,
            "messages": list(self.messages), "point_time": self.point_time,
            "fingerprint": self.fingerprint, "options": dict(self.options),
            "stats": dict(self.stats), "status": int(self.status),
            "summary": dict(self.summary),
        }

    def _column(self, name: str) -> int:
        if name not in self.names:
            raise ModelError(f"no parameter {name!r}; parameters are {list(self.names)}",
                             "SweepResult")
        return self.names.index(name)

    def _grid_shape(self, method: str) -> tuple[int, ...]:
        if self.shape is None:
            raise ModelError(f"{method} needs a grid sweep; this is a {self.kind}",
                             f"SweepResult.{method}")
        return self.shape

