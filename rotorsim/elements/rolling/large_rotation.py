"""Large displacements and rotations of a 2-node bearing element (seed 001 section 2.4).

For multibody use the nodes A (inner ring) and B (outer ring) may translate and rotate
arbitrarily; the rotations are Euler (rotation) vectors ``theta`` with the rotation tensor
(seed 001 eqs 28-29)

    Q = I + h1 Theta + h2 Theta^2,   h1 = sin(t) / t,   h2 = (sin(t/2) / (t/2))^2 / 2,

``Theta = skew(theta)``, ``t = |theta|``. The bearing sees the relative displacement of the
outer ring in the frame of node A and the relative tilt (eqs 30, 36, 37)

    xi = Q_A^T (u_B - u_A),     gamma = Q_A^T (e_zA x e_zB),   e_z = Q e_z0,

and its force and tangent are mapped back by the operator ``H = d[xi; gamma] / dy``
(eqs 40-42): ``P = H^T p``, ``K = H^T k H`` with ``p``, ``k`` the bearing's generalised force
and tangent in the local frame. Eq 42 leaves out the geometric term ``dH^T/dy p``; here it is
added, computed by complex-step differentiation of ``H^T p`` (exact to round-off), so that
the tangent is the exact derivative of the force (DESIGN section 4). In the small-rotation
limit ``xi = u_B - u_A`` and ``gamma = theta_B - theta_A`` (x, y) and the element reduces
to the rotorsim convention ``delta = u_inner - u_outer = -[xi, gamma_x, gamma_y]``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.base import ElementForce, FloatArray
from rotorsim.errors import ModelError

Array = NDArray[Any]
_EZ = np.array([0.0, 0.0, 1.0])
_COMPLEX_STEP = 1e-30


def skew(v: Array) -> Array:
    """Skew tensors (..., 3, 3) of vectors (..., 3): ``skew(a) b = a x b``."""
    z = np.zeros_like(v[..., 0])
    return np.stack([np.stack([z, -v[..., 2], v[..., 1]], -1),
                     np.stack([v[..., 2], z, -v[..., 0]], -1),
                     np.stack([-v[..., 1], v[..., 0], z], -1)], -2)


def _coefficients(theta: Array) -> tuple[Array, Array, Array]:
    """``h1, h2, h3`` of seed 001 eqs 29 and 33, series near zero; complex-step safe
    (``t^2 = theta . theta`` without a modulus)."""
    t2 = np.sum(theta * theta, axis=-1)
    small = np.abs(t2) < 1e-6
    t = np.sqrt(np.where(small, 1.0, t2))
    h1 = np.where(small, 1 - t2 / 6 + t2 ** 2 / 120, np.sin(t) / t)
    half = np.where(small, 1.0, np.sin(t / 2) / (t / 2))
    h2 = np.where(small, 0.5 - t2 / 24 + t2 ** 2 / 720, 0.5 * half ** 2)
    h3 = np.where(small, 1 / 6 - t2 / 120 + t2 ** 2 / 5040,
                  (1 - h1) / np.where(small, 1.0, t2))
    return h1, h2, h3


def rotation_tensor(theta: ArrayLike) -> Array:
    """``Q`` (..., 3, 3) of rotation vectors (..., 3) (seed 001 eq 28)."""
    th = np.asarray(theta)
    T = skew(th)
    h1, h2, _ = _coefficients(th)
    return np.eye(3) + h1[..., None, None] * T + h2[..., None, None] * (T @ T)


def tangent_tensor(theta: ArrayLike) -> Array:
    """``Gamma`` (..., 3, 3) of seed 001 eq 32: ``delta(Q) = skew(Gamma delta theta) Q``."""
    th = np.asarray(theta)
    T = skew(th)
    _, h2, h3 = _coefficients(th)
    return np.eye(3) + h2[..., None, None] * T + h3[..., None, None] * (T @ T)


def relative_motion(y: ArrayLike) -> tuple[Array, Array]:
    """``y_rel = [xi; gamma]`` (S, 6) and ``H`` (S, 6, 12) from ``y = [u_A, theta_A, u_B,
    theta_B]`` (S, 12) (seed 001 eqs 30-41)."""
    yy = np.asarray(y)
    uA, thA, uB, thB = yy[:, 0:3], yy[:, 3:6], yy[:, 6:9], yy[:, 9:12]
    QA, QB = rotation_tensor(thA), rotation_tensor(thB)
    GA, GB = tangent_tensor(thA), tangent_tensor(thB)
    QAt = np.swapaxes(QA, -1, -2)
    xi = np.einsum("sij,sj->si", QAt, uB - uA)
    ezA, ezB = QA @ _EZ, QB @ _EZ
    gamma = np.einsum("sij,sj->si", QAt, np.cross(ezA, ezB))
    X, G, EA, EB = skew(xi), skew(gamma), skew(ezA), skew(ezB)
    GAt = np.swapaxes(GA, -1, -2)
    S = yy.shape[0]
    H = np.zeros((S, 6, 12), dtype=np.result_type(yy, float))
    H[:, 0:3, 0:3] = -QAt
    H[:, 0:3, 6:9] = QAt
    H[:, 0:3, 3:6] = X @ GAt
    H[:, 3:6, 3:6] = G @ GAt + QAt @ EB @ EA @ GA
    H[:, 3:6, 9:12] = -QAt @ EA @ EB @ GB
    return np.concatenate([xi, gamma], axis=1), H


@dataclass(frozen=True, eq=False)
class LargeRotationBearing:
    """A 2-node bearing element in large displacements and rotations (module docstring).

    Parameters
    ----------
    element : RollingBearing or FlexibleRingBearingElement
        A node-to-node bearing element (``n_link`` given); its small-rotation force law is
        evaluated at the local relative motion.

    Examples
    --------
    >>> import rotorsim as rs
    >>> ball = rs.BallBearing(n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794,
    ...                       Kn=8.5e9, f_i=0.52, f_o=0.52)
    >>> big = LargeRotationBearing(rs.RollingBearing(ball, n=0, n_link=1))
    >>> y = np.zeros((1, 12)); y[0, 1] = 10e-6          # inner ring 10 um up
    >>> float(big.force(y, 0 * y, 0.0, 0.0).f[0, 1]) > 0
    True
    """

    element: Any

    def __post_init__(self) -> None:
        if len(getattr(self.element, "nodes", ())) != 2:
            raise ModelError("large rotations need a node-to-node element (give n_link)",
                             str(getattr(self.element, "label", self.element)))

    @property
    def nodes(self) -> tuple[int, ...]:
        return tuple(self.element.nodes)

    @property
    def tag(self) -> Any:
        return getattr(self.element, "tag", None)

    @property
    def bearing(self) -> Any:
        return getattr(self.element, "bearing", None)

    def _local(self, y_rel: Array, v_rel: Array, phi: Any, speed: Any, internal: Any
               ) -> tuple[Array, Array, Array, Any]:
        """Local generalised force ``p`` (S, 6) on ``y_rel`` and tangents (S, 6, 6)."""
        S = y_rel.shape[0]
        u = np.zeros((S, 12))
        u[:, :5] = -y_rel[:, :5]  # delta = u_inner - u_outer = -[xi, gamma_x, gamma_y]
        w = np.zeros((S, 12))
        w[:, :5] = -v_rel[:, :5]
        out = self.element.force(u, w, phi, speed, internal)
        idx = np.arange(5)
        p = np.zeros((S, 6))
        p[:, :5] = -np.asarray(out.f)[:, idx]        # dE/dy_rel = -dE/ddelta
        k = np.zeros((S, 6, 6))
        c = np.zeros((S, 6, 6))
        k[:, :5, :5] = np.asarray(out.K)[:, :5, :5]  # sign squared
        c[:, :5, :5] = np.asarray(out.C)[:, :5, :5]
        return p, k, c, out.internal

    def force(self, u: ArrayLike, v: ArrayLike, phi: ArrayLike, speed: ArrayLike,
              internal: Any = None) -> ElementForce:
        """Force ``H^T p`` (S, 12) and its exact tangents (module docstring)."""
        y = np.atleast_2d(np.asarray(u, dtype=float))
        yd = np.atleast_2d(np.asarray(v, dtype=float))
        if y.shape[1] != 12 or yd.shape != y.shape:
            raise ModelError(f"expected (S, 12) displacements and velocities, got {y.shape}",
                             "LargeRotationBearing")
        y_rel, H = relative_motion(y)
        v_rel = np.einsum("sij,sj->si", H, yd)
        p, k, c, state = self._local(y_rel, v_rel, phi, speed, internal)
        f = np.einsum("sji,sj->si", H, p)
        K = np.swapaxes(H, 1, 2) @ k @ H + np.swapaxes(H, 1, 2) @ c @ _rate_jacobian(y, yd) \
            + _geometric(y, p)
        C = np.swapaxes(H, 1, 2) @ c @ H
        return ElementForce(f, K, C, state)


def _geometric(y: FloatArray, p: FloatArray) -> FloatArray:
    """``d(H^T p)/dy`` at fixed ``p`` (S, 12, 12) by complex steps (exact to round-off)."""
    S = y.shape[0]
    out = np.zeros((S, 12, 12))
    for j in range(12):
        yc = y.astype(complex)
        yc[:, j] += 1j * _COMPLEX_STEP
        _, H = relative_motion(yc)
        out[:, :, j] = np.einsum("sji,sj->si", H, p).imag / _COMPLEX_STEP
    return out


def _rate_jacobian(y: FloatArray, yd: FloatArray) -> FloatArray:
    """``d(H ydot)/dy`` (S, 6, 12): the local rates also change with the configuration."""
    S = y.shape[0]
    out = np.zeros((S, 6, 12))
    if not np.any(yd):
        return out
    for j in range(12):
        yc = y.astype(complex)
        yc[:, j] += 1j * _COMPLEX_STEP
        _, H = relative_motion(yc)
        out[:, :, j] = np.einsum("sij,sj->si", H, yd).imag / _COMPLEX_STEP
    return out
