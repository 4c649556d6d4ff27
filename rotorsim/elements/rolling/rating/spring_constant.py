"""The ISO/TS 16281 spring constant of a ball, as the rating layer names it.

The implementation is :mod:`rotorsim.elements.rolling.contact.iso_spring` (beside the
exact Hertz constant it is the option to, which ``BallBearing.from_geometry(...,
method="iso16281")`` uses); this module keeps the import path of the rating layer.
"""

from rotorsim.elements.rolling.contact.iso_spring import ISO_CONSTANT, iso16281_ball_constant

__all__ = ["ISO_CONSTANT", "iso16281_ball_constant"]
