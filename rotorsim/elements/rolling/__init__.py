"""Nonlinear rolling-element bearings (rigid rings: seed 000; flexible rings: seed 001)."""

from rotorsim.elements.rolling.ball import BallBearing
from rotorsim.elements.rolling.centrifugal import CentrifugalBearing
from rotorsim.elements.rolling.ehl import Lubricant, LubricatedContacts
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller import RollerBearing
from rotorsim.elements.rolling.roller_profile import (
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
