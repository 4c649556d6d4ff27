"""Periodic forcing of a rotor and the fundamental frequency of its periodic response.

Everything that forces a rotor periodically is locked to the spin speed ``W`` and has an
*order* (frequency / ``W``):

* unbalance: order 1 (``me W^2`` rotating with the shaft angle ``phi``);
* varying compliance (VC) of a rolling bearing whose cage turns: order ``Z kappa`` (the
  rolling-element set advances one pitch ``2 pi / Z`` while the shaft turns
  ``2 pi / (Z kappa)``);
* housing (base) excitation :class:`HarmonicBase`: displacement ``a cos(b phi + phase)`` of
  order ``b`` (seed 002 section 3.5.2.3 excites at ``b = k Z kappa``, ``k = 1, 2``).

The response is periodic with the fundamental ``omega = f W`` when every order present is an
integer multiple ``h = order / f`` of the fundamental order ``f``; :func:`fundamental_order`
picks the largest such ``f``. Unbalance together with VC is generally *quasi-periodic*
(``Z kappa`` is irrational): then :func:`plan_excitation` freezes the rolling elements at
the shaft angle ``phi0`` (VC neglected) and says so in ``ExcitationPlan.approximation``
(the result carries it), unless the caller asks for VC explicitly, which raises.

In the phase ``tau = omega t`` of the fundamental the shaft angle is
``phi = phi0 + tau / f``, the spin ``W = omega / f``.

References
----------
Seed 002 section 3.5.2.1 (fundamental ``omega = omega_cage``-related VC frequency, external
loads as Fourier series eq 3.32) and section 3.5.2.3 (housing excitation, eq 3.43).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.analyses.varying_compliance import vc_orders
from rotorsim.assembly.loads import unit_direction
from rotorsim.errors import ModelError

MAX_MULTIPLE = 16
"""Largest ratio ``order / f`` accepted when searching a common fundamental order."""
ORDER_TOL = 1e-9
"""Relative tolerance of "integer multiple" tests on orders."""


@dataclass(frozen=True)
class HarmonicBase:
    """Harmonic housing (base) displacement locked to the shaft speed.

    The base moves by ``amplitude cos(order phi + phase)`` along ``direction`` (``phi`` the
    shaft angle), i.e. at the frequency ``order W``; coordinates become relative to the base
    and every mass feels ``-M e a_b(t)`` (seed 002 eq 3.43). With ``parameter="frequency"``
    the frequency is the continuation parameter instead and ``order`` is not used.

    Parameters
    ----------
    amplitude : float
        Displacement amplitude [m].
    order : float
        Frequency / spin speed (e.g. ``k * Z * kappa`` for the seed's ``w = k w_vc``).
    phase : float
        Phase [rad] at ``phi = 0``.
    direction : 3 floats
        Direction of the motion (normalised).

    Examples
    --------
    >>> HarmonicBase(1e-4, order=2.0).direction
    (0.0, 1.0, 0.0)
    """

    amplitude: float
    order: float = 1.0
    phase: float = 0.0
    direction: tuple[float, float, float] = (0.0, 1.0, 0.0)

    def __post_init__(self) -> None:
        for name in ("amplitude", "order", "phase"):
            if not math.isfinite(getattr(self, name)):
                raise ModelError(f"{name} must be finite, got {getattr(self, name)!r}",
                                 "HarmonicBase")
        if self.order <= 0:
            raise ModelError(f"order must be > 0, got {self.order!r}", "HarmonicBase")
        d = unit_direction(self.direction, "HarmonicBase.direction")
        object.__setattr__(self, "direction", tuple(float(x) for x in d))

    def describe(self) -> dict[str, Any]:
        """JSON-able description (result options)."""
        return {"amplitude": self.amplitude, "order": self.order, "phase": self.phase,
                "direction": list(self.direction)}


@dataclass(frozen=True)
class ExcitationPlan:
    """How the periodic problem is set up.

    Attributes
    ----------
    order : float
        Fundamental order ``f = omega / W`` (0 with ``parameter="frequency"``).
    moving_elements : bool
        Rolling elements move with their cages (VC included); False: frozen at ``phi0``.
    unbalance_harmonic, base_harmonic : int
        Harmonic of the fundamental carrying the unbalance and the base excitation (0 when
        absent).
    approximation : str
        "" for an exact periodic problem, else what was neglected.
    unbalance_ratio : float
        Signed speed ratio of the spool that carries the unbalance (1 on a one-line rotor):
        its unbalance turns at ``r W`` with the angle ``r phi``.
    quasi_periodic : bool
        The forcing and the VC are incommensurate and the caller left
        ``varying_compliance`` open: the response is a torus
        (:mod:`~rotorsim.analyses.periodic.torus` hands it to the quasi-periodic HB);
        ``approximation`` says what the frozen periodic problem would neglect.
    """

    order: float
    moving_elements: bool
    unbalance_harmonic: int
    base_harmonic: int
    approximation: str = ""
    unbalance_ratio: float = 1.0
    quasi_periodic: bool = False


def fundamental_order(orders: Sequence[float]) -> float | None:
    """Largest ``f`` with every order an integer multiple (<= ``MAX_MULTIPLE``) of ``f``.

    Returns None when the orders are incommensurate (quasi-periodic), 1.0 for no orders.

    Examples
    --------
    >>> fundamental_order([3.2, 6.4]), fundamental_order([1.0, 0.5]), fundamental_order([])
    (3.2, 0.5, 1.0)
    >>> fundamental_order([1.0, 3.57191]) is None
    True
    """
    values = sorted({float(o) for o in orders})
    if not values:
        return 1.0
    for m in range(1, MAX_MULTIPLE + 1):
        f = values[0] / m
        if all(_multiple(o, f) is not None for o in values):
            return f
    return None


def harmonic_of(order: float, fundamental: float) -> int:
    """``order / fundamental`` as an integer; ModelError if it is not one."""
    h = _multiple(order, fundamental)
    if h is None:
        raise ModelError(f"order {order:.9g} is not an integer multiple (<= {MAX_MULTIPLE}) "
                         f"of the fundamental order {fundamental:.9g}: the response would "
                         "not be periodic", "periodic.fundamental")
    return h


def _multiple(order: float, f: float) -> int | None:
    ratio = order / f
    h = round(ratio)
    if 1 <= h <= MAX_MULTIPLE and abs(ratio - h) <= ORDER_TOL * max(1.0, ratio):
        return int(h)
    return None


def plan_excitation(elements: Sequence[Any], *, unbalance: bool, base: HarmonicBase | None,
                    varying_compliance: bool | None, fundamental: float | None,
                    frequency_parameter: bool, unbalance_ratio: float = 1.0
                    ) -> ExcitationPlan:
    """Fundamental order, harmonics of each forcing and the VC treatment (module docstring).

    ``unbalance_ratio`` is the signed speed ratio of the spool carrying the unbalance on a
    machine of several lines: the unbalance is then of order ``|r|``.

    Raises
    ------
    ModelError
        For ``varying_compliance=True`` when VC is not periodic with the other forcing, or a
        ``fundamental`` of which a forcing order is not an integer multiple.
    """
    vc = vc_orders(elements)
    if frequency_parameter:
        return _frequency_plan(vc, unbalance, base, varying_compliance)
    u_order = abs(float(unbalance_ratio))
    forced = ([u_order] if unbalance else []) + ([base.order] if base is not None else [])
    moving = bool(vc) and varying_compliance is not False
    approximation = ""
    f = fundamental if fundamental is not None else fundamental_order(
        forced + (vc if moving else []))
    vc_periodic = f is not None and all(_multiple(o, f) is not None for o in vc)
    quasi = False
    if moving and not vc_periodic and varying_compliance is None:
        moving, quasi = False, True
        f = fundamental if fundamental is not None else fundamental_order(forced)
        approximation = (f"rolling elements frozen at the shaft angle phi0 (varying "
                         f"compliance at orders {_orders(vc)} neglected: with the forcing at "
                         f"orders {_orders(forced)} the response is quasi-periodic)")
    if f is None:
        raise ModelError(f"orders {_orders(forced + (vc if moving else []))} have no common "
                         "fundamental: the response is quasi-periodic; set "
                         "varying_compliance=False to freeze the rolling elements",
                         "periodic.varying_compliance")
    if not (math.isfinite(f) and f > 0):
        raise ModelError(f"must be > 0, got {f!r}", "periodic.fundamental")
    for o in vc if moving else []:
        harmonic_of(o, f)
    if vc and not moving and not approximation:
        approximation = ("rolling elements frozen at the shaft angle phi0 (varying "
                         "compliance neglected on request)")
    return ExcitationPlan(float(f), moving, harmonic_of(u_order, f) if unbalance else 0,
                          harmonic_of(base.order, f) if base is not None else 0,
                          approximation, float(unbalance_ratio), quasi)


def _frequency_plan(vc: list[float], unbalance: bool, base: HarmonicBase | None,
                    varying_compliance: bool | None) -> ExcitationPlan:
    if unbalance:
        raise ModelError("unbalance (order 1 of the fixed speed) is not periodic with a "
                         "continued excitation frequency; use parameter='speed'",
                         "periodic.unbalance")
    if base is None:
        raise ModelError("parameter='frequency' needs a base excitation", "periodic.base")
    if vc and varying_compliance:
        raise ModelError("varying compliance is not periodic with a continued excitation "
                         "frequency", "periodic.varying_compliance")
    approx = ("rolling elements frozen at the shaft angle phi0 (varying compliance "
              "neglected)") if vc else ""
    return ExcitationPlan(0.0, False, 0, 1, approx)


def _orders(values: Sequence[float]) -> str:
    return "[" + ", ".join(f"{v:.6g}" for v in values) + "]"


def rotating_coefficients(amplitude: ArrayLike, harmonic: int, rows: int) -> np.ndarray:
    """Coefficient array ``(rows, n)`` of ``Re(U e^{i h tau})``: ``Q_hc = Re U``,
    ``Q_hs = -Im U`` (layout of :mod:`rotorsim.harmonic_balance.fourier`)."""
    U = np.asarray(amplitude, dtype=complex)
    out = np.zeros((rows, U.size))
    if harmonic:
        out[2 * harmonic - 1] = U.real
        out[2 * harmonic] = -U.imag
    return out
