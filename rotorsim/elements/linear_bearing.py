"""Linear bearing, seal or support with speed-dependent coefficients.

The element connects a shaft node to ground, or to a second node (housing, pedestal,
casing) with ``n_link``. Its force on the shaft node is
``-(K d + C d' + Ms d'')`` with ``d = u_n - u_link`` (``u_link = 0`` for ground) in
``ux, uy, uz`` and, optionally, ``rx, ry``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from rotorsim.elements.base import ElementMatrices, FloatArray, as_float_array
from rotorsim.errors import ModelError

_LATERAL = ("xx", "xy", "yx", "yy")
COEFFICIENTS: tuple[str, ...] = (
    *(f"k{s}" for s in _LATERAL), "kzz", "krr", "ktt",
    *(f"c{s}" for s in _LATERAL), "czz", "crr", "ctt",
    *(f"m{s}" for s in _LATERAL),
)
"""Coefficient names: stiffness ``k``, damping ``c`` and added mass ``m``; ``zz`` axial,
``rr`` tilting (moment) about x and y, ``tt`` torsional (about z)."""


@dataclass(frozen=True, eq=False)
class BearingElement:
    """Linear bearing or seal, constant or tabulated against speed.

    Parameters
    ----------
    n : int
        Shaft node.
    kxx, kxy, kyx, kyy : float or array
        Lateral stiffness [N/m]; ``kyy`` defaults to ``kxx``. ``kxy`` is the force in x
        per unit displacement in y (cross-coupling).
    kzz : float or array
        Axial stiffness [N/m].
    krr : float or array
        Tilting stiffness about x and y [N m/rad].
    ktt : float or array
        Torsional stiffness about z [N m/rad] (couplings between shaft ends; bearings carry
        no torque).
    cxx, cxy, cyx, cyy, czz, crr, ctt : float or array
        Damping [N s/m, N m s/rad]; ``cyy`` defaults to ``cxx``.
    mxx, mxy, myx, myy : float or array
        Added mass [kg] (seals); ``myy`` defaults to ``mxx``.
    stiffness_matrix, damping_matrix : array (5, 5), optional
        Full coupled stiffness [N/m, N, N m/rad] and damping on the relative DOFs
        ``(x, y, z, rx, ry)``, added to the coefficients above (e.g. a rolling bearing
        linearised at its static load, whose stiffness couples radial, axial and tilt
        motion). Constant in speed.
    frequency : array, optional
        Spin speeds [rad/s] at which array coefficients are given, increasing. Between
        points coefficients are interpolated linearly; outside they are held at the end values.
    n_link : int, optional
        Second node (housing); ``None`` connects to ground.
    tag : str, optional
        Name used in messages.

    Examples
    --------
    >>> b = BearingElement(n=0, kxx=1e6, cxx=100.0)
    >>> float(b.matrices().K[1, 1])
    1000000.0
    >>> bs = BearingElement(n=0, kxx=[1e6, 2e6], frequency=[0.0, 100.0])
    >>> float(bs.coefficient("kyy", 50.0))
    1500000.0
    """

    n: int
    kxx: float | FloatArray = 0.0
    kyy: float | FloatArray | None = None
    kxy: float | FloatArray = 0.0
    kyx: float | FloatArray = 0.0
    kzz: float | FloatArray = 0.0
    krr: float | FloatArray = 0.0
    ktt: float | FloatArray = 0.0
    cxx: float | FloatArray = 0.0
    cyy: float | FloatArray | None = None
    cxy: float | FloatArray = 0.0
    cyx: float | FloatArray = 0.0
    czz: float | FloatArray = 0.0
    crr: float | FloatArray = 0.0
    ctt: float | FloatArray = 0.0
    mxx: float | FloatArray = 0.0
    myy: float | FloatArray | None = None
    mxy: float | FloatArray = 0.0
    myx: float | FloatArray = 0.0
    stiffness_matrix: FloatArray | None = None
    damping_matrix: FloatArray | None = None
    frequency: FloatArray | None = None
    n_link: int | None = None
    tag: str | None = None
    _table: dict[str, FloatArray] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        where = self.label
        for key, node in (("n", self.n), ("n_link", self.n_link)):
            if node is not None and (isinstance(node, bool)
                                     or not isinstance(node, int | np.integer) or node < 0):
                raise ModelError(f"{key} must be a non-negative integer, got {node!r}", where)
        if self.n_link is not None and self.n_link == self.n:
            raise ModelError(f"n_link must differ from n (both {self.n})", where)
        for key, default in (("kyy", "kxx"), ("cyy", "cxx"), ("myy", "mxx")):
            if getattr(self, key) is None:
                object.__setattr__(self, key, getattr(self, default))
        freq = (None if self.frequency is None
                else as_float_array(self.frequency, "frequency", where))
        if freq is not None:
            if freq.ndim != 1 or freq.size == 0 or not np.all(np.isfinite(freq)):
                raise ModelError("frequency must be a 1-D array of finite speeds", where)
            if np.any(np.diff(freq) <= 0):
                raise ModelError("frequency must be strictly increasing", where)
            object.__setattr__(self, "frequency", freq)
        table = {}
        for key in COEFFICIENTS:
            value = np.atleast_1d(as_float_array(getattr(self, key), key, where))
            if value.ndim != 1:
                raise ModelError(f"{key} must be a number or a 1-D array over frequency, got "
                                 f"shape {value.shape}", where)
            if not np.all(np.isfinite(value)):
                raise ModelError(f"{key} must be finite, got {getattr(self, key)!r}", where)
            if value.size > 1:
                if freq is None:
                    raise ModelError(f"{key} is an array but no frequency is given", where)
                if value.size != freq.size:
                    raise ModelError(
                        f"{key} has {value.size} values but frequency has {freq.size}", where
                    )
            table[key] = value
        for key in ("kxx", "kyy", "kzz", "krr", "ktt", "cxx", "cyy", "czz", "crr", "ctt",
                    "mxx", "myy"):
            if np.any(table[key] < 0):
                raise ModelError(f"direct coefficient {key} must be >= 0", where)
        object.__setattr__(self, "_table", table)
        for key in ("stiffness_matrix", "damping_matrix"):
            value = getattr(self, key)
            if value is None:
                continue
            matrix = as_float_array(value, key, where)
            if matrix.shape != (5, 5) or not np.all(np.isfinite(matrix)):
                raise ModelError(f"{key} must be a finite (5, 5) array on (x, y, z, rx, ry), "
                                 f"got shape {matrix.shape}", where)
            object.__setattr__(self, key, matrix)

    @property
    def label(self) -> str:
        return f"BearingElement '{self.tag}'" if self.tag else f"BearingElement(n={self.n})"

    @property
    def nodes(self) -> tuple[int, ...]:
        return (int(self.n),) if self.n_link is None else (int(self.n), int(self.n_link))

    @property
    def speed_dependent(self) -> bool:
        return any(v.size > 1 for v in self._table.values())

    def coefficient(self, name: str, speed: float | FloatArray) -> FloatArray:
        """Coefficient ``name`` at spin speed(s) ``speed`` [rad/s]."""
        values = self._table[name]
        if values.size == 1 or self.frequency is None:
            return np.broadcast_to(values[0], np.shape(speed)).astype(float)
        return np.asarray(np.interp(speed, self.frequency, values))

    @classmethod
    def coupling(cls, n: int, n_link: int, *, lateral: float = 0.0, angular: float = 0.0,
                 torsional: float = 0.0, axial: float = 0.0, lateral_damping: float = 0.0,
                 angular_damping: float = 0.0, torsional_damping: float = 0.0,
                 axial_damping: float = 0.0, tag: str | None = None) -> BearingElement:
        """A flexible coupling between two shaft ends ``n`` and ``n_link``.

        Parameters
        ----------
        n, n_link : int
            The two shaft ends (nodes of two lines, or of one line).
        lateral, angular, torsional, axial : float
            Stiffness [N/m, N m/rad, N m/rad, N/m] against relative radial offset, relative
            tilt (about x and y), relative twist (about z) and axial offset.
        lateral_damping, angular_damping, torsional_damping, axial_damping : float
            Damping in the same motions [N s/m, N m s/rad, N m s/rad, N s/m].
        tag : str, optional

        Examples
        --------
        >>> c = BearingElement.coupling(4, 5, lateral=1e7, angular=2e4, torsional=5e4)
        >>> m = c.matrices().K
        >>> float(m[5, 5]), float(m[5, 11]), float(m[3, 9])
        (50000.0, -50000.0, -20000.0)
        """
        return cls(n=n, n_link=n_link, kxx=lateral, krr=angular, ktt=torsional, kzz=axial,
                   cxx=lateral_damping, crr=angular_damping, ctt=torsional_damping,
                   czz=axial_damping, tag=tag)

    def with_node(self, n: int) -> BearingElement:
        import dataclasses

        return dataclasses.replace(self, n=n)

    def block_3x3(self, prefix: str, speed: float) -> FloatArray:
        """Lateral/axial block of ``k``, ``c`` or ``m`` at ``speed`` in (x, y, z) order."""
        g = lambda s: float(self.coefficient(f"{prefix}{s}", speed))  # noqa: E731
        zz = g("zz") if prefix != "m" else 0.0
        return np.array([[g("xx"), g("xy"), 0.0], [g("yx"), g("yy"), 0.0], [0.0, 0.0, zz]])

    def matrices(self, speed: float = 0.0) -> ElementMatrices:
        """Element matrices, ``(6, 6)`` to ground or ``(12, 12)`` node-to-node."""
        blocks = {}
        for prefix in ("k", "c", "m"):
            b = np.zeros((6, 6))
            b[:3, :3] = self.block_3x3(prefix, speed)
            if prefix != "m":
                rr = float(self.coefficient(f"{prefix}rr", speed))
                b[3, 3] = b[4, 4] = rr
                b[5, 5] = float(self.coefficient(f"{prefix}tt", speed))
                full = self.stiffness_matrix if prefix == "k" else self.damping_matrix
                if full is not None:
                    b[:5, :5] += full
            blocks[prefix] = b if self.n_link is None else np.block([[b, -b], [-b, b]])
        zero = np.zeros_like(blocks["k"])
        return ElementMatrices(M=blocks["m"], C=blocks["c"], G=zero, K=blocks["k"])
