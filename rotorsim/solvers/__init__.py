"""Rotor-agnostic solvers (DESIGN sections 1 and 6): counted sparse factorisations
(``linear``), Newton with line search (``newton``), eigenvalues (``eigen``), energy
minimisation and multi-start search (``minimize``, ``global_search``), pseudo-arclength
continuation (``continuation*``), statistics (``stats``) and BLAS thread caps (``threads``).

They work on matrices and callbacks only and never import ``model``, ``elements``,
``assembly`` or ``analyses`` (``tests/test_architecture.py``). Slow SciPy submodules
(``scipy.optimize``, ``scipy.stats``) are imported inside the functions that use them.
"""
