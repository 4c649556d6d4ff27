"""Verification models: slow, detailed counterparts of the fast elements.

Nothing is imported here, so ``import rotorsim.verification`` stays light; import the
modules themselves (they need scikit-fem, and meshio to write files):

* :mod:`rotorsim.verification.ring_fe` -- 2D plane-stress finite-element model of a radial
  cylindrical roller bearing with flexible rings (seed 001 section 3, the counterpart of its
  NX Nastran verification): :func:`~rotorsim.verification.ring_fe.ring_fe_roller_loads`
  with its option groups ``MeshOptions``, ``OuterRingSupport`` and ``NewtonOptions``,
  :class:`~rotorsim.verification.ring_fe.RingFEResult`,
  :func:`~rotorsim.verification.ring_fe.export_vtu`.

``examples/seed001_ring_fe.py`` runs the seed 001 bearing with it (roller loads, mesh study,
sensitivities).

* :mod:`rotorsim.verification.periodic_events` -- :func:`~.periodic_events.verify_events`
  (``rs.verify_events``): the bifurcations of a periodic branch checked by time integration
  of the full model next to them, with :mod:`rotorsim.verification.period_map` (the period
  map measured by ``rs.transient``); with ``measure="floquet"``,
  :mod:`rotorsim.verification.floquet_modes` (the branch's Floquet modes on all DOFs),
  :mod:`rotorsim.verification.mode_growth` (a mode followed along free transients, and the
  verdict) and :mod:`rotorsim.verification.event_modes` (the two sides of an event). Needs
  numpy and scipy only; it may import the analyses (transient and periodic results, the
  periodic stability model), which no analysis family may import from each other.
"""
