"""The rigid-ring ball bearing of seed 000: ``bearing`` (``BallBearing``: forces, analytic
tangent, energy), ``checks`` (input checks and the resolved geometry), ``tangent`` (the
tangent's terms) and ``centrifugal`` (two-race ball state under centrifugal and gyroscopic
loads).

May import: ``rolling.contact`` and the shared ``rolling`` modules (``geometry``, ``state``,
``element_equilibrium``).
"""
