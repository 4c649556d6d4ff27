"""Checks of the arguments shared by the linear analyses (modal, Campbell, critical speeds,
frequency response, static): one rule and one message for each.

Spin speeds are never negative. By the axis convention a rotor spins about ``+z`` at
``W >= 0``; whirl directions (forward/backward), gyroscopic signs and the speed axis of
tabulated bearing coefficients are all defined relative to that sense. A negative speed
would silently read bearing tables outside their range (held at the end value) and swap
the meaning of "forward", so it is refused everywhere with the way out: a rotor spinning
the other way is the same rotor seen from its other end (turned by pi about y: node order
reversed, ``x -> -x``, ``z -> -z``; cross-coupled bearing terms ``kxy``, ``kyx``, ``cxy``,
``cyx`` change sign) spinning at ``+W``.
"""

from __future__ import annotations

import numpy as np

from rotorsim.elements.base import as_float_array
from rotorsim.errors import ModelError

NEGATIVE_SPEED_HINT = ("rotors spin about +z at W >= 0; for the other sense, model the rotor "
                       "seen from its other end (nodes reversed, x -> -x, cross-coupled "
                       "bearing terms negated)")


def check_num_modes(num_modes: object, where: str) -> int:
    """A positive integer number of modes; ``bool``, ``2.5`` and ``0`` are refused.

    Examples
    --------
    >>> check_num_modes(2.5, "modal")
    Traceback (most recent call last):
    ...
    rotorsim.errors.ModelError: modal: num_modes must be a positive integer, got 2.5
    """
    if isinstance(num_modes, bool) or not isinstance(num_modes, int | np.integer) \
            or num_modes < 1:
        raise ModelError(f"num_modes must be a positive integer, got {num_modes!r}", where)
    return int(num_modes)


def check_speed(speed: object, where: str, name: str = "speed") -> float:
    """A finite, non-negative spin speed [rad/s] (see the module docstring).

    Examples
    --------
    >>> check_speed(-10.0, "modal")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    rotorsim.errors.ModelError: modal: speed must be >= 0 rad/s, got -10.0: rotors spin ...
    """
    if isinstance(speed, bool):
        raise ModelError(f"{name} must be a number [rad/s], got {speed!r}", where)
    if np.ndim(speed):  # type: ignore[arg-type]
        raise ModelError(f"{name} must be one number [rad/s], got {speed!r}", where)
    value = float(as_float_array(speed, name, where))
    if not np.isfinite(value):
        raise ModelError(f"{name} must be finite, got {speed!r}", where)
    if value < 0:
        raise ModelError(f"{name} must be >= 0 rad/s, got {speed!r}: {NEGATIVE_SPEED_HINT}",
                         where)
    return value


def check_sparse(sparse: object, where: str) -> bool | None:
    """``sparse`` is ``None`` (choose by size), ``True`` or ``False``; a string such as
    ``"no"`` would otherwise be read as true."""
    if sparse is not None and not isinstance(sparse, bool | np.bool_):
        raise ModelError(f"sparse must be None, True or False, got {sparse!r}", where)
    return None if sparse is None else bool(sparse)
