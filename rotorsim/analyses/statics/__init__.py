"""Static equilibria: of the rotor under gravity and point loads, and of single bearings.

- ``static``: the ``rs.static`` verb (linear solve with explicit rigid-body checks; rotors
  with rolling bearings go to ``rolling_dispatch``).
- ``nonlinear_static`` and ``rolling_rotor_statics``: Newton on ``K q + r(q) = f``, with an
  energy line search for rolling bearings; ``rotor_energy``: the same equilibrium as a
  minimum of the potential energy.
- ``bearing_statics`` and ``bearing_problem``: one bearing under given forces and moments
  (``rs.bearing_equilibrium``), the element being called, never calling.
- ``linearized_rotor``: rolling bearings replaced by their tangents at the static loads, and
  the static start of transient and periodic runs (``rolling_start``).

May import: :mod:`rotorsim.analyses.linear` and the shared modules of
:mod:`rotorsim.analyses`, ``model``, ``elements``, ``assembly``, ``solvers``, ``results``.
"""
