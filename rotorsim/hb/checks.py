"""Finite-difference check of an element's tangents (for users writing their own)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.hb.elements import Element

STEP = 1e-6
"""Relative central-difference step (truncation ~ STEP^2, round-off ~ eps / STEP)."""


def check_tangents(element: Element, q: ArrayLike, v: ArrayLike) -> float:
    """Largest difference between ``element``'s tangents and central differences of its
    force at the samples ``q, v`` (N, d), relative to the largest tangent entry.

    Keep the samples away from the switching points of a piecewise law (contact onset),
    where the one-sided derivatives differ.

    Examples
    --------
    >>> from rotorsim.hb.elements import HertzContact
    >>> rng = np.random.default_rng(0)
    >>> q = rng.uniform(0.2, 2.0, (50, 1))
    >>> check_tangents(HertzContact(0, stiffness=3.0, gap=0.1), q, np.zeros_like(q)) < 1e-8
    True
    """
    q = np.asarray(q, dtype=float)
    v = np.asarray(v, dtype=float)
    _, dfdq, dfdv = element.evaluate(q, v)
    worst, size = 0.0, 0.0
    for arg, exact in ((0, dfdq), (1, dfdv)):
        approx = np.zeros((*q.shape, q.shape[1]))
        for j in range(q.shape[1]):
            h = STEP * np.maximum(np.abs([q, v][arg][:, j]), 1.0)
            plus, minus = [q.copy(), v.copy()], [q.copy(), v.copy()]
            plus[arg][:, j] += h
            minus[arg][:, j] -= h
            approx[:, :, j] = (element.evaluate(*plus)[0]
                               - element.evaluate(*minus)[0]) / (2 * h[:, None])
        reference = np.zeros_like(approx) if exact is None else np.asarray(exact)
        worst = max(worst, float(np.max(np.abs(reference - approx), initial=0.0)))
        size = max(size, float(np.max(np.abs(reference), initial=0.0)))
    return worst / (size or 1.0)
