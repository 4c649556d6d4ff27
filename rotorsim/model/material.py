"""Isotropic linear-elastic materials."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from rotorsim.errors import ModelError


@dataclass(frozen=True)
class Material:
    """Isotropic material.

    Give the Young's modulus and exactly one of the shear modulus ``G_s`` or the
    Poisson ratio ``nu``; the other is derived from ``G_s = E / (2 (1 + nu))``.

    Parameters
    ----------
    name : str
        Label used in messages and model files.
    E : float
        Young's modulus [Pa].
    rho : float
        Density [kg/m^3].
    G_s : float, optional
        Shear modulus [Pa].
    nu : float, optional
        Poisson ratio [-].

    Examples
    --------
    >>> steel = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> round(steel.nu, 4)
    0.2993
    """

    name: str
    E: float
    rho: float
    G_s: float = field(default=math.nan)
    nu: float = field(default=math.nan)

    def __post_init__(self) -> None:
        where = f"Material '{self.name}'"
        for key in ("E", "rho", "G_s", "nu"):
            value = _number(getattr(self, key), key, where)
            if key in ("E", "rho") and not (math.isfinite(value) and value > 0):
                raise ModelError(f"{key} must be a positive finite number, got {value}", where)
            if math.isinf(value):  # NaN is the "not given" default of G_s and nu
                raise ModelError(f"{key} must be finite, got {value}", where)
        has_g = math.isfinite(self.G_s)
        has_nu = math.isfinite(self.nu)
        if has_nu and not -1.0 < self.nu < 0.5:
            raise ModelError(f"Poisson ratio {self.nu:.4f} outside (-1, 0.5)", where)
        if has_g == has_nu and not (has_g and _consistent(self.E, self.G_s, self.nu)):
            raise ModelError("give exactly one of G_s and nu", where)
        if has_g and not has_nu:
            if self.G_s <= 0:
                raise ModelError(f"G_s must be positive, got {self.G_s}", where)
            object.__setattr__(self, "nu", self.E / (2.0 * self.G_s) - 1.0)
        elif has_nu and not has_g:
            object.__setattr__(self, "G_s", self.E / (2.0 * (1.0 + self.nu)))
        if not -1.0 < self.nu < 0.5:
            raise ModelError(f"Poisson ratio {self.nu:.4f} outside (-1, 0.5)", where)


def _number(value: object, key: str, where: str) -> float:
    """``value`` as a float, or a :class:`ModelError` naming ``key`` (strings are refused:
    the API takes SI numbers; unit strings are read in model files and the CLI only)."""
    if isinstance(value, str | bytes | bool):
        raise ModelError(f"{key} must be a number in SI units, got {value!r}", where)
    try:
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ModelError(f"{key} must be a number, got {value!r}", where) from None


def _consistent(E: float, G: float, nu: float) -> bool:
    return math.isclose(G, E / (2.0 * (1.0 + nu)), rel_tol=1e-6)


steel = Material(name="steel", E=211e9, G_s=81.2e9, rho=7810.0)
"""Steel of Friswell et al. (2010) examples: E = 211 GPa, G = 81.2 GPa, rho = 7810 kg/m^3."""
