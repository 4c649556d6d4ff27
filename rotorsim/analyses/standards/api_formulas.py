"""The formulas of API 617 / API 684 used by the stability and unbalance checks.

Everything here works in SI (W, rad/s, m, kg, N/m) unless a name says otherwise
(``_us``: US customary, ``_rpm``: revolutions per minute).

Editions and clauses. The formulas follow API Standard 617, 7th edition (2002), chapter 1,
section 2.6 (2.6.2 unbalance response and separation margins, 2.6.5 Level I stability),
and API RP 684, 2nd edition (2005), sections SP6.8.2 and SP6.8.5, which explains them;
API 617 8th edition (2014) moved these clauses to section 4.8 (4.8.2, 4.8.5). No copy of
the standards was at hand: the formulas and clause numbers are those the standards' users
cite (ROSS's ``api_report`` among them), so check them, and any change of the 8th
edition, against the copy a project is bound to.

Units of Q_A. The anticipated cross-coupling is Wachel's estimate,
``Q_A = B T / (D H) * (rho_d / rho_s)``, with ``T = P / Omega`` the stage torque. API 617
prints it as ``Q_A = B C P / (D H N) * (rho_d / rho_s)`` with a units constant ``C``. The
US customary form (``C = 63``; P [hp], D and H [in], N [rpm], Q_A [klbf/in]) is
dimensionally consistent: ``63 P / N`` is the torque in klbf in (63 025 lbf in per hp/rpm).
The SI form as printed (``C = 9.55``; P [kW], D and H [mm], N [rpm], Q_A [kN/mm]) is
not: ``9.55 P / N`` is the torque in kN m, and kN m / mm^2 is 1000 kN/mm, so the printed
SI form gives a number 1000 times smaller than the consistent value in kN/mm (it is the
value in MN/mm). rotorsim computes the consistent form,
:func:`anticipated_cross_coupling`, in N/m from SI inputs; it equals the US form converted
(1 klbf/in = 175 126.8 N/m) up to the rounding of C (63 for 63.025, 0.04 %).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.errors import ModelError

MACHINE_FACTORS = {"compressor": 3.0, "turbine": 1.5}
"""Wachel's factor B of each machine type: B_c = 3 for centrifugal compressor stages,
B_t = 1.5 for turbine stages (API 617 7th ed. 2.6.5.5; API 684 SP6.8.5.6)."""
US_CONSTANT = 63.0
"""API's units constant C of the US customary Q_A form (hp, in, rpm -> klbf/in)."""
KLBF_PER_IN = 4448.2216152605 / 0.0254
"""N/m per klbf/in."""
UNBALANCE_SI = 6350.0
"""API residual unbalance constant: U = 6350 W / N [g mm] with W [kg], N [rpm]."""
UNBALANCE_US = 4.0
"""The same in US customary units: U = 4 W / N [oz in] with W [lb], N [rpm]."""
AF_CRITICALLY_DAMPED = 2.5
"""Amplification factor below which a resonance needs no separation margin
(API 617 7th ed. 2.6.2.10)."""
CLEARANCE_LIMIT = 0.75
"""Scaled peak-to-peak response over diametral running clearance allowed at a close
clearance (API 617 7th ed. 2.6.2.11)."""
CSR_BOUNDARY = ((0.0, 2.5), (16.53, 2.5), (60.0, 2.0))
"""Boundary between Regions A and B of the Level I screening chart (API 617 7th ed.
2.6.5.10; API 684 SP6.8.5.10) as points (average gas density [kg/m^3], CSR): 2.5 up
to 16.53 kg/m^3, falling linearly to 2.0 at 60 kg/m^3; above 60 kg/m^3 every CSR lies in
Region B. These are the points ROSS's ``api_report`` uses; check them against the
figure of the edition a project is bound to."""


def _positive(value: ArrayLike, name: str, where: str) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise ModelError(f"{name} must be finite and > 0, got {value!r}", where)
    return arr


def _machine(machine: str, where: str) -> float:
    if machine not in MACHINE_FACTORS:
        raise ModelError(f"machine must be one of {sorted(MACHINE_FACTORS)}, got "
                         f"{machine!r}", where)
    return MACHINE_FACTORS[machine]


def anticipated_cross_coupling(power: ArrayLike, speed: float, diameter: ArrayLike,
                               flow_height: ArrayLike, density_ratio: ArrayLike = 1.0,
                               machine: str = "compressor") -> np.ndarray:
    """Anticipated cross-coupled stiffness Q_A of each stage [N/m] (consistent SI form).

    ``Q_A = B P / (Omega D H) * (rho_d / rho_s)`` for a compressor stage, without the density
    ratio for a turbine stage (API 617 7th ed. 2.6.5.5; module docstring for the units).

    Parameters
    ----------
    power : float or array (S,)
        Power of each stage [W].
    speed : float
        Maximum continuous speed Omega [rad/s].
    diameter : float or array (S,)
        Impeller diameter (compressor) or blade pitch diameter (turbine) [m].
    flow_height : float or array (S,)
        Flow-path height: the minimum of diffuser and impeller discharge width (compressor)
        or the effective blade height (turbine) [m].
    density_ratio : float or array (S,)
        Discharge over suction gas density of each stage (compressors only).
    machine : {"compressor", "turbine"}

    Returns
    -------
    array (S,)
        Q_A of each stage [N/m]; their sum is the machine's Q_A.

    Examples
    --------
    >>> q = anticipated_cross_coupling(10e3, 1000 * math.pi / 30, 0.35, 0.08, 1.11)
    >>> round(float(q[0]), 1)   # 3 * 10 kW / (104.7 rad/s * 0.35 m * 0.08 m) * 1.11
    11356.8
    """
    where = "anticipated_cross_coupling"
    b = _machine(machine, where)
    p = _positive(power, "power", where)
    w = float(_positive(speed, "speed", where))
    d = _positive(diameter, "diameter", where)
    h = _positive(flow_height, "flow_height", where)
    ratio = _positive(density_ratio, "density_ratio", where) if machine == "compressor" \
        else 1.0
    return np.atleast_1d(b * p / (w * d * h) * ratio)


def anticipated_cross_coupling_us(power_hp: ArrayLike, speed_rpm: float,
                                  diameter_in: ArrayLike, flow_height_in: ArrayLike,
                                  density_ratio: ArrayLike = 1.0,
                                  machine: str = "compressor") -> np.ndarray:
    """Q_A of each stage in the US customary form of API 617 [klbf/in].

    ``Q_A = B C P / (D H N) * (rho_d / rho_s)`` with ``C = 63``, P [hp], D, H [in], N [rpm]
    (API 617 7th ed. 2.6.5.5). Kept for checks against hand calculations and data sheets;
    :func:`anticipated_cross_coupling` is the SI form rotorsim uses.

    Examples
    --------
    >>> round(float(anticipated_cross_coupling_us(1000, 10000, 12, 0.5, 1.2)[0]), 3)
    3.78
    """
    where = "anticipated_cross_coupling_us"
    b = _machine(machine, where)
    p = _positive(power_hp, "power_hp", where)
    n = float(_positive(speed_rpm, "speed_rpm", where))
    d = _positive(diameter_in, "diameter_in", where)
    h = _positive(flow_height_in, "flow_height_in", where)
    ratio = _positive(density_ratio, "density_ratio", where) if machine == "compressor" \
        else 1.0
    return np.atleast_1d(b * US_CONSTANT * p / (d * h * n) * ratio)


def csr_limit(density: float) -> float:
    """CSR on the Region A/B boundary at average gas density ``density`` [kg/m^3]
    (:data:`CSR_BOUNDARY`; 0 above 60 kg/m^3: every CSR is in Region B there).

    Examples
    --------
    >>> csr_limit(10.0), round(csr_limit(38.265), 4), csr_limit(70.0)
    (2.5, 2.25, 0.0)
    """
    if not math.isfinite(density) or density < 0:
        raise ModelError(f"average gas density must be finite and >= 0, got {density!r}",
                         "csr_limit")
    rho, csr = np.array(CSR_BOUNDARY).T
    if density > rho[-1]:
        return 0.0
    return float(np.interp(density, rho, csr))


def level1_screening(q_ratio: float, log_dec_a: float, csr: float, density: float | None,
                     machine: str = "compressor") -> tuple[bool, tuple[str, ...]]:
    """Whether API 617 asks for a Level II stability analysis, and why.

    Level II is required (API 617 7th ed. 2.6.5.8-2.6.5.10; API 684 SP6.8.5.10) when

    - the log decrement at Q_A is below 0.1 (every machine type), or, for compressors,
    - Q0 / Q_A < 2, or
    - 2 <= Q0 / Q_A < 10 and the point (average gas density, CSR) lies in Region B of the
      screening chart (CSR above :func:`csr_limit`).

    Parameters
    ----------
    q_ratio : float
        Q0 / Q_A.
    log_dec_a : float
        Log decrement of the first forward mode at Q_A.
    csr : float
        Critical speed ratio: maximum continuous speed over the first undamped critical
        speed on rigid supports.
    density : float or None
        Average gas density of the machine [kg/m^3]; ``None`` when not given (the Region
        test is then skipped and the reasons say so).
    machine : {"compressor", "turbine"}

    Returns
    -------
    (bool, tuple of str)
        Level II required, and the reasons (empty when not required).

    Examples
    --------
    >>> level1_screening(5.0, 0.3, 2.6, 10.0)
    (True, ('2 <= Q0/QA = 5 < 10 and CSR = 2.6 in Region B (limit 2.5 at 10 kg/m^3)',))
    >>> level1_screening(12.0, 0.3, 2.6, 10.0)
    (False, ())
    """
    _machine(machine, "level1_screening")
    reasons = []
    if log_dec_a < 0.1:
        reasons.append(f"log dec at QA = {log_dec_a:.3g} < 0.1")
    if machine == "compressor":
        if q_ratio < 2.0:
            reasons.append(f"Q0/QA = {q_ratio:.3g} < 2")
        elif q_ratio < 10.0 and density is not None:
            limit = csr_limit(density)
            if csr > limit:
                reasons.append(f"2 <= Q0/QA = {q_ratio:.3g} < 10 and CSR = {csr:.3g} in "
                               f"Region B (limit {limit:.3g} at {density:.3g} kg/m^3)")
        elif q_ratio < 10.0:
            reasons.append(f"2 <= Q0/QA = {q_ratio:.3g} < 10 and no average gas density "
                           "given for the Region A/B test")
    return bool(reasons), tuple(reasons)


def residual_unbalance(mass: ArrayLike, speed_rpm: float) -> np.ndarray:
    """API unbalance U = 6350 W / N per plane, in [kg m] (6350 W/N g mm, W [kg], N [rpm]).

    Equal to the US form ``4 W / N`` [oz in] with W [lb]: 4 oz in/lb = 6350.0 g mm/kg
    (API 617 7th ed. 2.6.2.7).

    Examples
    --------
    >>> float(residual_unbalance(63.5, 10000.0)[0])   # 40.32 g mm
    4.03225e-05
    """
    m = _positive(mass, "mass", "residual_unbalance")
    n = float(_positive(speed_rpm, "speed_rpm", "residual_unbalance"))
    return np.atleast_1d(UNBALANCE_SI * m / n * 1e-6)


def residual_unbalance_us(weight_lb: ArrayLike, speed_rpm: float) -> np.ndarray:
    """U = 4 W / N per plane [oz in], W [lb], N [rpm] (API 617 7th ed. 2.6.2.7)."""
    w = _positive(weight_lb, "weight_lb", "residual_unbalance_us")
    n = float(_positive(speed_rpm, "speed_rpm", "residual_unbalance_us"))
    return np.atleast_1d(UNBALANCE_US * w / n)


def required_separation_margin(af: ArrayLike, below: ArrayLike) -> np.ndarray:
    """Separation margin API 617 requires of a resonance, as a fraction.

    With ``AF >= 2.5`` (API 617 7th ed. 2.6.2.10; API 684 SP6.8.2.10):

    - below the minimum operating speed: ``SM = 17 (1 - 1/(AF - 1.5))`` %, at most 16 %
      (of the minimum speed);
    - above the maximum continuous speed: ``SM = 10 + 17 (1 - 1/(AF - 1.5))`` %, at most
      26 % (of the MCS).

    A resonance with ``AF < 2.5`` is critically damped: no margin is required (0).

    Parameters
    ----------
    af : array
        Amplification factors.
    below : bool array
        True for a resonance below the operating range, False above it.

    Examples
    --------
    >>> required_separation_margin([2.0, 3.5, 3.5, 20.0], [True, True, False, False]).round(4)
    array([0.   , 0.085, 0.185, 0.26 ])
    """
    a = np.asarray(af, dtype=float)
    low = np.asarray(below, dtype=bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        base = 17.0 * (1.0 - 1.0 / (a - 1.5))
    margin = np.where(low, np.minimum(base, 16.0), np.minimum(10.0 + base, 26.0))
    return np.where(a >= AF_CRITICALLY_DAMPED, margin / 100.0, 0.0)


def vibration_limit(mcs_rpm: float) -> float:
    """Mechanical-test vibration limit Av1 = 25.4 sqrt(12000 / N) um peak-to-peak, at most
    25.4 um, in [m] (API 617 7th ed. 2.6.2.11 with 2.6.8.8).

    Examples
    --------
    >>> round(vibration_limit(12000.0) * 1e6, 3), round(vibration_limit(3000.0) * 1e6, 3)
    (25.4, 25.4)
    >>> round(vibration_limit(48000.0) * 1e6, 3)
    12.7
    """
    n = float(_positive(mcs_rpm, "mcs_rpm", "vibration_limit"))
    return min(25.4e-6 * math.sqrt(12000.0 / n), 25.4e-6)
