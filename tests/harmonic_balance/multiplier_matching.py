"""Pairing of Floquet multipliers for comparisons in the harmonic-balance tests."""

from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment


def matched(mu: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """``mu`` reordered to pair each entry with the nearest entry of ``ref`` (an optimal
    assignment). Sorting instead would order a complex-conjugate pair by the last bits of
    their real parts, which differ between BLAS kernels."""
    mu, ref = np.asarray(mu), np.asarray(ref)
    _, cols = linear_sum_assignment(np.abs(ref[:, None] - mu[None, :]))
    return mu[cols]
