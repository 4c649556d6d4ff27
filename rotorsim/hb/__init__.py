"""Public harmonic balance for any mechanical system (``rs.hb``), as short as NLvib.

A :class:`System` is ``M, C, K`` (dense or sparse, optional gyroscopic ``G`` with spin)
plus nonlinear elements and harmonic forcing; :func:`frequency_response` continues its
periodic response over a frequency range with Floquet stability and located bifurcations;
:func:`solve` gives one frequency; :func:`solve_quasi` the quasi-periodic response to two
incommensurate frequencies (:mod:`rotorsim.hb.quasi`). The Duffing oscillator of NLvib's
example 01::

    import rotorsim as rs
    duffing = rs.hb.System(mass=1, stiffness=1, damping=0.05, forcing=[0.18],
                           elements=[rs.hb.CubicSpring(0, k3=0.1)])
    frf = rs.hb.frequency_response(duffing, start=0.5, stop=1.6, harmonics=7)
    print(frf.peak(0))            # largest fundamental amplitude and its frequency
    frf.plot(0)

Elements (:mod:`rotorsim.hb.elements`): :class:`CubicSpring`, :class:`UnilateralSpring`,
:class:`BilateralGap`, :class:`HertzContact`, :class:`CoulombFriction`, or any object
following the :class:`Element` protocol (``dofs`` and batched ``evaluate(q, v)`` returning
the force and its exact tangents; check them with :func:`check_tangents`).

This layer is built on :mod:`rotorsim.harmonic_balance` and :mod:`rotorsim.solvers` and,
like them, never imports the rotor model (DESIGN section 1).
"""

from rotorsim.hb.checks import check_tangents
from rotorsim.hb.elements import (
    BilateralGap,
    CoulombFriction,
    CubicSpring,
    Element,
    HertzContact,
    UnilateralSpring,
)
from rotorsim.hb.measures import amplitude
from rotorsim.hb.quasi import ToneForcing, solve_quasi
from rotorsim.hb.response import frequency_response, solve
from rotorsim.hb.result import Bifurcation, FrequencyResponse, Peak, Point
from rotorsim.hb.system import Forcing, System

__all__ = [
    "Bifurcation",
    "BilateralGap",
    "CoulombFriction",
    "CubicSpring",
    "Element",
    "Forcing",
    "FrequencyResponse",
    "HertzContact",
    "Peak",
    "Point",
    "System",
    "ToneForcing",
    "UnilateralSpring",
    "amplitude",
    "check_tangents",
    "frequency_response",
    "solve",
    "solve_quasi",
]
