"""Two-node Timoshenko shaft element with hollow and linearly tapered sections.

The element has 6 DOFs per node (``ux, uy, uz, rx, ry, rz``). Bending in the x-z plane
uses ``(ux, ry)`` with ``ry = dux/dz`` in the Euler-Bernoulli limit; bending in the y-z
plane uses ``(uy, rx)`` with ``rx = -duy/dz``. Axial (``uz``) and torsional (``rz``)
motion use linear interpolation.

Bending uses the interdependent interpolation of the Timoshenko beam: cubic lateral
displacement and quadratic rotation fields that depend on the shear parameter
``Phi = 12 E I / (kappa G A L^2)`` and make the shear strain constant along the element.
For a uniform element these fields solve the static Timoshenko equations exactly, so
the stiffness matrix is exact and the mass, rotary-inertia and gyroscopic matrices are the
classical consistent ones (Friswell et al. 2010, section 5.4). For a tapered element the
bending stiffness is the inverse of the exact cantilever flexibility of the frustum
(:mod:`rotorsim.elements.beam_flexibility`), so it stays statically exact; the other
matrices are integrated over the varying section by 6-point Gauss-Legendre quadrature
(exact for a linear taper in diameter) with the interpolation at the shear parameter
``Phi = 4 f_shear / f_bending`` of the same flexibilities. With shear the frequencies
converge at order 2 in the element length (the shear strain is constant per element),
at order 4 without (docs/validation.md, case 1).

All matrices are computed for a batch of elements at once (:func:`shaft_matrices`).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from rotorsim.elements.base import ElementMatrices, FloatArray, check_finite
from rotorsim.elements.beam_flexibility import XI_FLEX, plane_bending_stiffness
from rotorsim.errors import ModelError
from rotorsim.model.material import Material

_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(6)
_XI = 0.5 * (_GAUSS_X + 1.0)  # quadrature points on [0, 1]
_WQ = 0.5 * _GAUSS_W


def cowper_shear_coefficient(nu: float | FloatArray, ratio: float | FloatArray) -> FloatArray:
    """Shear coefficient of a hollow circular section (Cowper 1966).

    ``kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2)``
    with ``m = inner / outer diameter``; ``6 (1 + nu) / (7 + 6 nu)`` for a solid section.

    Parameters
    ----------
    nu : float or array
        Poisson ratio [-].
    ratio : float or array
        Inner-to-outer diameter ratio [-].
    """
    m2 = np.asarray(ratio, dtype=float) ** 2
    nu = np.asarray(nu, dtype=float)
    a = (1.0 + m2) ** 2
    return np.asarray(6.0 * (1.0 + nu) * a / ((7.0 + 6.0 * nu) * a + (20.0 + 12.0 * nu) * m2))


@dataclass(frozen=True)
class ShaftElement:
    """Two-node Timoshenko beam element of a rotating shaft.

    Element ``i`` of a rotor joins node ``n`` and ``n + 1``; leave ``n`` as ``None`` and the
    :class:`~rotorsim.model.rotor.Rotor` numbers elements in order.

    Parameters
    ----------
    L : float
        Length [m].
    idl, odl : float
        Inner and outer diameter at the left (lower-z) end [m].
    material : Material
        Shaft material.
    idr, odr : float, optional
        Inner and outer diameter at the right end [m]; default to the left values.
        Different values make a linearly tapered (conical) element.
    n : int, optional
        Left node number.
    shear_effects, rotary_inertia, gyroscopic : bool
        Switch shear deformation (off gives Euler-Bernoulli), rotary inertia of the
        section and the gyroscopic matrix.
    axial_force : float
        Constant axial force [N], tension positive, for the geometric stiffness.
    shear_coefficient : float, optional
        Timoshenko shear coefficient; default Cowper's value for a hollow circle,
        :func:`cowper_shear_coefficient`.
    alpha, beta : float
        Rayleigh damping ``C = alpha M + beta K`` [1/s, s].
    tag : str, optional
        Name used in messages.

    Examples
    --------
    >>> from rotorsim.model.material import steel
    >>> el = ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel)
    >>> mats = el.matrices()
    >>> round(float(mats.M[0, 0] + mats.M[0, 6]), 4) == round(el.mass / 2, 4)
    True
    """

    L: float
    idl: float
    odl: float
    material: Material
    idr: float | None = None
    odr: float | None = None
    n: int | None = None
    shear_effects: bool = True
    rotary_inertia: bool = True
    gyroscopic: bool = True
    axial_force: float = 0.0
    shear_coefficient: float | None = None
    alpha: float = 0.0
    beta: float = 0.0
    tag: str | None = None

    def __post_init__(self) -> None:
        where = self.label
        if not isinstance(self.material, Material):
            raise ModelError("material is missing or not a Material", where)
        if self.idr is None:
            object.__setattr__(self, "idr", self.idl)
        if self.odr is None:
            object.__setattr__(self, "odr", self.odl)
        check_finite(self.L, "L (length)", where, positive=True)
        for key in ("idl", "idr"):
            check_finite(getattr(self, key), key, where, nonnegative=True)
        for key in ("odl", "odr"):
            check_finite(getattr(self, key), key, where, positive=True)
        for inner, outer in (("idl", "odl"), ("idr", "odr")):
            if getattr(self, inner) >= getattr(self, outer):
                raise ModelError(
                    f"inner diameter {inner}={getattr(self, inner)} m must be < outer "
                    f"diameter {outer}={getattr(self, outer)} m",
                    where,
                )
        check_finite(self.axial_force, "axial_force", where)
        check_finite(self.alpha, "alpha", where, nonnegative=True)
        check_finite(self.beta, "beta", where, nonnegative=True)
        if self.shear_coefficient is not None:
            check_finite(self.shear_coefficient, "shear_coefficient", where, positive=True)

    @property
    def label(self) -> str:
        name = f"'{self.tag}'" if self.tag else f"[{self.n}]" if self.n is not None else ""
        return f"ShaftElement{name}"

    @property
    def nodes(self) -> tuple[int, ...]:
        if self.n is None:
            raise ModelError("element has no node number; add it to a Rotor first", self.label)
        return (self.n, self.n + 1)

    @property
    def tapered(self) -> bool:
        return self.idl != self.idr or self.odl != self.odr

    @property
    def volume(self) -> float:
        """Material volume [m^3] (exact for a linear taper in diameter)."""
        return float(np.sum(_WQ * _section(self, _XI)[0]) * self.L)

    @property
    def mass(self) -> float:
        """Mass [kg]."""
        return self.volume * self.material.rho

    def with_node(self, n: int) -> ShaftElement:
        """Copy numbered as joining nodes ``n`` and ``n + 1`` (already validated)."""
        out = copy.copy(self)
        object.__setattr__(out, "n", int(n))
        return out

    def matrices(self, speed: float = 0.0) -> ElementMatrices:
        """Element matrices ``(12, 12)``; independent of ``speed``."""
        batch = shaft_matrices([self])
        return ElementMatrices(batch.M[0], batch.C[0], batch.G[0], batch.K[0])


def _section(el: ShaftElement, xi: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Area, second moment of area and diameter ratio at fractions ``xi`` of the length."""
    assert el.idr is not None and el.odr is not None
    do = el.odl + (el.odr - el.odl) * xi
    di = el.idl + (el.idr - el.idl) * xi
    area = math.pi / 4.0 * (do**2 - di**2)
    inertia = math.pi / 64.0 * (do**4 - di**4)
    return area, inertia, di / do


def shaft_matrices(elements: Sequence[ShaftElement]) -> ElementMatrices:
    """Matrices of many shaft elements at once.

    Parameters
    ----------
    elements : sequence of ShaftElement
        ``E`` elements.

    Returns
    -------
    ElementMatrices
        Arrays of shape ``(E, 12, 12)``.
    """
    props = _batch_properties(elements)
    fields = _shape_fields(props["L"], props["phi"])
    return _integrate(props, fields)


def _batch_properties(elements: Sequence[ShaftElement]) -> dict[str, FloatArray]:
    geometry = np.array([(e.idl, e.odl, e.idr, e.odr) for e in elements], dtype=float)
    area, inertia, _ = _sections(geometry, _XI)

    def col(fn):  # per-element scalar as a column (E, 1)
        return np.array([fn(el) for el in elements], dtype=float)[:, None]

    E, G, rho = (col(lambda e, k=k: getattr(e.material, k)) for k in ("E", "G_s", "rho"))
    nu = col(lambda e: e.material.nu)
    given = col(lambda e: e.shear_coefficient if e.shear_coefficient is not None else np.nan)
    length = col(lambda e: e.L)[:, 0]
    shear_on = col(lambda e: float(e.shear_effects))

    def kappa(r):
        return np.where(np.isnan(given), cowper_shear_coefficient(nu, r), given)

    area_f, inertia_f, ratio_f = _sections(geometry, XI_FLEX)
    inv_kga = shear_on / (kappa(ratio_f) * G * area_f)
    bending, phi = plane_bending_stiffness(length, E * inertia_f, inv_kga)
    return {
        "L": length,
        "phi": phi,
        "K_bending": bending,
        "EA": E * area,
        "GJ": G * 2.0 * inertia,
        "rhoA": rho * area,
        "rhoI": col(lambda e: float(e.rotary_inertia)) * rho * inertia,
        "rhoJ": rho * 2.0 * inertia,
        "rhoJ_gyro": col(lambda e: float(e.gyroscopic)) * rho * 2.0 * inertia,
        "P": np.broadcast_to(col(lambda e: e.axial_force), area.shape),
        "alpha": col(lambda e: e.alpha)[:, 0],
        "beta": col(lambda e: e.beta)[:, 0],
    }


def _sections(geometry: FloatArray, xi: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Area, second moment and diameter ratio ``(E, Q)`` at fractions ``xi`` of the lengths
    of elements with ``geometry`` rows ``(idl, odl, idr, odr)``."""
    x = xi[None, :]
    di = geometry[:, [0]] + (geometry[:, [2]] - geometry[:, [0]]) * x
    do = geometry[:, [1]] + (geometry[:, [3]] - geometry[:, [1]]) * x
    return math.pi / 4.0 * (do**2 - di**2), math.pi / 64.0 * (do**4 - di**4), di / do


def _shape_fields(length: FloatArray, phi: FloatArray) -> dict[str, FloatArray]:
    """Interpolation rows ``(E, Q, 12)`` of every field and of its z-derivative."""
    n_el = length.size
    x = _XI[None, :]
    L = length[:, None]
    p = phi[:, None]
    d = 1.0 + p
    # plane bending fields on [w1, theta1, w2, theta2] with theta = dw/dz (EB limit)
    w = np.stack(
        [
            (1 - 3 * x**2 + 2 * x**3 + p * (1 - x)) / d,
            L * (x - 2 * x**2 + x**3 + p / 2 * (x - x**2)) / d,
            (3 * x**2 - 2 * x**3 + p * x) / d,
            L * (-(x**2) + x**3 + p / 2 * (x**2 - x)) / d,
        ],
        axis=-1,
    )
    dw = np.stack(
        [
            (-6 * x + 6 * x**2 - p) / (d * L),
            (1 - 4 * x + 3 * x**2 + p / 2 * (1 - 2 * x)) / d,
            (6 * x - 6 * x**2 + p) / (d * L),
            (-2 * x + 3 * x**2 + p / 2 * (2 * x - 1)) / d,
        ],
        axis=-1,
    )
    t = np.stack(
        [
            6 * (x**2 - x) / (d * L),
            (1 - 4 * x + 3 * x**2 + p * (1 - x)) / d,
            6 * (x - x**2) / (d * L),
            (-2 * x + 3 * x**2 + p * x) / d,
        ],
        axis=-1,
    )
    dt = np.stack(
        [
            6 * (2 * x - 1) / (d * L**2),
            (-4 + 6 * x - p) / (d * L),
            6 * (1 - 2 * x) / (d * L**2),
            (-2 + 6 * x + p) / (d * L),
        ],
        axis=-1,
    )
    ones = np.ones((n_el, _XI.size))
    lin = np.stack([ones * (1 - x), ones * x], axis=-1)
    dlin = np.stack([-ones / L, ones / L], axis=-1)

    def place(values, idx, signs=None):
        out = np.zeros((n_el, _XI.size, 12))
        vals = values if signs is None else values * np.asarray(signs)
        out[..., idx] = vals
        return out

    ix, iy, iz, irz = [0, 4, 6, 10], [1, 3, 7, 9], [2, 8], [5, 11]
    sy = [1.0, -1.0, 1.0, -1.0]  # y-plane DOFs are [uy1, -rx1, uy2, -rx2]
    return {
        "ux": place(w, ix), "dux": place(dw, ix),
        "ry": place(t, ix), "dry": place(dt, ix),
        "uy": place(w, iy, sy), "duy": place(dw, iy, sy),
        # rx = -theta of the y-z plane
        "rx": place(-t, iy, sy), "drx": place(-dt, iy, sy),
        "uz": place(lin, iz), "duz": place(dlin, iz),
        "rz": place(lin, irz), "drz": place(dlin, irz),
    }


def _gram(coef: FloatArray, a: FloatArray, b: FloatArray | None = None) -> FloatArray:
    """``sum_q w_q coef_q a_q^T b_q`` per element, shape (E, 12, 12) (times L by caller)."""
    b = a if b is None else b
    weighted = a * (coef * _WQ)[:, :, None]
    return np.matmul(weighted.transpose(0, 2, 1), b)


_PLANES = ((np.array([0, 4, 6, 10]), np.ones(4)),  # x-z plane: [ux1, ry1, ux2, ry2]
           (np.array([1, 3, 7, 9]), np.array([1.0, -1.0, 1.0, -1.0])))  # [uy1, -rx1, ...]


def _integrate(props: dict[str, FloatArray], f: dict[str, FloatArray]) -> ElementMatrices:
    L = props["L"][:, None, None]
    K = (
        _gram(props["EA"], f["duz"]) + _gram(props["GJ"], f["drz"])
        + _gram(props["P"], f["dux"]) + _gram(props["P"], f["duy"])
    ) * L
    for idx, sign in _PLANES:
        K[:, idx[:, None], idx[None, :]] += props["K_bending"] * np.outer(sign, sign)
    M = (
        _gram(props["rhoA"], f["ux"]) + _gram(props["rhoA"], f["uy"])
        + _gram(props["rhoA"], f["uz"])
        + _gram(props["rhoI"], f["rx"]) + _gram(props["rhoI"], f["ry"])
        + _gram(props["rhoJ"], f["rz"])
    ) * L
    half = _gram(props["rhoJ_gyro"], f["rx"], f["ry"]) * L
    G = half - np.swapaxes(half, 1, 2)
    K = 0.5 * (K + np.swapaxes(K, 1, 2))
    M = 0.5 * (M + np.swapaxes(M, 1, 2))
    C = props["alpha"][:, None, None] * M + props["beta"][:, None, None] * K
    return ElementMatrices(M=M, C=C, G=G, K=K)
