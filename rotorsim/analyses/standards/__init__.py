"""Checks of a rotor against the API standards for turbomachinery (API 617, API 684).

- ``api_formulas``: the standards' formulas as plain functions: anticipated cross-coupling
  Q_A, the Level I screening criteria, the residual unbalance U, the half-power
  amplification factor and the required separation margins.
- ``api_stability``: the Level I stability analysis (log decrement of the first forward
  mode at the maximum continuous speed against applied cross-coupling, Q0, Q0/Q_A, CSR).
- ``api_unbalance``: the unbalance response analysis (unbalance at the anti-nodes of each
  mode, amplification factors, separation margins, clearance ratios).

May import: the shared modules of :mod:`rotorsim.analyses`, the ``linear`` family,
``model``, ``elements``, ``assembly``, ``solvers``, ``results``. No other analysis family.
"""
