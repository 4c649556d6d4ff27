"""Bearing rating: life and contact pressures from the load on every rolling element.

- :mod:`.iso281`: ISO 281:2007 basic dynamic load rating ``C`` (catalogue value or the
  geometry formulas with ``b_m`` and the ``f_c`` tables), static rating ``C0`` (ISO 76),
  the ``X, Y, e`` tables of the dynamic equivalent load ``P`` and ``L10 = (C/P)^p``.
- :mod:`.life_factor`: the ISO 281 life modification factor ``a_ISO`` (viscosity ratio
  ``kappa``, contamination factor ``e_C``, fatigue load limit ``C_u``) and the reliability
  factor ``a1``.
- :mod:`.iso16281`: ISO/TS 16281 modified reference rating life ``L10r`` from the internal
  load distribution (raceway reference loads, equivalent loads per ring with the rotating
  ring, laminae of rollers), and the reference load ``P_ref``.
- :mod:`.load_history`: ``L10r`` over sampled load histories (transients, periodic
  solutions, duty cycles) by Palmgren-Miner on the material points of each ring.
- :mod:`.hertz_pressure`: maximum Hertz pressure and contact-ellipse semi-axes of every
  ball-raceway contact (exact elliptic integrals, batched), shoulder truncation, and the
  line-contact pressure of every roller slice.

Nothing here solves an equilibrium: every function takes loads or ring displacements that
an analysis found (:mod:`rotorsim.analyses`).
"""
