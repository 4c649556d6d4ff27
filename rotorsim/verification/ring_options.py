"""Options of :func:`~rotorsim.verification.ring_fe.ring_fe_roller_loads`, grouped by concern.

* :class:`MeshOptions`: the contact patches and the mesh of the rings;
* :class:`OuterRingSupport`: how the outer ring is held;
* :class:`NewtonOptions`: the Newton solve on the roller contacts.

The values are checked where they are used (:mod:`~rotorsim.verification.ring_model`), with
messages that name the option. :func:`grouped_options` turns the keywords these groups
replaced into a ``TypeError`` that names their new home.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

WHERE = "ring_fe_roller_loads"


@dataclass(frozen=True)
class MeshOptions:
    """Contact patches and mesh of the rings.

    Parameters
    ----------
    contact_half_width : float, optional
        Half-width ``a`` [m] of the raceway arc that carries a roller load; default a
        quarter of the thinner ring's radial thickness.
    mesh_size : float, optional
        Element size in the contact patches and at the raceways [m]; default ``a / 3``.
    max_size : float, optional
        Largest element size [m]; default a third of the thinner ring thickness.
    growth : float
        Size ratio of neighbouring elements in the graded zones (1 to 2).

    Examples
    --------
    >>> MeshOptions(mesh_size=3e-3, max_size=7e-3).growth
    1.3
    """

    contact_half_width: float | None = None
    mesh_size: float | None = None
    max_size: float | None = None
    growth: float = 1.3


@dataclass(frozen=True)
class OuterRingSupport:
    """Support of the outer ring.

    Parameters
    ----------
    kind : {"faces", "housing", "clamped"}
        ``"faces"``: a soft elastic support of the ring faces (the outer ring deforms
        freely); ``"housing"``: a Winkler housing on ``r = R_h``; ``"clamped"``: the outer
        surface fixed (module docstring of :mod:`~rotorsim.verification.ring_fe`).
    stiffness : float, optional
        Total lateral stiffness of the ``"faces"``/``"housing"`` support [N/m]; default
        ``1e-3 E b``.

    Examples
    --------
    >>> OuterRingSupport("housing", 6e8)
    OuterRingSupport(kind='housing', stiffness=600000000.0)
    """

    kind: str = "faces"
    stiffness: float | None = None


@dataclass(frozen=True)
class NewtonOptions:
    """Newton solve on the roller contacts.

    Parameters
    ----------
    tol : float
        Tolerance on the relative residual (> 0).
    max_iter : int
        Iteration limit (>= 1).
    """

    tol: float = 1e-10
    max_iter: int = 50


_GROUPS: dict[str, type] = {"mesh": MeshOptions, "support": OuterRingSupport,
                            "newton": NewtonOptions}
_MOVED: dict[str, tuple[str, str]] = {
    "contact_half_width": ("mesh", "contact_half_width"),
    "mesh_size": ("mesh", "mesh_size"),
    "max_size": ("mesh", "max_size"),
    "growth": ("mesh", "growth"),
    "support_stiffness": ("support", "stiffness"),
    "tol": ("newton", "tol"),
    "max_iter": ("newton", "max_iter"),
}
"""Old keyword -> (group keyword, field of the group)."""


def grouped_options(mesh: Any, support: Any, newton: Any, moved: dict[str, Any]
                    ) -> tuple[MeshOptions, OuterRingSupport, NewtonOptions]:
    """The option groups, defaults for ``None``.

    Raises
    ------
    TypeError
        For a keyword that moved into a group (``moved`` holds the keywords outside the
        signature; the message names the new home), for an unknown keyword, and for a group
        of the wrong type (``support="clamped"`` names ``OuterRingSupport(kind=...)``).

    Examples
    --------
    >>> grouped_options(None, None, None, {"mesh_size": 3e-3})
    Traceback (most recent call last):
    ...
    TypeError: ring_fe_roller_loads: 'mesh_size' moved to mesh=MeshOptions(mesh_size=...)
    """
    for name in moved:
        if name not in _MOVED:
            raise TypeError(f"{WHERE}() got an unexpected keyword argument {name!r}")
        group, key = _MOVED[name]
        raise TypeError(f"{WHERE}: {name!r} moved to {group}={_GROUPS[group].__name__}"
                        f"({key}=...)")
    if isinstance(support, str):
        raise TypeError(f"{WHERE}: support={support!r} moved to "
                        f"support=OuterRingSupport(kind={support!r})")
    for name, value in (("mesh", mesh), ("support", support), ("newton", newton)):
        if value is not None and not isinstance(value, _GROUPS[name]):
            raise TypeError(f"{WHERE}: {name} must be a {_GROUPS[name].__name__} or None, "
                            f"got {type(value).__name__}")
    return (MeshOptions() if mesh is None else mesh,
            OuterRingSupport() if support is None else support,
            NewtonOptions() if newton is None else newton)
