"""Option-group fields as flat keys: the form of model files and the command line.

A model file writes ``harmonics = 6`` and ``max_points = 600`` where the API takes
``harmonics=rs.Harmonics(6)`` and ``continuation=rs.ContinuationOptions(max_points=600)``.
The flat key of a field is its metadata ``key`` (``Harmonics.count`` is ``harmonics``,
``Checkpointing.every`` is ``checkpoint_every``) or its name; its metadata ``file`` is the
type of its value in a file (fields without one are not written in files), ``none`` the
word that stands for None (``stability = "none"``).

Examples
--------
>>> from rotorsim.options import ContinuationOptions, Harmonics, StabilityOptions
>>> flat_key(Harmonics, "count")
'harmonics'
>>> group_from_flat(StabilityOptions, {"stability": "none"})
StabilityOptions(method=None, modes='auto', tol=None, bifurcations=True, beyond=100)
>>> to_flat(ContinuationOptions(max_points=600), ("max_step", "max_points"))
{'max_points': 600}
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping
from typing import Any, TypeVar

from rotorsim.options.group import OptionGroup

G = TypeVar("G", bound=OptionGroup)


def option_field(cls: type[OptionGroup], name: str) -> dataclasses.Field[Any]:
    """The dataclass field ``name`` of the group ``cls``."""
    for f in dataclasses.fields(cls):  # type: ignore[arg-type]
        if f.name == name:
            return f
    raise KeyError(f"{cls.__name__} has no field {name!r}")


def flat_key(cls: type[OptionGroup], name: str) -> str:
    """The flat key of field ``name`` (metadata ``key``, else the name)."""
    return str(option_field(cls, name).metadata.get("key") or name)


def group_from_flat(cls: type[G], values: Mapping[str, Any], base: G | None = None) -> G:
    """A group (``base`` or the defaults) with the fields given by flat ``values`` (keys
    of ``cls`` only; the ``none`` word read as None)."""
    changes: dict[str, Any] = {}
    for f in dataclasses.fields(cls):  # type: ignore[arg-type]
        key = str(f.metadata.get("key") or f.name)
        if key in values:
            value = values[key]
            none = f.metadata.get("none")
            changes[f.name] = None if none is not None and value == none else value
    start = base if base is not None else cls()
    return dataclasses.replace(start, **changes) if changes else start  # type: ignore[type-var]


def to_flat(group: OptionGroup, names: Iterable[str]) -> dict[str, Any]:
    """``{flat key: value}`` of the fields ``names`` that differ from their default (None
    written as the ``none`` word)."""
    given = group.given()
    out: dict[str, Any] = {}
    for name in names:
        if name in given:
            f = option_field(type(group), name)
            value = given[name]
            out[flat_key(type(group), name)] = f.metadata.get("none") if value is None \
                else list(value) if isinstance(value, tuple) else value
    return out
