"""Quintic Hermite interpolation of a second-order trajectory: the dense output of the
fifth-order Radau stepper (:mod:`~rotorsim.time_integration.radau`)."""

from __future__ import annotations

import numpy as np

from rotorsim.time_integration.base import FloatArray, IntArray, State


def quintic_hermite(old: State, new: State, t: FloatArray,
                    dofs: IntArray) -> tuple[FloatArray, FloatArray]:
    """``q`` and ``v`` (len(t), len(dofs)) of the quintic through ``q, v, a`` at both ends.

    Examples
    --------
    >>> z = np.zeros(1)
    >>> s0 = State(0.0, z, z, np.full(1, 2.0), z)          # q = t^2
    >>> s1 = State(1.0, np.ones(1), np.full(1, 2.0), np.full(1, 2.0), z)
    >>> q, v = quintic_hermite(s0, s1, np.array([0.5]), np.arange(1))
    >>> float(q[0, 0]), float(v[0, 0])
    (0.25, 1.0)
    """
    h = new.t - old.t
    s = ((np.asarray(t, dtype=float) - old.t) / h)[:, None]
    s2, s3 = s * s, s * s * s
    s4, s5 = s3 * s, s3 * s2
    basis = (1 - 10 * s3 + 15 * s4 - 6 * s5, s - 6 * s3 + 8 * s4 - 3 * s5,
             0.5 * (s2 - 3 * s3 + 3 * s4 - s5), 10 * s3 - 15 * s4 + 6 * s5,
             -4 * s3 + 7 * s4 - 3 * s5, 0.5 * (s3 - 2 * s4 + s5))
    slope = (-30 * s2 + 60 * s3 - 30 * s4, 1 - 18 * s2 + 32 * s3 - 15 * s4,
             0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4), 30 * s2 - 60 * s3 + 30 * s4,
             -12 * s2 + 28 * s3 - 15 * s4, 0.5 * (3 * s2 - 8 * s3 + 5 * s4))
    ends = (old.q[dofs], h * old.v[dofs], h * h * old.a[dofs], new.q[dofs],
            h * new.v[dofs], h * h * new.a[dofs])
    q = sum(b * x[None, :] for b, x in zip(basis, ends, strict=True))
    v = sum(b * x[None, :] for b, x in zip(slope, ends, strict=True)) / h
    return np.asarray(q), np.asarray(v)
