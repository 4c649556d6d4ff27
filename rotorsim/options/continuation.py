"""The branch-following settings of a periodic run: :class:`ContinuationOptions`."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

from rotorsim.options.group import OptionGroup, about, check_count, check_positive

if TYPE_CHECKING:
    from rotorsim.solvers.continuation import Continuation


@dataclass(frozen=True)
class ContinuationOptions(OptionGroup):
    """Pseudo-arclength continuation of :func:`~rotorsim.periodic` and
    :func:`~rotorsim.periodic_parameter` (``continuation=rs.ContinuationOptions(...)``).

    Steps are scaled arclengths: the parameter range counts 1 and each DOF's scale is its
    typical static displacement, so the steps are fractions of the range. Fields left at
    None take the verb's default (``periodic``: ``max_step=0.05``, ``max_points=1000``;
    ``periodic_parameter``: ``max_step=0.05``, ``max_points=200``).

    Parameters
    ----------
    step : float, optional
        First scaled step (default a quarter of ``max_step``; at most ``max_step``).
    max_step : float, optional
        Largest scaled step.
    max_points : int, optional
        Points of the branch, the first one included (>= 2).
    tol : float
        Corrector tolerance on the scaled residual (also of the first point).
    solver : Continuation, optional
        The full options of :class:`rotorsim.solvers.continuation.Continuation` for
        experts, instead of ``step``, ``max_step`` and ``max_points``; its bounds and
        direction are replaced by the verb's range, its scales kept when not the default 1.

    Examples
    --------
    >>> ContinuationOptions(max_step=0.1).max_points is None     # the verb's default
    True
    >>> ContinuationOptions(max_step=-1.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rotorsim.options.group.OptionError: ContinuationOptions.max_step: must be a positive ...
    """

    FROM_VERB: ClassVar[tuple[str, ...]] = ("max_step", "max_points")
    HINT: ClassVar[str] = (" (a solver Continuation goes into "
                           "rs.ContinuationOptions(solver=...))")

    step: float | None = field(
        default=None, metadata=about("first scaled arclength step (default max_step / 4)",
                                     file=float, gt=0))
    max_step: float | None = field(
        default=None, metadata=about("largest scaled arclength step", file=float, gt=0))
    max_points: int | None = field(
        default=None, metadata=about("largest number of branch points", file=int, ge=2))
    tol: float = field(
        default=1e-10, metadata=about("corrector tolerance on the scaled residual",
                                      file=float, gt=0))
    solver: Continuation | None = field(
        default=None, metadata=about("full solver options (experts)"))

    def resolved(self, defaults: ContinuationOptions) -> ContinuationOptions:
        """The verb's defaults filled in, unless a solver brings its own."""
        return self if self.solver is not None else super().resolved(defaults)

    def __post_init__(self) -> None:
        for name in ("step", "max_step"):
            value = getattr(self, name)
            if value is not None and not check_positive(value):
                raise self._fail(name, f"must be a positive number, got {value!r}")
        if self.max_points is not None and not check_count(self.max_points, 2):
            raise self._fail("max_points", f"must be an integer >= 2, got "
                                           f"{self.max_points!r}")
        if not (_real(self.tol) and math.isfinite(self.tol) and self.tol > 0):
            raise self._fail("tol", f"must be a positive number, got {self.tol!r}")
        if self.solver is not None:
            if not hasattr(self.solver, "max_step") or isinstance(self.solver, OptionGroup):
                raise self._fail("solver", "expected a rotorsim.solvers.continuation."
                                           f"Continuation, got {type(self.solver).__name__}")
            given = [n for n in ("step", "max_step", "max_points")
                     if getattr(self, n) is not None]
            if given:
                raise self._fail("solver", f"give the solver or {', '.join(given)}, not "
                                           "both (the solver has its own steps and points)")


def _real(value: Any) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)
