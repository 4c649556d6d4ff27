"""Load-deflection constant ``Kn`` at another exponent ``n``.

A contact law ``Q = Kn delta^n`` (Hertz: ``n = 3/2`` points, ``10/9`` lines) is replaced by
``Q = Kn' delta^n'`` with another exponent (e.g. ``n' = 1`` for a linear study, or a
measured exponent). Two conventions, stated by the argument given:

* ``load=Q_ref``: the two laws agree exactly at ``Q_ref`` (same deflection there),
  ``Kn' = Q_ref / delta_ref^n'`` with ``delta_ref = (Q_ref / Kn)^(1/n)``;
* ``load_range=(Q_lo, Q_hi)``: least squares on ``log Q`` at 64 deflections spaced
  logarithmically between those of ``Q_lo`` and ``Q_hi``,
  ``log Kn' = mean(log Q_k - n' log delta_k)``.

Units: ``Kn`` [N/m^n] in, ``Kn'`` [N/m^n'] out (SI throughout).
"""

from __future__ import annotations

import math

import numpy as np

from rotorsim.errors import ModelError


def kn_for_exponent(Kn: float, exponent: float, new_exponent: float, *,
                    load: float | None = None,
                    load_range: tuple[float, float] | None = None) -> float:
    """``Kn'`` [N/m^new_exponent] of the law with ``new_exponent`` (module docstring).

    Parameters
    ----------
    Kn : float
        Constant of the original law [N/m^exponent].
    exponent, new_exponent : float
        ``n`` and ``n'`` (>= 1).
    load : float, optional
        Reference load [N] where both laws agree.
    load_range : (float, float), optional
        Load range [N] of a least-squares fit in log space (instead of ``load``).

    Examples
    --------
    >>> k = kn_for_exponent(1e10, 1.5, 1.0, load=1000.0)   # the secant stiffness at 1 kN
    >>> round(k / (1000.0 / (1000.0 / 1e10) ** (2 / 3)), 12)
    1.0
    """
    where = "kn_for_exponent"
    for name, value in (("Kn", Kn), ("exponent", exponent), ("new_exponent", new_exponent)):
        if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
            raise ModelError(f"{name} must be positive and finite, got {value!r}", where)
    if exponent < 1.0 or new_exponent < 1.0:
        raise ModelError(f"exponents must be >= 1, got {exponent} and {new_exponent}", where)
    if (load is None) == (load_range is None):
        raise ModelError("give exactly one of load and load_range", where)
    if load is not None:
        if not (math.isfinite(load) and load > 0):
            raise ModelError(f"load must be positive [N], got {load!r}", where)
        deflection = (load / Kn) ** (1.0 / exponent)
        return float(load / deflection**new_exponent)
    assert load_range is not None
    lo, hi = (float(v) for v in load_range)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise ModelError(f"load_range must be 0 < low < high [N], got {load_range!r}", where)
    d = np.geomspace((lo / Kn) ** (1 / exponent), (hi / Kn) ** (1 / exponent), 64)
    log_q = math.log(Kn) + exponent * np.log(d)
    return float(np.exp(np.mean(log_q - new_exponent * np.log(d))))
