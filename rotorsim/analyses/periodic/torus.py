"""``rs.periodic`` on a quasi-periodic problem: unbalance with the varying compliance (VC)
of rolling bearings whose cages turn, at incommensurate orders, or the unbalances of two
spools turning at different speeds.

The response is then a 2-torus, not a periodic orbit. Rather than freezing the rolling
elements (an answer that depends on an arbitrary cage angle, issue 17), ``rs.periodic``
hands the problem to the two-frequency harmonic balance
(:func:`~rotorsim.analyses.quasiperiodic.branch.quasi_periodic`) and returns a
:class:`~rotorsim.results.quasi_periodic.QuasiPeriodicResult`. The periodic options map
as follows:

* ``harmonics=H``: the box ``(H, H2)`` of tones ``k1 W + k2 w2``, ``H2 =`` :func:`vc_order`
  (3 for ``H >= 7``, 2 for ``H >= 4``, else 1) for the VC, whose tones decay fast, and
  ``H2 = H`` for two spools, whose unbalances both force the nonlinear bearings;
  ``Harmonics.samples`` is not used (the torus grid follows the box);
* ``continuation``: ``max_points`` caps the points; the largest speed step where the
  response is flat is ``max_step`` of the range, at most :data:`MAX_STEP` (a step of a
  fifth of the range can leap over a lightly damped resonance), and at least the range over
  half of ``max_points`` (room to refine); pseudo-arclength continuation shortens it
  through resonances and turns at folds;
* ``stability``: any method gives the characteristic exponents by the quasi-periodic Hill
  method; None skips them. ``StabilityOptions.beyond`` revolutions of a transient find
  what the motion is where a torus loses stability (0 skips it).

Not available on a torus (a :class:`~rotorsim.errors.ModelError` says so and how to freeze
the rolling elements instead): a fold map, peak location, checkpoints, ``x0``. A housing
excitation, the unbalance of a spool that turns at a speed ratio other than 1, or rolling
bearings of several VC orders (three or more frequencies) keep the rolling elements frozen,
recorded in ``result.approximation``.
"""

from __future__ import annotations

from typing import Any

from rotorsim.analyses.quasiperiodic.branch import quasi_periodic
from rotorsim.analyses.quasiperiodic.output import quasi_periodic_result
from rotorsim.analyses.quasiperiodic.problem import SAME_ORDER
from rotorsim.analyses.varying_compliance import vc_orders
from rotorsim.assembly.loads import spool_groups
from rotorsim.errors import ModelError
from rotorsim.options import Excitation
from rotorsim.results.quasi_periodic import QuasiPeriodicResult

MAX_STEP = 0.05
"""Largest step where the response is flat, as a fraction of the speed range (the periodic
default): a fifth of the range leaps over the default model's lightly damped resonance
(measured: 0.1 leaps, 0.05 passes it in 190 points, 0.02 in 477)."""
FREEZE = "; set varying_compliance=False to freeze the rolling elements instead"


def one_vc_order(elements: Any) -> bool:
    """The rolling bearings whose cages turn share one VC order (two frequencies in all:
    a 2-torus; several orders would make more, and the rolling elements stay frozen)."""
    orders = vc_orders(elements)
    return bool(orders) and max(orders) - min(orders) <= SAME_ORDER * max(orders)


def two_spools(system: Any, unbalance: list[tuple[int, float, float]]) -> bool:
    """The unbalances sit on two spools turning at different speeds (a torus of their two
    1X frequencies)."""
    return bool(unbalance) and len(spool_groups(system, unbalance)) == 2


def vc_order(harmonics: int) -> int:
    """VC harmonics ``H2`` that go with ``H`` shaft harmonics."""
    return 3 if harmonics >= 7 else 2 if harmonics >= 4 else 1


def refuse_unsupported(where: str, spools: bool = False, **given: Any) -> None:
    """ModelError naming the first option a torus does not support (``spools``: the torus
    of two spools' unbalances, which no option turns into a periodic problem)."""
    what = ("the unbalances of two spools at incommensurate speeds" if spools else
            f"unbalance with varying compliance{FREEZE}")
    for name, value in given.items():
        if value:
            raise ModelError(f"{name} is not available for a quasi-periodic response "
                             f"({what})", f"{where}.{name}")


def beyond_split(revolutions: int) -> tuple[int, int] | None:
    """``StabilityOptions.beyond`` as (settle, record) revolutions: two fifths settle."""
    if revolutions <= 0:
        return None
    settle = 2 * revolutions // 5
    return settle, revolutions - settle


def torus_branch(model: Any, nonlinear: Any, *, start: float, stop: float, opts: Any,
                 described: dict[str, Any], clock: float,
                 spools: bool = False) -> QuasiPeriodicResult:
    """The branch of tori for ``rs.periodic``'s arguments (module docstring); ``spools``:
    the second frequency is a second spool's 1X (else the VC)."""
    h, e, st = opts.harmonics, opts.excitation, opts.stability
    box = (int(h.count), int(h.count) if spools else vc_order(int(h.count)))
    span = abs(float(stop) - float(start))
    stepping = opts.stepping()
    max_points = int(stepping.max_points)
    fraction = min(float(stepping.max_step), MAX_STEP)
    step = span * max(fraction, 1.0 / max(1, (max_points - 1) // 2))   # room to refine
    branch = quasi_periodic(
        model, start=float(start), stop=float(stop), step=step, unbalance=list(e.unbalance),
        harmonics=box, truncation="box",
        excitation=Excitation(gravity=e.gravity, direction=e.direction, loads=list(e.loads)),
        nonlinear=tuple(nonlinear), stability=st.method is not None, max_points=max_points,
        beyond=beyond_split(int(st.beyond)))
    options = {**described, "quasi_periodic": True, "box": list(box), "step": step,
               "stability": None if st.method is None else "hill"}
    return quasi_periodic_result(branch, opts.output.nodes, options, clock)
