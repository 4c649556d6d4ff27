"""Element protocols and the container for element matrices (DESIGN section 4)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

DOF_NAMES: tuple[str, ...] = ("ux", "uy", "uz", "rx", "ry", "rz")
"""Local DOF order of every node: translations then small rotations about x, y, z."""
DOFS_PER_NODE = 6


@dataclass(frozen=True)
class ElementMatrices:
    """Mass, damping, gyroscopic and stiffness matrices of one or many elements.

    Each array has shape ``(n, n)`` for one element or ``(E, n, n)`` for a batch,
    with ``n = 6 * number of nodes`` in the local DOF order of :data:`DOF_NAMES`.
    ``G`` multiplies the spin speed: the element adds ``M a + (C + W G) v + K q``.
    """

    M: FloatArray
    C: FloatArray
    G: FloatArray
    K: FloatArray


@runtime_checkable
class LinearElement(Protocol):
    """An element with constant or speed-dependent linear matrices."""

    @property
    def nodes(self) -> tuple[int, ...]: ...

    def matrices(self, speed: float = 0.0) -> ElementMatrices: ...


@dataclass(frozen=True, eq=False)
class ElementForce:
    """Restoring force and tangents of a nonlinear element for ``S`` samples.

    Attributes
    ----------
    f : array (S, n)
        Restoring force on the element DOFs [N, N m] (enters the equation of motion as
        ``+ r(q, q')``).
    K : array (S, n, n)
        ``df/du``.
    C : array (S, n, n)
        ``df/dv``.
    internal : None or array
        Converged internal DOFs to warm-start the next call (none for rigid rings).
    """

    f: FloatArray
    K: FloatArray
    C: FloatArray
    internal: Any = None


@runtime_checkable
class NonlinearElement(Protocol):
    """An element with a nonlinear restoring force, batched over ``S`` samples
    (DESIGN section 4): ``u, v`` are ``(S, n)`` DOF displacements and velocities, ``phi`` and
    ``speed`` ``(S,)`` shaft angles and spin speeds; ``internal`` warm-starts internal DOFs."""

    @property
    def nodes(self) -> tuple[int, ...]: ...

    def force(self, u: FloatArray, v: FloatArray, phi: FloatArray, speed: FloatArray,
              internal: Any = None) -> ElementForce: ...


def frozen_scalar(value: float) -> FloatArray:
    """A read-only 0-d float array: with numpy 2 it is a cheaper operand than a Python float
    in small-array hot paths (the same value, bit for bit)."""
    arr = np.array(float(value))
    arr.flags.writeable = False
    return arr


def check_finite(value: float, name: str, where: str, *, positive: bool = False,
                 nonnegative: bool = False) -> None:
    """Raise :class:`~rotorsim.errors.ModelError` unless ``value`` is a finite number (or
    array of them) signed as asked. Strings are refused: the API takes SI numbers, unit
    strings are read only in model files and the CLI."""
    from rotorsim.errors import ModelError

    arr = as_float_array(value, name, where)
    if arr.ndim:
        raise ModelError(f"{name} must be a single number, got {value!r}", where)
    if not np.all(np.isfinite(arr)):
        raise ModelError(f"{name} must be finite, got {value!r}", where)
    if positive and np.any(arr <= 0):
        raise ModelError(f"{name} must be > 0, got {value!r}", where)
    if nonnegative and np.any(arr < 0):
        raise ModelError(f"{name} must be >= 0, got {value!r}", where)


def as_float_array(value: Any, name: str, where: str) -> FloatArray:
    """``value`` as a float array, or a :class:`~rotorsim.errors.ModelError` naming ``name``
    if it is a string or not numeric (e.g. ``"50 mm"`` passed to the SI-only API)."""
    from rotorsim.errors import ModelError

    if isinstance(value, bool):
        raise ModelError(f"{name} must be a number, got {value!r}", where)
    if isinstance(value, str | bytes) or (
            isinstance(value, list | tuple) and any(isinstance(v, str | bytes) for v in value)):
        raise ModelError(f"{name} must be a number in SI units, got {value!r} (unit strings "
                         "are read in model files and the CLI only)", where)
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ModelError(f"{name} must be a number, got {value!r}", where) from None
