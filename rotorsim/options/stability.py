"""Floquet stability and bifurcations of a periodic run: :class:`StabilityOptions`."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from typing import ClassVar

from rotorsim.options.group import OptionGroup, about

METHODS = ("auto", "hill", "hsu", "variational")
"""Floquet methods (:mod:`rotorsim.analyses.periodic.stability`)."""


@dataclass(frozen=True)
class StabilityOptions(OptionGroup):
    """Stability of the points of a periodic branch in :func:`~rotorsim.periodic` and
    :func:`~rotorsim.periodic_parameter` (``stability="hsu"``, ``stability=None`` or
    ``stability=rs.StabilityOptions(...)``).

    Parameters
    ----------
    method : {"auto", "hill", "hsu", "variational"} or None
        Floquet method: ``"auto"`` is Hill's method on small (or reduced) models, Hsu's
        otherwise; None skips the multipliers.
    modes : "auto", int or None
        Fixed-interface modes of the Craig-Bampton stability model (None: the full system;
        ``"auto"``: the full system when small, else the modes below ``1.5 H omega_max``).
    tol : float, optional
        A point is stable when ``max |mu| < 1 + tol`` (default the verb's, 1e-5).
    bifurcations : bool
        Detect and locate folds, branch points, period doublings and Neimark-Sacker
        points.
    beyond : int
        Tori only: shaft revolutions of the transient run where a torus loses stability,
        to find what the motion is there (two fifths settle, three fifths are recorded:
        :func:`~rotorsim.analyses.quasiperiodic.beyond.motion_beyond`); 0 skips it.

    Examples
    --------
    >>> StabilityOptions("hsu", modes=12).method
    'hsu'
    >>> StabilityOptions(modes=-3)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rotorsim.options.group.OptionError: StabilityOptions.modes: must be None, 'auto' or an ...
    """

    FROM_VERB: ClassVar[tuple[str, ...]] = ("tol",)
    SHORTCUT: ClassVar[str | None] = "method"

    method: str | None = field(
        default="auto", metadata=about("Floquet method: auto, hill, hsu or variational "
                                       "(none: skip)", key="stability", file=str,
                                       choices=METHODS, none="none"))
    modes: int | str | None = field(
        default="auto", metadata=about("fixed-interface modes of the stability model "
                                       "(None: full system)"))
    tol: float | None = field(
        default=None, metadata=about("stable when max |mu| < 1 + tol (default 1e-5)",
                                     key="stability_tol", file=float, ge=0))
    bifurcations: bool = field(
        default=True, metadata=about("detect and locate bifurcations", file=bool))
    beyond: int = field(
        default=100, metadata=about("tori: revolutions of the transient run where a torus "
                                    "loses stability (0: none)", file=int, ge=0))

    def __post_init__(self) -> None:
        if self.method is not None and self.method not in METHODS:
            raise TypeError(f"unknown stability method {self.method!r}; valid: "
                            f"{', '.join(METHODS)} or None")
        modes = self.modes
        whole = isinstance(modes, numbers.Integral) and not isinstance(modes, bool) \
            and int(modes) >= 0
        if not (modes is None or modes == "auto" or whole):
            raise self._fail("modes", f"must be None, 'auto' or an integer >= 0, got "
                                      f"{modes!r}")
        tol = self.tol
        if tol is not None and not (isinstance(tol, numbers.Real) and not isinstance(
                tol, bool) and math.isfinite(tol) and tol >= 0):
            raise self._fail("tol", f"must be finite and >= 0, got {tol!r}")
        beyond = self.beyond
        if not (isinstance(beyond, numbers.Integral) and not isinstance(beyond, bool)
                and (beyond == 0 or beyond >= 10)):
            raise self._fail("beyond", f"must be 0 or an integer >= 10 revolutions, got "
                                       f"{beyond!r}")
        if not isinstance(self.bifurcations, bool):
            raise self._fail("bifurcations", f"must be True or False, got "
                                             f"{self.bifurcations!r}")
