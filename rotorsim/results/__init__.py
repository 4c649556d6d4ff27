"""Result types: one frozen dataclass per analysis (arrays, DOF labels, options, statistics,
status), with post-processing that needs no live rotor (spectra, order tracks, orbits).

May import ``assembly`` (``DofMap``), ``elements`` and ``errors``; never ``analyses``,
``plotting`` or matplotlib (``tests/test_architecture.py``). Saving and loading is
:mod:`rotorsim.io`, figures are :mod:`rotorsim.plotting`.
"""
