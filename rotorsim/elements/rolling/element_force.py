"""Force and tangents of the rolling-bearing element in its 5 ring DOFs and their
expansion to its node DOFs (:class:`~rotorsim.elements.rolling.element.RollingBearing`).

Stiffness-proportional contact damping ``F_d = beta_c K(delta) delta'`` (element module
docstring): ``C = beta_c K`` exactly, and ``dF/d delta`` gains ``beta_c (dK/d delta)
delta'``, a central difference of the exact tangent along the velocity (step
``FD_STEP`` in the displacement scaled by ``(1, 1, 1, arm, arm)``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.base import frozen_scalar

FloatArray = NDArray[np.float64]
FD_STEP = 1e-9
"""Scaled step [m] of the central difference of the tangent along the velocity."""


# 0-d arrays: cheaper operands than Python floats in the hot path (same values)
_ZERO, _ONE, _FD_H, _FD_2H = (frozen_scalar(x) for x in (0.0, 1.0, FD_STEP, 2 * FD_STEP))
_SIGNS = np.array([1.0, -1.0])  # inner node +F, outer node -F
_SIGN_BLOCKS = np.array([[1.0, -1.0], [-1.0, 1.0]])[:, None, :, None]  # (2, 1, 2, 1)


def per_sample(value: ArrayLike, n_samples: int) -> FloatArray:
    """A scalar or (S,) array as (S,) floats (a broadcast view of a scalar)."""
    arr = np.asarray(value, dtype=float).reshape(-1)
    return arr if arr.shape[0] == n_samples else np.broadcast_to(arr, (n_samples,))


def _apply(k: FloatArray, x: FloatArray) -> FloatArray:
    """``k @ x`` per sample: (S, 5, 5) times (S, 5)."""
    return np.asarray(np.matmul(k, x[:, :, None]))[:, :, 0]


def damped_tangents(fast: Any, state: Callable[..., Any], beta: FloatArray | None,
                    scale: FloatArray, delta: FloatArray, rate: FloatArray, psi: FloatArray,
                    speeds: FloatArray, internal: Any
                    ) -> tuple[FloatArray, FloatArray, FloatArray, Any]:
    """Force (S, 5), ``dF/d delta``, ``dF/d delta'`` (S, 5, 5) and internal DOFs.

    ``fast(delta, cos psi, sin psi)`` is the model's force-and-tangent hot path (rigid ball
    and roller models; None otherwise), ``state(delta, psi, speeds, internal)`` its full
    state; ``beta`` the damping factor as a 0-d array (None: no damping), ``scale`` the
    rate scaling of the difference step.
    """
    if beta is None or not rate.any():
        if fast is not None:
            f0, k0 = fast(delta, np.cos(psi), np.sin(psi))
            solved = None
        else:
            st = state(delta, psi, speeds, internal)
            f0, k0, solved = st.force, st.stiffness, getattr(st, "internal", None)
        # at rest beta K delta' = 0: the force is the elastic one
        return f0, k0, np.zeros_like(k0) if beta is None else beta * k0, solved
    scaled = rate * scale
    size = np.sqrt(np.add.reduce(scaled * scaled, axis=1))  # as np.linalg.norm
    step = _FD_H * (rate / np.where(size > _ZERO, size, _ONE)[:, None])
    n_samples = delta.shape[0]
    shifted = np.empty((3, n_samples, 5))
    shifted[0] = delta
    np.add(delta, step, out=shifted[1])
    np.subtract(delta, step, out=shifted[2])
    if fast is not None:
        force3, k3 = fast(shifted, np.cos(psi), np.sin(psi))
        f0, k0, k_plus, k_minus, solved = force3[0], k3[0], k3[1], k3[2], None
    else:
        warm = None if internal is None else np.concatenate([internal] * 3)
        st = state(shifted.reshape(3 * n_samples, 5), np.concatenate([psi, psi, psi]),
                   np.concatenate([speeds] * 3), warm)
        f0, k0 = st.force[:n_samples], st.stiffness[:n_samples]
        k_plus = st.stiffness[n_samples:2 * n_samples]
        k_minus = st.stiffness[2 * n_samples:]
        solved = getattr(st, "internal", None)
        solved = None if solved is None else solved[:n_samples]
    dk = (k_plus - k_minus) / _FD_2H
    force = f0 + beta * _apply(k0, rate)
    return force, k0 + beta * dk * size[:, None, None], beta * k0, solved


def expand_vector(f5: FloatArray, linked: bool) -> FloatArray:
    """Force (S, 5) on the element DOFs: (S, 6) to ground, (S, 12) node to node (inner
    node ``+F``, outer ``-F``)."""
    if not linked:
        out = np.zeros((f5.shape[0], 6))
        out[:, :5] = f5
        return out
    out = np.zeros((f5.shape[0], 2, 6))
    np.multiply(f5[:, None, :], _SIGNS[:, None], out=out[:, :, :5])
    return out.reshape(-1, 12)


def expand_matrix(k5: FloatArray, linked: bool) -> FloatArray:
    """Tangent (S, 5, 5) on the element DOFs, (S, 6, 6) or (S, 12, 12)."""
    if not linked:
        out = np.zeros((k5.shape[0], 6, 6))
        out[:, :5, :5] = k5
        return out
    out = np.zeros((k5.shape[0], 2, 6, 2, 6))
    np.multiply(k5[:, None, :, None, :], _SIGN_BLOCKS, out=out[:, :, :5, :, :5])
    return out.reshape(-1, 12, 12)
