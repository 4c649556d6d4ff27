"""Nonlinear rolling-element bearings (rigid rings: seed 000; flexible rings: seed 001).

Subpackages, one bearing model each, over a shared contact layer:

- :mod:`~rotorsim.elements.rolling.contact`: the laws of one contact (Hertz point and line
  contacts, slices and crowning, the EHL film of one contact). Imports nothing else of
  ``rolling``.
- :mod:`~rotorsim.elements.rolling.ball`: ``BallBearing`` (rigid rings, 5 DOF), its analytic
  tangent and its centrifugal (two-race) state.
- :mod:`~rotorsim.elements.rolling.roller`: ``RollerBearing`` (cylindrical and tapered,
  whole-roller or sliced), roller profiles, input checks, centrifugal state.
- :mod:`~rotorsim.elements.rolling.flexible_ring`: ``FlexibleRingRollerBearing`` (per-roller
  internal DOFs and ring energies, condensed) and its 2-node element.
- :mod:`~rotorsim.elements.rolling.rating`: ISO 281 and ISO/TS 16281 lives and Hertz
  contact pressures from the element loads of the ball and roller models (may import them;
  nothing else of ``rolling`` imports it).

Shared modules at this level: ``geometry`` (angular positions, cage ratio), ``state``
(``BearingState``), ``element_equilibrium`` and ``condensation`` (batched inner Newton). The
bearing models import ``contact`` and these, never each other, except that the flexible-ring
model uses the roller profiles. The wrappers ``element`` (the 2-node ``RollingBearing``),
``centrifugal``, ``reversed``, ``large_rotation`` and ``lubrication`` (EHL contacts of a
whole bearing) may import any model. Nothing in ``rolling`` imports ``rotorsim.analyses``:
an element returns forces, tangents and linearisations at a given state, and the
equilibrium is found by :mod:`rotorsim.analyses.statics`.
"""

from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.centrifugal import CentrifugalBearing
from rotorsim.elements.rolling.lubrication import Lubricant, LubricatedContacts
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    StraightProfile,
)
from rotorsim.elements.rolling.state import BearingState

__all__ = [
    "BallBearing",
    "BearingState",
    "CentrifugalBearing",
    "CircularCrown",
    "LogarithmicProfile",
    "Lubricant",
    "LubricatedContacts",
    "ReversedBearing",
    "RollerBearing",
    "StraightProfile",
]
