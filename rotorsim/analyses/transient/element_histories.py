"""Rolling-element histories of a transient: the load and contact angle of every element."""

from __future__ import annotations

import inspect
from typing import Any

import numpy as np

from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.results.transient import TransientResult


def rolling_element_histories(system: RotorSystem, result: TransientResult
                              ) -> tuple[dict[str, FloatArray], dict[str, FloatArray]]:
    """``element_loads`` and ``contact_angles`` (k, Z) of each bearing, by tag, from the
    kept bearing DOFs, shaft angles and speeds of ``result`` (one batched state call per
    bearing)."""
    nl = system.nonlinear
    loads: dict[str, FloatArray] = {}
    angles: dict[str, FloatArray] = {}
    if nl is None:
        return loads, angles
    for i, (el, tag) in enumerate(zip(nl.elements, result.bearing_tags, strict=True)):
        u = np.hstack([result.node_displacement(int(node)) for node in el.nodes])
        state = _state(el, u, result.angle, result.speed)
        if state is None:
            continue
        key = tag if tag not in loads else f"{tag}_{i}"
        loads[key] = np.asarray(state.element_load, dtype=float)
        angles[key] = np.asarray(state.contact_angle, dtype=float)
    return loads, angles


def _state(element: Any, u: FloatArray, phi: FloatArray, speed: FloatArray) -> Any:
    """The bearing state at element DOFs ``u`` (S, 6 * nodes); None for elements without
    rolling elements."""
    assert u.shape[1] == DOFS_PER_NODE * len(element.nodes)
    if hasattr(element, "state") and "speed" in inspect.signature(element.state).parameters \
            and not hasattr(element, "bearing_state_from_relative"):
        try:
            return element.state(u, phi, speed)
        except TypeError:
            pass
    bearing = getattr(element, "bearing", None)
    if bearing is None or not hasattr(bearing, "state") or not hasattr(element, "relative"):
        return None
    delta = element.relative(u)
    psi = bearing.element_angles(phi)
    if "speed" in inspect.signature(bearing.state).parameters:
        return bearing.state(delta, psi, speed=speed)
    return bearing.state(delta, psi)
