"""Harmonic sets on a 2-torus: the combination tones ``k1 w1 + k2 w2`` of a quasi-periodic
response, in box or diamond truncation.

A quasi-periodic signal with two incommensurate base frequencies ``w1`` and ``w2`` is a
function on the torus of the angles ``theta = (w1 t, w2 t)``:

    q(t) = a_0 + sum_j [ c_j cos(k_j . theta) + s_j sin(k_j . theta) ],

where the wave vectors ``k_j = (k1, k2)`` are integers, one of each pair ``+-k`` (the
half-plane ``k1 > 0``, or ``k1 = 0`` and ``k2 > 0``). The truncation chooses which ``k``
are kept:

- **box**: ``|k1| <= H1`` and ``|k2| <= H2``, sizes chosen per frequency;
- **diamond**: ``|k1| + |k2| <= H``, the usual choice when the combination tones decay
  with their order ``|k1| + |k2|``.

References
----------
L. Liu, E. H. Dowell, K. C. Hall, "A novel harmonic balance analysis for the Van der Pol
oscillator", *Int. J. Non-Linear Mech.* 42 (2007) 2-12; S. Schilder, W. Vogt,
S. Schreiber, H. M. Osinga, "Fourier methods for quasi-periodic oscillations",
*Int. J. Numer. Meth. Eng.* 67 (2006) 629-671 (the torus formulation and the truncations);
M. Krack, J. Gross, *Harmonic Balance for Nonlinear Vibration Problems*, Springer 2019,
section 4.2 (multi-frequency harmonic balance).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError

IntArray = NDArray[np.int64]
FloatArray = NDArray[np.float64]

WHERE = "TorusHarmonics"


@dataclass(frozen=True, eq=False)
class TorusHarmonics:
    """The wave vectors ``k (n_h, 2)`` of a quasi-periodic harmonic set (the mean excluded).

    Build it with :meth:`box` or :meth:`diamond`. Rows are ordered by order
    ``|k1| + |k2|``, then ``k1``, then ``k2``.

    Examples
    --------
    >>> TorusHarmonics.diamond(1).k.tolist()
    [[0, 1], [1, 0]]
    >>> TorusHarmonics.box(1, 1).size
    4
    """

    k: IntArray
    truncation: str

    @classmethod
    def box(cls, h1: int, h2: int) -> TorusHarmonics:
        """``|k1| <= h1`` and ``|k2| <= h2`` (``h1, h2 >= 0``, not both 0)."""
        _orders(h1, h2)
        k1, k2 = np.meshgrid(np.arange(-h1, h1 + 1), np.arange(-h2, h2 + 1), indexing="ij")
        return cls(_half_plane(k1.ravel(), k2.ravel()), "box")

    @classmethod
    def diamond(cls, h: int) -> TorusHarmonics:
        """``|k1| + |k2| <= h`` (``h >= 1``)."""
        _orders(h, h)
        if h < 1:
            raise ModelError(f"h must be >= 1, got {h!r}", f"{WHERE}.diamond")
        k1, k2 = np.meshgrid(np.arange(-h, h + 1), np.arange(-h, h + 1), indexing="ij")
        keep = np.abs(k1) + np.abs(k2) <= h
        return cls(_half_plane(k1[keep], k2[keep]), "diamond")

    @property
    def size(self) -> int:
        """Number of wave vectors ``n_h`` (each has a cosine and a sine coefficient)."""
        return int(self.k.shape[0])

    @property
    def rows(self) -> int:
        """Rows of a coefficient array: ``2 n_h + 1`` (the mean first)."""
        return 2 * self.size + 1

    def frequencies(self, w1: float, w2: float) -> FloatArray:
        """``k1 w1 + k2 w2`` of every wave vector [rad/s] (may be negative)."""
        return self.k[:, 0] * float(w1) + self.k[:, 1] * float(w2)

    def default_samples(self) -> tuple[int, int]:
        """Torus grid ``(N1, N2)``: the smallest powers of two above ``4 max|k_i|``, at least
        8, so that products up to third order of the retained tones do not alias back onto
        them (``N_i > (p + 1) max|k_i|`` for order ``p``)."""
        top = np.abs(self.k).max(axis=0)
        return tuple(int(max(8, 2 ** int(np.ceil(np.log2(4 * t + 1))))) for t in top)  # type: ignore[return-value]

    def index(self, k1: int, k2: int) -> int:
        """Row of the wave vector ``(k1, k2)`` (or of ``(-k1, -k2)``) in :attr:`k`."""
        hit = np.flatnonzero((self.k[:, 0] == k1) & (self.k[:, 1] == k2)
                             | (self.k[:, 0] == -k1) & (self.k[:, 1] == -k2))
        if hit.size == 0:
            raise ModelError(f"({k1}, {k2}) is not in the harmonic set", WHERE)
        return int(hit[0])


def _half_plane(k1: IntArray, k2: IntArray) -> IntArray:
    keep = (k1 > 0) | ((k1 == 0) & (k2 > 0))
    k = np.stack([k1[keep], k2[keep]], axis=1).astype(np.int64)
    order = np.lexsort((k[:, 1], k[:, 0], np.abs(k).sum(axis=1)))
    return k[order]


def _orders(h1: object, h2: object) -> None:
    for name, h in (("h1", h1), ("h2", h2)):
        if isinstance(h, bool) or not isinstance(h, int | np.integer) or h < 0:
            raise ModelError(f"{name} must be an integer >= 0, got {h!r}", WHERE)
    if h1 == 0 and h2 == 0:
        raise ModelError("h1 and h2 cannot both be 0", WHERE)
