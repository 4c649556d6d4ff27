"""The loads of a transient or periodic run: :class:`Excitation`."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from rotorsim.options.group import OptionGroup, about

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from rotorsim.analyses.periodic.excitation import HarmonicBase
    from rotorsim.analyses.transient.loads import BaseExcitation

STANDARD_GRAVITY = 9.80665
"""Standard acceleration of gravity [m/s^2] (the value of
:data:`rotorsim.assembly.loads.STANDARD_GRAVITY`)."""


@dataclass(frozen=True)
class Excitation(OptionGroup):
    """What drives the rotor in :func:`~rotorsim.transient`, :func:`~rotorsim.periodic`
    and :func:`~rotorsim.periodic_parameter` (``excitation=rs.Excitation(...)``).

    Nodes and DOFs are checked against the model by the verb (errors name
    ``unbalance[i]``, ``loads[i]``, ``gravity``, ``direction``).

    Parameters
    ----------
    unbalance : sequence of (node, me, angle)
        Unbalances [kg m, rad] rotating with the shaft angle (harmonic 1 of the speed in a
        periodic run). The verbs also take them as their ``unbalance=`` keyword (not both).
    gravity : float or None
        Acceleration of gravity [m/s^2] (default standard gravity 9.80665); None for none.
    direction : 3 floats
        Direction in which gravity acts (normalised), default ``-y``.
    loads : sequence of (node, dof, value)
        Constant point forces [N] and moments [N m] (``dof`` one of ``"ux"`` .. ``"rz"``);
        harmonic 0 of a periodic run.
    base : HarmonicBase or BaseExcitation, optional
        Motion of the housing: :class:`~rotorsim.HarmonicBase` (a harmonic displacement,
        periodic runs) or :class:`~rotorsim.BaseExcitation` (an acceleration ``a_b(t)``,
        transients); coordinates are then relative to the base (seed 002 eq 3.43).
        Not used by ``periodic_parameter``.
    forces : callable, optional
        ``forces(t) -> array (n_free,)`` of extra loads on the free DOFs [N, N m]
        (``system.dofs_of(node, dofs)`` gives indices); transients only.

    Examples
    --------
    >>> Excitation(gravity=None, loads=[(3, "uy", -100.0)]).loads
    ((3, 'uy', -100.0),)
    >>> Excitation(forces=5.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rotorsim.options.group.OptionError: Excitation.forces: must be a callable forces(t) ...
    """

    unbalance: Sequence[tuple[int, float, float]] = field(
        default=(), metadata=about("unbalances (node, me, angle)", "kg m, rad"))
    gravity: float | None = field(
        default=STANDARD_GRAVITY, metadata=about("acceleration of gravity (None: none)", "m/s^2"))
    direction: ArrayLike = field(
        default=(0.0, -1.0, 0.0), metadata=about("direction in which gravity acts"))
    loads: Sequence[tuple[int, str, float]] = field(
        default=(), metadata=about("constant point loads (node, dof, value)", "N, N m"))
    base: HarmonicBase | BaseExcitation | None = field(
        default=None, metadata=about("housing (base) motion"))
    forces: Callable[[float], ArrayLike] | None = field(
        default=None, metadata=about("extra loads forces(t) on the free DOFs (transients)",
                                     "N, N m"))

    def __post_init__(self) -> None:
        for name in ("unbalance", "loads"):
            value = getattr(self, name)
            if isinstance(value, str | bytes) or not _iterable(value):
                raise self._fail(name, f"expected a sequence of (node, ...) entries, got "
                                       f"{value!r}")
            object.__setattr__(self, name, tuple(value))
        if isinstance(self.direction, list):
            object.__setattr__(self, "direction", tuple(self.direction))
        if self.forces is not None and not callable(self.forces):
            raise self._fail("forces", "must be a callable forces(t) -> array (n_free,) "
                                       f"[N], got {type(self.forces).__name__}")


def _iterable(value: Any) -> bool:
    try:
        iter(value)
    except TypeError:
        return False
    return True
