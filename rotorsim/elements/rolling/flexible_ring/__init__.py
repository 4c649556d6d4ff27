"""The roller bearing with flexible rings of seed 001: ``bearing``
(``FlexibleRingRollerBearing``), ``checks`` (its input checks and ring sections),
``roller`` (the potential of one roller, eqs 8-19), ``geometry``, ``state``, ``solve`` (the
condensed inner solve, eqs 20-26) and ``element`` (``FlexibleRingBearingElement``, the
2-node element).

May import: ``rolling.contact``, ``rolling.roller.profile`` and the shared ``rolling``
modules (``geometry``, ``state``, ``condensation``).
"""
