"""Typed option groups of the analysis verbs, shared by the Python API, the model-file
schema and the command line, so that each option is defined once.

A verb's options are grouped by concern into frozen dataclasses:

- :class:`Excitation`: unbalance, gravity, point loads, base motion, user forces.
- :class:`Harmonics`: harmonics, time samples, fundamental and condensation of harmonic
  balance.
- :class:`ContinuationOptions`: steps, point budget and tolerance of branch following.
- :class:`StabilityOptions`: Floquet method, stability model, tolerance, bifurcations.
- :class:`Output`: kept nodes, samples, velocities, reducers, rolling-element histories,
  progress bars.
- :class:`Checkpointing`: checkpoint file, interval and resume.
- :class:`SteadyStop`: when a transient stops early because its response is steady.

Each field carries its default, a one-line help text and its unit in the field's metadata
(:func:`~rotorsim.options.group.about`), and is validated when the group is built
(:class:`~rotorsim.options.group.OptionError`, a ``ModelError`` naming
``<Group>.<field>``). A field left at None takes the verb's default.

This package sits beside :mod:`rotorsim.errors` at the bottom of the layers: it imports
nothing of rotorsim but the errors (and a few types for annotations only), and every layer
(analyses, io, cli) may import it.
"""

from rotorsim.options.checkpointing import Checkpointing
from rotorsim.options.continuation import ContinuationOptions
from rotorsim.options.excitation import Excitation
from rotorsim.options.group import OptionError, OptionGroup
from rotorsim.options.harmonics import Harmonics
from rotorsim.options.output import Output
from rotorsim.options.stability import StabilityOptions
from rotorsim.options.steady import SteadyStop

__all__ = [
    "Checkpointing",
    "ContinuationOptions",
    "Excitation",
    "Harmonics",
    "OptionError",
    "OptionGroup",
    "Output",
    "StabilityOptions",
    "SteadyStop",
]
