"""Assembly: a :class:`~rotorsim.model.rotor.Rotor` turned into sparse global matrices.

``dof_map`` (global and free DOF numbering), ``sparse`` (one shared CSR pattern), ``system``
(``RotorSystem`` and ``assemble``: ``M, C, G, K`` and the speed-dependent linear terms),
``loads`` (gravity, unbalance, point loads), ``nonlinear`` (the nonlinear elements with
their DOF indices), ``reduction`` (Craig-Bampton) and ``system_damping`` (the modal damping
matrix of a machine).

May import: ``model``, ``elements``, ``solvers``, ``errors``. Never ``rotorsim.analyses``
(``tests/test_architecture.py``).
"""
