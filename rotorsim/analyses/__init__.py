"""Analyses: the only layer that knows both the rotor model and the numerics.

An analysis takes a :class:`~rotorsim.model.rotor.Rotor` (or an assembled
:class:`~rotorsim.assembly.system.RotorSystem`), builds the rotor-agnostic problem that
``solvers``, ``time_integration`` or ``harmonic_balance`` solve, and returns a frozen result
of ``rotorsim.results``. The public verbs are exported from :mod:`rotorsim`.

Families, each a subpackage, in the order in which they may import each other:

- :mod:`~rotorsim.analyses.linear`: modal analysis, mode shapes, Campbell diagrams,
  critical speeds and maps, frequency and unbalance responses.
- :mod:`~rotorsim.analyses.statics`: linear and nonlinear static equilibrium, rotor and
  bearing statics, the potential-energy minimum, linearisation at the static loads.
- :mod:`~rotorsim.analyses.transient` and :mod:`~rotorsim.analyses.periodic`: time
  integration and harmonic balance; siblings, they do not import each other.
- :mod:`~rotorsim.analyses.sweep`: parameter sweeps over any verb above.

A family imports only the families before it. The modules at this level
(``system_input``, ``keyword_check``, ``rigid_motions``) are shared by every family and
import none of them. No analysis imports ``rotorsim.io``, ``rotorsim.cli`` or
``rotorsim.plotting``, apart from the checkpoint files of long runs (``rotorsim.io``).
``tests/test_architecture.py`` enforces these rules.
"""
