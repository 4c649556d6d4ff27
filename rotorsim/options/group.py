"""What every option group shares: documented fields, validation errors that name the
field, shortcut values, verb defaults and fields a verb does not use.

An option group is a frozen dataclass whose fields carry, besides their default, a one-line
help text and a unit in their metadata (:func:`about`), so that the model-file schema and
the command line can describe the same option without writing it again.
Its ``__post_init__`` validates each field alone and raises :class:`OptionError` with
``where = "<Group>.<field>"``.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
import os
from collections.abc import Sequence
from typing import Any, ClassVar, TypeVar

from rotorsim.errors import ModelError

G = TypeVar("G", bound="OptionGroup")


class OptionError(ModelError):
    """A bad value of an option field; ``reason`` is the message without ``where``, so that
    a verb can name its own keyword when it built the group from a shortcut value."""

    def __init__(self, reason: str, where: str) -> None:
        self.reason = reason
        super().__init__(reason, where)


def about(help: str, unit: str = "", **extra: Any) -> dict[str, Any]:
    """Metadata of an option field: ``help`` (one line, also the command-line help),
    ``unit`` (SI, "" when dimensionless) and ``extra`` entries (e.g. ``key``: the flat
    name of the option in model files and on the command line, when not the field's)."""
    return {"help": help, "unit": unit, **extra}


class OptionGroup:
    """Base of the option groups (frozen dataclasses).

    ``SHORTCUT`` names the field that a plain value given to the verb's keyword fills (e.g.
    ``harmonics=8`` is ``Harmonics(count=8)``); None when the keyword takes only the group.
    ``FROM_VERB`` names the fields whose default depends on the verb.
    """

    SHORTCUT: ClassVar[str | None] = None
    HINT: ClassVar[str] = ""
    FROM_VERB: ClassVar[tuple[str, ...]] = ()
    """Fields whose None means "the verb's default" (:meth:`resolved`)."""

    def _fail(self, name: str, reason: str) -> OptionError:
        return OptionError(reason, f"{type(self).__name__}.{name}")

    @classmethod
    def coerce(cls: type[G], value: Any, where: str) -> G:
        """``value`` as a group: the group itself, None (the defaults), or a plain value for
        the ``SHORTCUT`` field; errors then name ``where`` (the verb's keyword)."""
        if isinstance(value, cls):
            return value
        if cls.SHORTCUT is None:
            if value is None:
                return cls()
            raise ModelError(f"expected rs.{cls.__name__} or None, got "
                             f"{type(value).__name__}{cls.HINT}", where)
        if isinstance(value, OptionGroup):
            raise ModelError(f"expected rs.{cls.__name__}, got {type(value).__name__}", where)
        try:
            return cls(**{cls.SHORTCUT: value})
        except OptionError as exc:
            raise ModelError(exc.reason, where) from None

    def given(self) -> dict[str, Any]:
        """The fields that differ from the class defaults."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)  # type: ignore[arg-type]
                if not _same(getattr(self, f.name), f.default)}

    def resolved(self: G, defaults: G) -> G:
        """A copy whose ``FROM_VERB`` fields left at None take the value of ``defaults``
        (the verb's own defaults, written once in the verb)."""
        changes = {name: getattr(defaults, name) for name in self.FROM_VERB
                   if getattr(self, name) is None}
        return dataclasses.replace(self, **changes)  # type: ignore[type-var]

    def merged(self: G, where: str, **shortcuts: Any) -> G:
        """A copy with the verb's shortcut keywords (e.g. ``unbalance=``, ``nodes=``) put in
        their fields; a ModelError naming ``<where>.<keyword>`` when a field is given both
        as a keyword and in the group, or when a shortcut value is bad."""
        changes: dict[str, Any] = {}
        defaults = {f.name: f.default for f in dataclasses.fields(self)}  # type: ignore[arg-type]
        for name, value in shortcuts.items():
            if _unset(value, defaults[name]):
                continue
            if name in self.given():
                raise ModelError(f"given twice: as {name}= and in {type(self).__name__}"
                                 f"({name}=...); give it once", f"{where}.{name}")
            changes[name] = value
        if not changes:
            return self
        try:
            return dataclasses.replace(self, **changes)  # type: ignore[type-var]
        except OptionError as exc:
            field = exc.where.rsplit(".", 1)[-1] if exc.where else ""
            raise ModelError(exc.reason, f"{where}.{field}") from None

    def refuse(self, names: Sequence[str], where: str, verb: str) -> None:
        """A ModelError when one of the fields ``names`` (not used by ``verb``) is given."""
        given = self.given()
        for name in names:
            if name in given:
                raise ModelError(f"not an option of {verb}; leave it unset",
                                 f"{where}.{name}")


def _unset(value: Any, default: Any) -> bool:
    """Whether a shortcut keyword was left unset: None, or empty when the field's default
    is an empty tuple (``unbalance=()``)."""
    if value is None:
        return True
    return default == () and isinstance(value, Sequence) and not isinstance(value, str) \
        and len(value) == 0


def _same(value: Any, default: Any) -> bool:
    if value is default:
        return True
    if default is None or value is None:
        return False
    try:
        return bool(value == default)
    except (TypeError, ValueError):  # e.g. arrays
        return False


def check_count(value: Any, least: int) -> bool:
    """Whether ``value`` is an integer (not a bool) ``>= least`` (``4.0`` counts)."""
    if isinstance(value, bool):
        return False
    try:
        return bool(int(value) == value and value >= least)
    except (TypeError, ValueError, OverflowError):
        return False


def check_positive(value: Any) -> bool:
    """Whether ``value`` is a finite real number > 0 (not a bool)."""
    return (isinstance(value, numbers.Real) and not isinstance(value, bool)
            and math.isfinite(value) and float(value) > 0)


def check_path(value: Any) -> bool:
    """Whether ``value`` is None, a string or an ``os.PathLike``."""
    return value is None or isinstance(value, str | os.PathLike)
