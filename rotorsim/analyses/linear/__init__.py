"""Linear analyses of the rotor's matrices ``M, C + W G, K`` at given spin speeds.

- ``modal``: complex modes at one speed; ``mode_shapes``: MAC, whirl and mode kind.
- ``campbell``: damped modes over a speed grid, tracked through crossings.
- ``critical_speeds`` and ``critical_speed_map``: synchronous critical speeds, and against
  the support stiffness.
- ``frequency_response``: unbalance response and receptances.
- ``argument_checks``: the argument checks they share (mode counts, speeds).

May import: the shared modules of :mod:`rotorsim.analyses`, ``model``, ``elements``,
``assembly``, ``solvers``, ``results``. No other analysis family.
"""
