"""ISO 281:2007 life modification: ``a_ISO`` and the reliability factor ``a1``.

``L_nm = a1 a_ISO L10`` (ISO 281 clause 9). ``a_ISO`` depends on the viscosity ratio
``kappa = nu / nu_1`` (operating over rated kinematic viscosity of the lubricant), on the
contamination factor ``e_C`` (ISO 281 Table 13, 0 severe to 1 extremely clean), on the
fatigue load limit ``C_u`` [N] (catalogue) and on the equivalent load ``P`` [N]
(``P_ref`` of ISO/TS 16281 for the modified reference rating life). ISO 281 eqs (13)-(16)
(radial ball / radial roller / thrust ball / thrust roller)::

    a_ISO = 0.1 [1 - (c1 - c2 / kappa^c3)^c4 (e_C C_u / (s P))^c5]^(-c6),   a_ISO <= 50

with ``(c1, c2, c4, c5, c6) = (2.5671, 2.2649 | 1.9987, 0.83, 1/3, 9.3)`` for balls and
``(1.5859, 1.3993 | 1.2348, 1, 0.4, 9.185)`` for rollers; ``c3 = 0.054381`` for
``0.1 <= kappa < 0.4`` (with the first ``c2``), ``0.19087`` for ``0.4 <= kappa < 1`` and
``0.071739`` for ``1 <= kappa <= 4`` (second ``c2``); ``s = 1`` radial, ``3`` thrust ball,
``2.5`` thrust roller. ``kappa > 4`` is taken as 4; ``kappa < 0.1`` is outside the
standard and raises.

References
----------
ISO 281:2007 clause 9.3, eqs (13)-(16), Table 12 (``a1``), Table 13 (``e_C``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.errors import ModelError

FloatArray = NDArray[np.float64]

_RELIABILITY = np.array([90.0, 95.0, 96.0, 97.0, 98.0, 99.0, 99.2, 99.4, 99.6, 99.8, 99.9,
                         99.92, 99.94, 99.95])
_A1 = np.array([1.0, 0.64, 0.55, 0.47, 0.37, 0.25, 0.22, 0.19, 0.16, 0.12, 0.093, 0.087,
                0.080, 0.077])
"""ISO 281 Table 12."""

_CONSTANTS = {"ball": (2.5671, (2.2649, 1.9987), 0.83, 1.0 / 3.0, 9.3),
              "roller": (1.5859, (1.3993, 1.2348), 1.0, 0.4, 9.185)}
_LOAD_SCALE = {("ball", False): 1.0, ("roller", False): 1.0, ("ball", True): 3.0,
               ("roller", True): 2.5}


def reliability_factor(reliability: float = 90.0) -> float:
    """``a1`` of ISO 281 Table 12 for the reliability [%] (90 to 99.95, interpolated).

    Examples
    --------
    >>> reliability_factor(99.0)
    0.25
    """
    if not _RELIABILITY[0] <= reliability <= _RELIABILITY[-1]:
        raise ModelError(f"reliability {reliability!r} % outside 90 to 99.95 % (ISO 281 "
                         "Table 12)", "reliability_factor")
    return float(np.interp(reliability, _RELIABILITY, _A1))


def life_modification_factor(kind: str, viscosity_ratio: float, contamination: float,
                             fatigue_load_limit: float, P: ArrayLike, *,
                             thrust: bool = False) -> FloatArray:
    """ISO 281 ``a_ISO`` (module docstring), capped at 50.

    Parameters
    ----------
    kind : {"ball", "roller"}
    viscosity_ratio : float
        ``kappa = nu / nu_1`` [-], >= 0.1 (values above 4 count as 4).
    contamination : float
        ``e_C`` in [0, 1] (ISO 281 Table 13).
    fatigue_load_limit : float
        ``C_u`` [N].
    P : array_like
        Equivalent load (or ``P_ref``) [N], > 0.
    thrust : bool
        Thrust bearing (load scale 3 balls, 2.5 rollers).

    Examples
    --------
    >>> round(float(life_modification_factor("ball", 1.0, 0.5, 335.0, 1400.0)), 3)
    3.082
    """
    where = "life_modification_factor"
    if kind not in _CONSTANTS:
        raise ModelError(f"unknown bearing kind {kind!r}; valid: ball, roller", where)
    if not (np.isfinite(viscosity_ratio) and viscosity_ratio >= 0.1):
        raise ModelError(f"viscosity ratio kappa = {viscosity_ratio!r} must be >= 0.1 "
                         "(ISO 281 does not cover thinner films)", where)
    if not 0.0 <= contamination <= 1.0:
        raise ModelError(f"contamination factor e_C = {contamination!r} must be in [0, 1]",
                         where)
    if not (np.isfinite(fatigue_load_limit) and fatigue_load_limit > 0):
        raise ModelError(f"fatigue load limit C_u must be positive [N], got "
                         f"{fatigue_load_limit!r}", where)
    load = np.asarray(P, dtype=float)
    if not np.isfinite(load).all() or (load <= 0).any():
        raise ModelError("equivalent load P must be positive and finite [N]", where)
    c1, c2s, c4, c5, c6 = _CONSTANTS[kind]
    kappa = min(float(viscosity_ratio), 4.0)
    c2, c3 = ((c2s[0], 0.054381) if kappa < 0.4 else
              (c2s[1], 0.19087) if kappa < 1.0 else (c2s[1], 0.071739))
    lube = max(c1 - c2 / kappa**c3, 0.0) ** c4
    ratio = contamination * fatigue_load_limit / (_LOAD_SCALE[(kind, thrust)] * load)
    inner = 1.0 - lube * ratio**c5
    with np.errstate(divide="ignore", invalid="ignore"):
        value = np.where(inner > 0.0, 0.1 * np.abs(inner) ** -c6, 50.0)
    return np.asarray(np.minimum(value, 50.0))
