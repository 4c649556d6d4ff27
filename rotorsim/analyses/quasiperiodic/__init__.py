"""Quasi-periodic responses of rotors: unbalance with rolling-element varying compliance on
a 2-torus (issue 17)."""

from rotorsim.analyses.quasiperiodic.beyond import motion_beyond
from rotorsim.analyses.quasiperiodic.branch import QuasiPeriodicBranch, quasi_periodic
from rotorsim.analyses.quasiperiodic.point import QuasiPeriodicPoint, quasi_periodic_point

__all__ = ["QuasiPeriodicBranch", "QuasiPeriodicPoint", "motion_beyond", "quasi_periodic",
           "quasi_periodic_point"]
