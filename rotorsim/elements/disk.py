"""Rigid disk and point mass elements (one node)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from rotorsim.elements.base import ElementMatrices, check_finite
from rotorsim.errors import ModelError
from rotorsim.model.material import Material


@dataclass(frozen=True)
class DiskElement:
    """Rigid disk on a shaft node.

    Its mass acts in ``ux, uy, uz``, the diametral inertia in ``rx, ry``, the polar inertia
    in ``rz`` and in the gyroscopic matrix ``G[rx, ry] = Ip = -G[ry, rx]``.

    Parameters
    ----------
    n : int
        Node number.
    m : float
        Mass [kg].
    Id : float
        Diametral (transverse) moment of inertia [kg m^2].
    Ip : float
        Polar moment of inertia [kg m^2].
    tag : str, optional
        Name used in messages.

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> d = DiskElement.from_geometry(2, steel, width=0.07, i_d=0.05, o_d=0.28)
    >>> round(d.m, 3), round(d.Id, 5), round(d.Ip, 5)
    (32.59, 0.17809, 0.32956)
    """

    n: int
    m: float
    Id: float
    Ip: float
    tag: str | None = None

    def __post_init__(self) -> None:
        where = self.label
        if isinstance(self.n, bool) or not isinstance(self.n, int | np.integer) or self.n < 0:
            raise ModelError(f"node number must be a non-negative integer, got {self.n!r}", where)
        check_finite(self.m, "m", where, positive=True)
        check_finite(self.Id, "Id", where, nonnegative=True)
        check_finite(self.Ip, "Ip", where, nonnegative=True)

    @property
    def label(self) -> str:
        return f"DiskElement '{self.tag}'" if self.tag else f"DiskElement(n={self.n})"

    @property
    def nodes(self) -> tuple[int, ...]:
        return (int(self.n),)

    @classmethod
    def from_geometry(
        cls, n: int, material: Material, width: float, i_d: float, o_d: float,
        tag: str | None = None,
    ) -> DiskElement:
        """Disk from a solid annulus.

        ``m = rho pi/4 (o_d^2 - i_d^2) width``, ``Ip = m (o_d^2 + i_d^2) / 8``,
        ``Id = Ip / 2 + m width^2 / 12``.

        Parameters
        ----------
        n : int
            Node number.
        material : Material
            Disk material.
        width, i_d, o_d : float
            Axial width, bore and outer diameter [m].
        """
        where = f"DiskElement(n={n})" if tag is None else f"DiskElement '{tag}'"
        if not isinstance(material, Material):
            raise ModelError(f"material must be a Material, got {type(material).__name__}",
                             where)
        check_finite(width, "width", where, positive=True)
        check_finite(i_d, "i_d", where, nonnegative=True)
        check_finite(o_d, "o_d", where, positive=True)
        if i_d >= o_d:
            raise ModelError(f"bore i_d={i_d} m must be < outer diameter o_d={o_d} m", where)
        m = material.rho * math.pi / 4.0 * (o_d**2 - i_d**2) * width
        Ip = m * (o_d**2 + i_d**2) / 8.0
        Id = Ip / 2.0 + m * width**2 / 12.0
        return cls(n=n, m=m, Id=Id, Ip=Ip, tag=tag)

    def with_node(self, n: int) -> DiskElement:
        return dataclasses.replace(self, n=n)

    def matrices(self, speed: float = 0.0) -> ElementMatrices:
        """Element matrices ``(6, 6)``; independent of ``speed``."""
        M = np.diag([self.m, self.m, self.m, self.Id, self.Id, self.Ip]).astype(float)
        G = np.zeros((6, 6))
        G[3, 4], G[4, 3] = self.Ip, -self.Ip
        zero = np.zeros((6, 6))
        return ElementMatrices(M=M, C=zero, G=G, K=zero.copy())


@dataclass(frozen=True)
class PointMass:
    """Lumped translational mass on a node (housing, pedestal, coupling hub).

    Parameters
    ----------
    n : int
        Node number.
    m : float
        Mass in every direction [kg]; ``mx, my, mz`` override it per direction.
    """

    n: int
    m: float = 0.0
    mx: float | None = None
    my: float | None = None
    mz: float | None = None
    tag: str | None = None

    def __post_init__(self) -> None:
        where = self.label
        if isinstance(self.n, bool) or not isinstance(self.n, int | np.integer) or self.n < 0:
            raise ModelError(f"node number must be a non-negative integer, got {self.n!r}", where)
        for key in ("m", "mx", "my", "mz"):
            value = getattr(self, key)
            if value is not None:
                check_finite(value, key, where, nonnegative=True)
        if max(self.masses) <= 0:
            raise ModelError("mass must be > 0 in at least one direction", where)

    @property
    def nodes(self) -> tuple[int, ...]:
        return (int(self.n),)

    @property
    def label(self) -> str:
        return f"PointMass '{self.tag}'" if self.tag else f"PointMass(n={self.n})"

    @property
    def masses(self) -> tuple[float, float, float]:
        return tuple(  # type: ignore[return-value]
            self.m if v is None else v for v in (self.mx, self.my, self.mz)
        )

    def with_node(self, n: int) -> PointMass:
        return dataclasses.replace(self, n=n)

    def matrices(self, speed: float = 0.0) -> ElementMatrices:
        M = np.zeros((6, 6))
        M[[0, 1, 2], [0, 1, 2]] = self.masses
        zero = np.zeros((6, 6))
        return ElementMatrices(M=M, C=zero, G=zero.copy(), K=zero.copy())
