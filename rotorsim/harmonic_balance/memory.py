"""Memory of a harmonic-balance discretisation, estimated before anything is allocated.

A request such as ``harmonics=10000`` would otherwise run into a ``MemoryError`` (or the
operating system's out-of-memory killer) deep inside numpy after minutes of work.
:func:`check_memory` estimates the largest arrays of one residual evaluation, Newton step
and continuation step and refuses with a :class:`~rotorsim.errors.ModelError` that names the
figure and the limit. The estimate counts (8-byte floats, 16-byte complex):

* the dense Jacobian of the ``m = (2H + 1) k`` unknowns (``k`` nonlinear DOFs when
  condensed, all ``n`` DOFs otherwise), ``JACOBIAN_COPIES`` times: the AFT Galerkin product
  and its transposed copy, the bordered matrix of continuation and its LU factors;
* the gather indices of the AFT product (four ``(2H + 1)^2`` integer arrays);
* the force and its tangents at the ``N`` time samples (``N k^2``, twice, and their FFT),
  and ``SAMPLE_VALUES_PER_ELEMENT`` values per sample and rolling element of the bearings;
* with condensation, the LU factors of ``Z_LL,h`` for ``h = 0..H`` at the two cached
  frequencies (dense complex below the sparse threshold of
  :mod:`~rotorsim.harmonic_balance.condensation`) and the transfer matrices.

It is an estimate of the peak, not a bound: the limit leaves room for the rest.
"""

from __future__ import annotations

import os

from rotorsim.errors import ModelError

JACOBIAN_COPIES = 4
"""Dense Jacobian-sized arrays alive at once (AFT product, its reshaped copy, the bordered
matrix, its LU factors)."""

SAMPLE_VALUES_PER_ELEMENT = 32
"""Floats per time sample and rolling element held by a bearing evaluation (deflections,
loads, tangents per element)."""

DEFAULT_LIMIT = 8 * 2**30
"""Limit [bytes] where the physical memory cannot be read."""

GIB = 2**30


def estimate_bytes(harmonics: int, samples: int, nonlinear_dofs: int, dofs: int, *,
                   condense: bool = True, rolling_elements: int = 0) -> int:
    """Estimated peak memory [bytes] of a harmonic-balance run (module docstring).

    Parameters
    ----------
    harmonics, samples : int
        ``H`` and ``N``.
    nonlinear_dofs, dofs : int
        ``k`` nonlinear DOFs and ``n`` DOFs of the problem.
    condense : bool
        Unknowns on the nonlinear DOFs only.
    rolling_elements : int
        Rolling elements of all bearings (balls, rollers).

    Examples
    --------
    >>> round(estimate_bytes(10, 128, 12, 200) / 2**20, 1)       # MiB
    5.7
    """
    rows, N, k, n = 2 * harmonics + 1, samples, nonlinear_dofs, dofs
    m = rows * (k if condense else n)
    jacobian = JACOBIAN_COPIES * 8 * m * m
    gather = 4 * 8 * rows * rows
    sampled = 8 * N * k * k * 2 + 16 * (N // 2 + 1) * k * k \
        + 8 * N * rolling_elements * SAMPLE_VALUES_PER_ELEMENT
    linear = n - k
    condensed = 0
    if condense and linear:
        dense = linear <= 120
        factors = 16 * linear * linear if dense else 16 * 40 * linear
        condensed = 2 * (harmonics + 1) * (factors + 16 * linear * k)
    return int(jacobian + gather + sampled + condensed)


def memory_limit() -> int:
    """Half the physical memory of this machine [bytes] (``DEFAULT_LIMIT`` when unknown)."""
    try:
        total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return DEFAULT_LIMIT
    return int(total // 2) if total > 0 else DEFAULT_LIMIT


def check_memory(harmonics: int, samples: int, nonlinear_dofs: int, dofs: int, *,
                 condense: bool = True, rolling_elements: int = 0,
                 where: str = "harmonic balance") -> int:
    """:func:`estimate_bytes`, refused above :func:`memory_limit`.

    Returns
    -------
    int
        The estimate [bytes].

    Raises
    ------
    ModelError
        When the estimate exceeds the limit; the message gives both in GiB.
    """
    need = estimate_bytes(harmonics, samples, nonlinear_dofs, dofs, condense=condense,
                          rolling_elements=rolling_elements)
    limit = memory_limit()
    if need > limit:
        unknowns = (2 * harmonics + 1) * (nonlinear_dofs if condense else dofs)
        raise ModelError(f"H = {harmonics} harmonics with N = {samples} samples need about "
                         f"{need / GIB:.3g} GiB ({unknowns} unknowns, dense Jacobian), above "
                         f"the limit of {limit / GIB:.3g} GiB (half the physical memory); "
                         "use fewer harmonics", where)
    return need


HILL_COPIES = 6
"""Complex dense matrices of the size of Hill's pencil alive at once (the two pencil
matrices, the eigensolver's work copies and the eigenvectors)."""


def check_hill_memory(rows: int, where: str = "hill") -> int:
    """Estimated memory [bytes] of Hill's method with a pencil of ``rows`` rows
    (``HILL_COPIES`` dense complex matrices), refused above :func:`memory_limit`.

    Raises
    ------
    ModelError
        When the estimate exceeds the limit (figure and limit in GiB).
    """
    need = HILL_COPIES * 16 * rows * rows
    limit = memory_limit()
    if need > limit:
        raise ModelError(f"Hill's method with a pencil of {rows} rows needs about "
                         f"{need / GIB:.3g} GiB, above the limit of {limit / GIB:.3g} GiB (half "
                         "the physical memory); use stability='hsu', fewer harmonics or "
                         "stability_modes", where)
    return need
