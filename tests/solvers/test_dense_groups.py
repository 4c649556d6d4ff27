"""The groups of a dense coupling pattern against scipy's connected components."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from rotorsim.errors import ModelError
from rotorsim.solvers.dense_groups import coupled_groups


@pytest.mark.parametrize("seed", range(6))
def test_groups_equal_scipys_connected_components(seed):
    rng = np.random.default_rng(seed)
    for _ in range(50):
        n = int(rng.integers(1, 80))
        pattern = rng.random((n, n)) < rng.uniform(0.0, 0.1)  # not symmetric
        count, labels = connected_components(sp.csr_matrix(pattern), directed=False)
        expected = [np.flatnonzero(labels == g) for g in range(count)]
        found = coupled_groups(pattern)
        assert len(found) == count
        assert all(np.array_equal(a, b) for a, b in zip(found, expected, strict=True))


def test_a_long_chain_is_one_group():
    # a path 0 - 1 - ... - 999 in scrambled order: the labels travel its whole length
    n = 1000
    order = np.random.default_rng(0).permutation(n)
    pattern = np.zeros((n, n), dtype=bool)
    pattern[order[:-1], order[1:]] = True
    (group,) = coupled_groups(pattern)
    assert np.array_equal(group, np.arange(n))


@pytest.mark.parametrize("shape", [(3, 4), (5,), (2, 2, 2)])
def test_a_pattern_that_is_not_square_is_refused_by_name(shape):
    with pytest.raises(ModelError, match=r"coupled_groups: .*square matrix, got shape"):
        coupled_groups(np.ones(shape, dtype=bool))
