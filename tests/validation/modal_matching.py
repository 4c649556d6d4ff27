"""Pairing of computed and reference eigenvalues for the validation tests."""

from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment


def match_eigenvalues(reference, computed) -> tuple[np.ndarray, np.ndarray]:
    """Indices ``(i, j)`` pairing each reference eigenvalue with a distinct computed one.

    The pairing minimises the summed distance ``|ref_i - computed_j|`` in the complex plane
    (Hungarian algorithm), so degenerate pairs and differently sorted lists match.
    """
    ref = np.asarray(reference, dtype=complex)
    got = np.asarray(computed, dtype=complex)
    cost = np.abs(ref[:, None] - got[None, :])
    i, j = linear_sum_assignment(cost)
    return i, j


def relative_error(value, reference) -> np.ndarray:
    """``|value - reference| / |reference|`` elementwise."""
    value = np.asarray(value)
    reference = np.asarray(reference)
    return np.abs(value - reference) / np.abs(reference)
