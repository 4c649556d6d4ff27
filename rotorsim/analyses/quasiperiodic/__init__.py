"""Quasi-periodic responses of rotors: unbalance with rolling-element varying compliance on
a 2-torus (issue 17)."""

from rotorsim.analyses.quasiperiodic.point import QuasiPeriodicPoint, quasi_periodic_point

__all__ = ["QuasiPeriodicPoint", "quasi_periodic_point"]
