"""Rotor-agnostic implicit time integration (DESIGN sections 1 and 6).

Build a :class:`SecondOrderProblem` (``M a + (C + s(t) G) v + K q + r(q, v, t) = f(t)``),
pick a stepper (:class:`Newmark` family, optionally wrapped in :class:`Adaptive`, the
fourth-order :class:`Adams`, or the error-controlled fifth-order :class:`Radau`) and call
:func:`integrate` with an :class:`OutputSpec` (samples, kept unknowns and velocities,
reducers); long runs write checkpoints and resume from them, continue from the final state
of an earlier run (``start=``) and may stop once steady (``stop_when=``, e.g. a
:class:`SteadyDetector`).
"""

from rotorsim.errors import CheckpointError
from rotorsim.time_integration.adams import Adams
from rotorsim.time_integration.adaptive import Adaptive
from rotorsim.time_integration.base import Counters, State, TimeStepper, cubic_hermite
from rotorsim.time_integration.checkpoint import load_checkpoint, save_checkpoint
from rotorsim.time_integration.integrate import IntegrationResult, integrate
from rotorsim.time_integration.newmark import Newmark
from rotorsim.time_integration.output import OutputSpec, Reducer
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.radau import Radau
from rotorsim.time_integration.steady import SteadyDetector

__all__ = [
    "Adams",
    "Adaptive",
    "CheckpointError",
    "Counters",
    "IntegrationResult",
    "Newmark",
    "OutputSpec",
    "Radau",
    "Reducer",
    "SecondOrderProblem",
    "State",
    "SteadyDetector",
    "TimeStepper",
    "cubic_hermite",
    "integrate",
    "load_checkpoint",
    "save_checkpoint",
]
