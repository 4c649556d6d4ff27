"""Result of a Campbell analysis: tracked modes over a spin-speed grid."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.polynomial import polynomial as poly
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.results.critical_speeds import (
    CriticalSpeeds,
    check_harmonic,
    check_whirl_filter,
)

FloatArray = NDArray[np.float64]
StrArray = NDArray[np.str_]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class CampbellResult:
    """Damped natural frequencies tracked over spin speed.

    Column ``j`` of every ``(S, num_modes)`` array follows one physical mode through
    crossings and veering (see :func:`rotorsim.analyses.linear.campbell.campbell`). Rows of
    speeds whose modal analysis failed hold ``NaN`` (and ``""`` in the string arrays).

    Attributes
    ----------
    speeds : array (S,)
        Spin speeds [rad/s], increasing.
    wd, wn : array (S, num_modes)
        Damped and undamped natural frequencies [rad/s].
    log_dec, damping_ratio : array (S, num_modes)
        Logarithmic decrement and damping ratio [-].
    whirl_ratio : array (S, num_modes)
        Amplitude-weighted ``(rf - rb) / (rf + rb)``: +1 forward circular, -1 backward.
    whirl : str array (S, num_modes)
        ``"forward"``, ``"backward"``, ``"mixed"`` or ``"none"`` (non-lateral).
    kind : str array (S, num_modes)
        ``"lateral"``, ``"axial"`` or ``"torsional"``.
    tracking_mac : array (S, num_modes)
        MAC between a track's shape and its shape at the previous good speed (``NaN`` on
        the first row): values well below 1 flag a doubtful match (grid too coarse).
    status : int array (S,)
        :class:`~rotorsim.errors.Status` of every speed.
    notes : tuple of str
        Remarks on the result, e.g. fewer modes than ``num_modes`` at some speeds (their
        columns hold ``NaN`` there).

    Examples
    --------
    >>> s = np.array([0.0, 100.0, 200.0])
    >>> res = CampbellResult(
    ...     speeds=s, wd=np.array([[90.0], [110.0], [130.0]]), wn=np.full((3, 1), np.nan),
    ...     log_dec=np.zeros((3, 1)), damping_ratio=np.zeros((3, 1)),
    ...     whirl_ratio=np.ones((3, 1)), whirl=np.full((3, 1), "forward"),
    ...     kind=np.full((3, 1), "lateral"), tracking_mac=np.ones((3, 1)),
    ...     status=np.zeros(3, np.int64))
    >>> res.critical_speeds(harmonic=1).speed.round(6).tolist()
    [112.5]
    """

    speeds: FloatArray
    wd: FloatArray
    wn: FloatArray
    log_dec: FloatArray
    damping_ratio: FloatArray
    whirl_ratio: FloatArray
    whirl: StrArray
    kind: StrArray
    tracking_mac: FloatArray
    status: IntArray
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    summary: dict[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()

    @property
    def num_modes(self) -> int:
        """Number of tracked modes (columns of ``wd``)."""
        return int(self.wd.shape[1])

    def critical_speeds(self, harmonic: float = 1, whirl: str | None = None,
                        spool: str | None = None) -> CriticalSpeeds:
        """Crossings of every track with the excitation line ``w = harmonic * W``.

        A crossing is a sign change of ``wd - harmonic * W`` between two consecutive
        good speeds (a zero on a grid point counts once). It is located on the cubic
        through the four nearest good grid points around the bracketing interval
        (fewer points, down to linear, at the ends of the grid or next to a failed speed);
        the log decrement is interpolated linearly.

        Parameters
        ----------
        harmonic : float
            Excitation order ``k`` > 0 (1 for unbalance, 2 for misalignment, ...).
        whirl : {"forward", "backward"}, optional
            Keep only crossings of tracks whirling this way at the crossing.
        spool : str, optional
            On a machine of several lines: the exciting line. Its speed ratio ``r`` makes
            the line ``w = harmonic |r| W``; ``options["excites"]`` names the whirl its
            unbalance drives (forward for ``r > 0``, backward for ``r < 0``).

        Returns
        -------
        CriticalSpeeds
            Sorted by speed; ``mode`` is the track (column) index.
        """
        k = check_harmonic(harmonic, "CampbellResult.critical_speeds")
        ratios = self.summary.get("line_speed_ratios") or {"shaft": 1.0}
        if spool is not None:
            if spool not in ratios:
                raise ModelError(f"no line named {spool!r} (lines: {', '.join(ratios)})",
                                 "CampbellResult.critical_speeds")
            if ratios[spool] == 0:
                raise ModelError(f"line {spool!r} does not rotate (speed ratio 0)",
                                 "CampbellResult.critical_speeds")
            k = k * abs(float(ratios[spool]))
        check_whirl_filter(whirl, "CampbellResult.critical_speeds")
        rows: list[tuple[float, float, int, int]] = []  # speed, log_dec, track, nearest row
        for j in range(self.num_modes):
            rows.extend(self._track_crossings(j, k))
        rows.sort()
        speed = np.array([r[0] for r in rows], dtype=float)
        track = np.array([r[2] for r in rows], dtype=np.int64)
        near = np.array([r[3] for r in rows], dtype=np.int64)
        result = CriticalSpeeds(
            speed=speed, frequency=k * speed, mode=track,
            whirl=self.whirl[near, track].astype(str), kind=self.kind[near, track].astype(str),
            log_dec=np.array([r[1] for r in rows], dtype=float), harmonic=k,
            options={"source": "campbell", "interpolation": "local cubic (4 points)",
                     **({} if spool is None else {
                         "spool": spool, "excites": "forward" if ratios[spool] > 0
                         else "backward"})},
            summary=self.summary,
        )
        return result.select(whirl)

    def _track_crossings(self, j: int, k: float) -> list[tuple[float, float, int, int]]:
        s = self.speeds
        f = self.wd[:, j] - k * s
        good = np.isfinite(f)
        out = [(float(s[i]), float(self.log_dec[i, j]), j, int(i))
               for i in np.flatnonzero(good & (f == 0.0))]
        brackets = np.flatnonzero(good[:-1] & good[1:] & (f[:-1] * f[1:] < 0.0))
        for i in brackets:
            x = _root_in_interval(s, f, good, int(i))
            speed = s[i] + x * (s[i + 1] - s[i])
            ld = self.log_dec[i : i + 2, j]
            log_dec = ld[0] + x * (ld[1] - ld[0]) if np.all(np.isfinite(ld)) else \
                ld[int(x >= 0.5)]
            out.append((float(speed), float(log_dec), j, int(i + (x >= 0.5))))
        return out


def _root_in_interval(s: FloatArray, f: FloatArray, good: NDArray[np.bool_], i: int) -> float:
    """Root of the local interpolant of ``f`` in ``[s_i, s_i+1]`` as a fraction ``x``.

    The interpolant matches ``f`` at both ends, which have opposite signs, so Brent's
    method on ``[0, 1]`` always finds a root there.
    """
    lo, hi = i, i + 1
    if lo - 1 >= 0 and good[lo - 1]:
        lo -= 1
    if hi + 1 < s.size and good[hi + 1]:
        hi += 1
    h = s[i + 1] - s[i]
    x = (s[lo : hi + 1] - s[i]) / h
    y = f[lo : hi + 1]
    coef = poly.polyfit(x, y, deg=x.size - 1)
    if poly.polyval(0.0, coef) * poly.polyval(1.0, coef) >= 0.0:  # rounding: use the line
        return float(f[i] / (f[i] - f[i + 1]))
    from scipy.optimize import brentq  # slow to import: on first use

    return float(brentq(lambda t: float(poly.polyval(t, coef)), 0.0, 1.0, xtol=1e-14))
