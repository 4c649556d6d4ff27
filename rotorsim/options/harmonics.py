"""The harmonic-balance discretisation of a periodic run: :class:`Harmonics`."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from rotorsim.options.group import OptionGroup, about, check_count, check_positive


@dataclass(frozen=True)
class Harmonics(OptionGroup):
    """Harmonics and time samples of :func:`~rotorsim.periodic` and
    :func:`~rotorsim.periodic_parameter` (``harmonics=8`` or
    ``harmonics=rs.Harmonics(8, samples=128)``).

    Parameters
    ----------
    count : int
        ``H >= 1`` harmonics of the fundamental, at least the harmonic of every forcing
        (checked by the verb, with the memory the discretisation needs).
    samples : int, optional
        AFT samples per period, ``N >= 2 H + 1`` (default ``2**ceil(log2(8 H))``; increase
        for hard contacts, check with ``harmonic_balance.sample_convergence``).
    fundamental : float, optional
        Order ``f = omega / W`` of the fundamental instead of the automatic one (e.g. half
        of it for a period-2 branch); every forcing order must be a multiple of it.
        ``periodic`` only.
    condense : bool
        Exact condensation onto the nonlinear DOFs (the full system is for checks).
        ``periodic`` only.

    Examples
    --------
    >>> Harmonics(8, samples=64)
    Harmonics(count=8, samples=64, fundamental=None, condense=True)
    >>> Harmonics(2, samples=3)
    Traceback (most recent call last):
    ...
    rotorsim.options.group.OptionError: Harmonics.samples: must be an integer >= 2 H + 1 = 5, got 3
    """

    SHORTCUT: ClassVar[str | None] = "count"

    count: int = field(
        default=10, metadata=about("number of harmonics H", key="harmonics", file=int,
                                   ge=1, le=200))
    samples: int | None = field(
        default=None, metadata=about("AFT samples per period (default 2**ceil(log2(8 H)))",
                                     file=int, ge=4))
    fundamental: float | None = field(
        default=None, metadata=about("order omega / W of the fundamental (default: from "
                                     "the forcing)", file=float, gt=0))
    condense: bool = field(
        default=True, metadata=about("exact condensation onto the nonlinear DOFs",
                                     file=bool))

    def __post_init__(self) -> None:
        if not check_count(self.count, 1):
            raise self._fail("count", f"must be a positive integer (harmonics of the "
                                      f"fundamental), got {self.count!r}")
        if self.samples is not None and not check_count(self.samples, 2 * self.count + 1):
            raise self._fail("samples", f"must be an integer >= 2 H + 1 = "
                                        f"{2 * self.count + 1}, got {self.samples!r}")
        if self.fundamental is not None and not check_positive(self.fundamental):
            raise self._fail("fundamental", f"must be a positive number, got "
                                            f"{self.fundamental!r}")
        if not isinstance(self.condense, bool):
            raise self._fail("condense", f"must be True or False, got {self.condense!r}")

