"""Elements: one element kind per module, each a frozen dataclass holding its parameters.

``base`` (the ``LinearElement`` and ``NonlinearElement`` protocols, ``ElementMatrices``,
``ElementForce``), ``shaft`` (Timoshenko beam), ``disk`` (rigid disk, point mass),
``linear_bearing`` (8-coefficient bearings and seals), ``beam_flexibility`` and the
nonlinear rolling bearings in :mod:`~rotorsim.elements.rolling`.

An element returns its matrices, force, tangent and linearisation at a given state; it never
imports ``rotorsim.analyses`` (finding an equilibrium is an analysis). May import
``errors`` and ``model``; ``tests/test_architecture.py`` enforces this.
"""
