"""Transient responses: the rotor's equations of motion integrated in time.

- ``transient``: the ``rs.transient`` verb (steppers from ``rotorsim.time_integration``).
- ``speed_profile``: spin-speed schedules W(t) with acceleration and angle.
- ``torque_drive``, ``torque_laws``, ``spin_equation``: speed from motor, load and friction
  torques (the rigid spin equation integrated up front); ``torsion_loads`` and
  ``torque_damping``: the drive's loads and slip damping on the torsional DOFs;
  ``spin_feedback``: the neglected torque of the lateral motion on the spin.
- ``loads``: the time-dependent loads and nonlinear forces as stepper callbacks, base
  excitation.
- ``start``: the initial state (zero, given, or the static equilibrium).
- ``reduction``: Craig-Bampton reduction of a transient.
- ``element_histories``: the load and contact angle of every rolling element over time.

May import: :mod:`rotorsim.analyses.statics`, :mod:`rotorsim.analyses.linear`, the shared
modules of :mod:`rotorsim.analyses`, the model layers, ``time_integration``, ``solvers``,
``results`` and the checkpoint files of ``rotorsim.io``. Not ``analyses.periodic``.
"""
