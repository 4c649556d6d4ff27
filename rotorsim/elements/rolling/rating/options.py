"""Options of a bearing rating: where ``C`` comes from, the rotating ring, ``a_ISO`` inputs."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from rotorsim.elements.rolling.contact.hertz_point import BEARING_STEEL_E, BEARING_STEEL_NU
from rotorsim.elements.rolling.rating.iso16281 import ROTATING_RINGS
from rotorsim.errors import ModelError

_LIFE_FACTOR_KEYS = ("viscosity_ratio", "contamination", "fatigue_load_limit")


@dataclass(frozen=True)
class RatingOptions:
    """How a bearing is rated (ISO 281, ISO/TS 16281) and its contacts evaluated.

    Parameters
    ----------
    C, C0 : float, optional
        Catalogue basic dynamic and static load ratings [N]. Default: the ISO 281 / ISO 76
        geometry formulas (:mod:`~rotorsim.elements.rolling.rating.iso281`).
    bm : float, optional
        ISO 281 rating factor ``b_m`` for ``C`` from geometry (default 1.3 balls, 1.1
        rollers).
    rotating_ring : {"inner", "outer"}
        Ring turning relative to a fixed load (single loads and duty cycles); histories
        take the ring motion from the shaft angle (the inner ring turns with the shaft).
    n_laminae : int, optional
        Laminae per roller (default: the roller model's ``n_slices``).
    reliability : float
        Reliability [%] of ``L_nm`` (ISO 281 ``a1``), 90 to 99.95.
    viscosity_ratio, contamination, fatigue_load_limit : float, optional
        ``kappa = nu / nu_1`` [-], ``e_C`` [-] and ``C_u`` [N] of the life modification
        factor ``a_ISO`` (give all three, or none: then ``a_ISO = 1``).
    shoulder_heights : (float, float), optional
        Heights [m] of the loaded-side groove shoulders above the groove bottom (inner,
        outer ring): ball-bearing ellipse truncation check.
    E, nu, E_ring, nu_ring : float
        Elastic constants of rolling elements and rings for the pressures [Pa, -].
    n_cells : int
        Angular cells per ring of the load-history life.

    Examples
    --------
    >>> RatingOptions(C=14.8e3).rotating_ring
    'inner'
    >>> RatingOptions(C=-1.0)
    Traceback (most recent call last):
    ...
    rotorsim.errors.ModelError: RatingOptions: C must be positive and finite [N], got -1.0
    """

    C: float | None = None
    C0: float | None = None
    bm: float | None = None
    rotating_ring: str = "inner"
    n_laminae: int | None = None
    reliability: float = 90.0
    viscosity_ratio: float | None = None
    contamination: float | None = None
    fatigue_load_limit: float | None = None
    shoulder_heights: tuple[float, float] | None = None
    E: float = BEARING_STEEL_E
    nu: float = BEARING_STEEL_NU
    E_ring: float | None = None
    nu_ring: float | None = None
    n_cells: int = 360

    def __post_init__(self) -> None:
        where = "RatingOptions"
        for key in ("C", "C0", "bm", "fatigue_load_limit", "E", "E_ring"):
            value = getattr(self, key)
            if value is not None and not (_finite(value) and value > 0):
                raise ModelError(f"{key} must be positive and finite [N], got {value!r}"
                                 if key.startswith(("C", "f")) else
                                 f"{key} must be positive and finite, got {value!r}", where)
        if self.rotating_ring not in ROTATING_RINGS:
            raise ModelError(f"unknown rotating_ring {self.rotating_ring!r}; valid: "
                             f"{', '.join(ROTATING_RINGS)}", where)
        given = [k for k in _LIFE_FACTOR_KEYS if getattr(self, k) is not None]
        if given and len(given) != len(_LIFE_FACTOR_KEYS):
            missing = [k for k in _LIFE_FACTOR_KEYS if k not in given]
            raise ModelError(f"a_ISO needs {', '.join(_LIFE_FACTOR_KEYS)}; missing "
                             f"{', '.join(missing)}", where)
        for key in ("n_laminae", "n_cells"):
            value = getattr(self, key)
            if value is not None and (isinstance(value, bool) or not isinstance(value, int)
                                      or value < 1):
                raise ModelError(f"{key} must be an integer >= 1, got {value!r}", where)
        if self.shoulder_heights is not None:
            heights = tuple(self.shoulder_heights)
            if len(heights) != 2 or not all(_finite(h) and h > 0 for h in heights):
                raise ModelError("shoulder_heights must be two positive heights [m] (inner, "
                                 f"outer), got {self.shoulder_heights!r}", where)

    @property
    def life_factor(self) -> bool:
        """True when the ``a_ISO`` inputs are given."""
        return self.viscosity_ratio is not None

    @property
    def materials(self) -> dict[str, Any]:
        return {"E": self.E, "nu": self.nu, "E_ring": self.E_ring, "nu_ring": self.nu_ring}


def _finite(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(
        value)
