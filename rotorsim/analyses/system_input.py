"""Accept either a Rotor or an already assembled RotorSystem in every analysis."""

from __future__ import annotations

from rotorsim.assembly.system import RotorSystem, assemble
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor


def as_system(model: Rotor | RotorSystem) -> RotorSystem:
    """Assemble ``model`` if it is a :class:`Rotor`; pass a :class:`RotorSystem` through."""
    if isinstance(model, RotorSystem):
        return model
    if isinstance(model, Rotor):
        return assemble(model)
    raise ModelError(f"expected a Rotor or RotorSystem, got {type(model).__name__}", "model")
