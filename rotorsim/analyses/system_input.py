"""Accept either a Rotor or an already assembled RotorSystem in every analysis."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rotorsim.assembly.system import RotorSystem, assemble
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor


def as_system(model: Rotor | RotorSystem) -> RotorSystem:
    """Assemble ``model`` if it is a :class:`Rotor`; pass a :class:`RotorSystem` through.

    Linear analyses call it: a model with nonlinear elements is refused (they would be
    silently left out), with the way to linearise them.
    """
    if isinstance(model, RotorSystem):
        system = model
    elif isinstance(model, Rotor):
        require_linear(model)
        system = assemble(model)
    else:
        raise ModelError(f"expected a Rotor or RotorSystem, got {type(model).__name__}",
                         "model")
    if system.nonlinear is not None:
        raise ModelError(NONLINEAR_HINT.format(len(system.nonlinear.elements)), "model")
    return system


NONLINEAR_HINT = ("the model has {} nonlinear elements (rolling bearings), which a linear "
                  "analysis cannot use: linearise them at the static load with "
                  "rs.linearize_rolling_bearings(rotor).rotor, or run rs.transient / "
                  "rs.static")


def require_linear(rotor: Rotor) -> None:
    """Raise :class:`ModelError` when ``rotor`` has nonlinear elements."""
    if rotor.nonlinear_elements:
        raise ModelError(NONLINEAR_HINT.format(len(rotor.nonlinear_elements)), "model")


def nonlinear_system(model: Any, nonlinear: Sequence[Any], where: str) -> RotorSystem:
    """The assembled system of a Rotor (with ``nonlinear`` elements added), of a loaded
    model file (its rotor with its rolling bearings), or an assembled RotorSystem as it is
    (then ``nonlinear`` must be empty). Nonlinear analyses (periodic, quasiperiodic) call
    it; errors name ``where``."""
    if isinstance(model, RotorSystem):
        if nonlinear:
            raise ModelError("give the nonlinear elements to assemble(), or a Rotor here",
                             where)
        return model
    if not isinstance(model, Rotor) and hasattr(model, "rotor"):
        model = model.rotor.with_nonlinear(tuple(getattr(model, "rolling_bearings", ())))
    if not isinstance(model, Rotor):
        raise ModelError(f"expected a Rotor, RotorSystem or Model, got "
                         f"{type(model).__name__}", where)
    return assemble(model, nonlinear=tuple(nonlinear))
