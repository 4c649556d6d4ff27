"""Periodic responses by harmonic balance, their continuation, stability and bifurcations.

- ``periodic``: the ``rs.periodic`` verb (branches over speed or forcing amplitude);
  ``parameter``: ``rs.periodic_parameter`` (branches over a model parameter at a fixed
  speed) and ``variation``: how the residual varies with that parameter.
- ``problem``: the rotor's periodic problem as a rotor-agnostic ``HBProblem``;
  ``excitation``: periodic forcing and the fundamental frequency.
- ``branch``: start and continuation; ``resume``: continuing from a results file.
- ``stability``: Floquet method choice and stability model; ``events``: period doublings
  and Neimark-Sacker points; ``folds``: jump maps.
- ``output``: the branch assembled into a ``PeriodicResult``.

May import: :mod:`rotorsim.analyses.statics`, :mod:`rotorsim.analyses.linear`, the shared
modules of :mod:`rotorsim.analyses`, the model layers, ``harmonic_balance``, ``solvers``,
``results`` and the checkpoint files of ``rotorsim.io``. Not ``analyses.transient``.
"""
