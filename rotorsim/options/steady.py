"""When a transient may stop early because its response is steady: :class:`SteadyStop`."""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from dataclasses import dataclass, field

from rotorsim.options.group import OptionGroup, about, check_count

DOF_NAMES = ("ux", "uy", "uz", "rx", "ry", "rz")


@dataclass(frozen=True)
class SteadyStop(OptionGroup):
    """Stop :func:`~rotorsim.transient` once steady (``steady=rs.SteadyStop(...)``).

    Over each shaft revolution (the angle ``phi`` from ``k 2 pi`` to ``(k + 1) 2 pi``, so
    also at a varying speed) the run takes the peak-to-peak ``p_k`` of the watched DOFs
    over its time steps; it stops at the end of a revolution once
    ``max |p_k - p_{k-1}| <= rtol * max p_k + atol`` has held for ``revolutions``
    consecutive revolutions (:class:`~rotorsim.time_integration.steady.SteadyDetector`,
    which says why the peak-to-peak and not a once-per-revolution sample).
    ``result.stopped`` then gives the reason, time and revolution.

    Parameters
    ----------
    nodes : sequence of int, optional
        Nodes watched (default: the kept nodes of ``output``, all by default).
    dofs : sequence of str
        DOFs watched at those nodes (default the lateral ``ux``, ``uy``).
    rtol : float
        Allowed change per revolution relative to the largest peak-to-peak.
    atol : float
        Absolute allowance [m, rad].
    revolutions : int
        Consecutive settled revolutions needed.

    Examples
    --------
    >>> SteadyStop(rtol=1e-4).revolutions
    3
    >>> SteadyStop(revolutions=0)
    Traceback (most recent call last):
    ...
    rotorsim.options.group.OptionError: SteadyStop.revolutions: must be a positive integer, got 0
    """

    nodes: Sequence[int] | None = field(
        default=None, metadata=about("nodes watched (default the kept nodes)"))
    dofs: Sequence[str] = field(default=("ux", "uy"), metadata=about("DOFs watched"))
    rtol: float = field(
        default=1e-3, metadata=about("allowed change of the peak-to-peak per revolution, "
                                     "relative", key="steady_rtol", file=float, ge=0))
    atol: float = field(
        default=0.0, metadata=about("absolute allowance of that change", "m",
                                    key="steady_atol", file=float, ge=0))
    revolutions: int = field(
        default=3, metadata=about("consecutive settled revolutions before stopping",
                                  key="steady_revolutions", file=int, ge=1))

    def __post_init__(self) -> None:
        if self.nodes is not None:
            nodes = tuple(self.nodes) if isinstance(self.nodes, Sequence) else None
            if not nodes or not all(isinstance(n, numbers.Integral)
                                    and not isinstance(n, bool) for n in nodes):
                raise self._fail("nodes", f"expected node numbers, got {self.nodes!r}")
            object.__setattr__(self, "nodes", nodes)
        dofs = tuple(self.dofs) if isinstance(self.dofs, Sequence) \
            and not isinstance(self.dofs, str) else ()
        if not dofs or not all(d in DOF_NAMES for d in dofs):
            raise self._fail("dofs", f"expected DOF names among {', '.join(DOF_NAMES)}, "
                                     f"got {list(self.dofs)}")
        object.__setattr__(self, "dofs", dofs)
        for name in ("rtol", "atol"):
            value = getattr(self, name)
            if not (isinstance(value, numbers.Real) and not isinstance(value, bool)
                    and math.isfinite(value) and float(value) >= 0):
                raise self._fail(name, f"must be a finite number >= 0, got {value!r}")
        if self.rtol == 0 and self.atol == 0:
            raise self._fail("rtol", "rtol and atol are both 0: the run would never stop")
        if not check_count(self.revolutions, 1):
            raise self._fail("revolutions", f"must be a positive integer, got "
                                            f"{self.revolutions!r}")
