"""Gather the restoring forces and tangents of a rotor's nonlinear elements (DESIGN section 4).

A :class:`NonlinearAssembly` knows, for each nonlinear element (rolling bearings), where
its DOFs sit among the free DOFs of a :class:`~rotorsim.assembly.system.RotorSystem`. It
works on the *nonlinear DOFs* only: the sorted union ``dofs`` of the free DOFs the elements
touch (``k`` of them). One call evaluates every element for ``S`` samples at once (a time
step passes ``S = 1``, harmonic balance all samples of a period):

    f (S, k), df/dq (S, k, k), df/dv (S, k, k) = assembly.evaluate(q_nl, v_nl, phi, speed)

Elements with identical parameters (the usual pair of equal bearings) share one batched
call, stacked over elements and samples. An element DOF that is fixed, or was removed as
unconnected by :func:`~rotorsim.assembly.system.assemble`, has zero displacement and its
force is dropped (it goes to ground).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.elements.base import DOFS_PER_NODE, FloatArray, NonlinearElement
from rotorsim.errors import ModelError

IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class _Group:
    """Elements evaluated by one batched call of ``element``."""

    element: NonlinearElement
    members: IntArray  # indices into NonlinearAssembly.elements (G,)
    positions: IntArray  # (G, nd) position of each element DOF in `dofs`, -1 if removed
    force_index: IntArray  # target position in (k,) of each kept entry of (G*nd,)
    force_kept: IntArray  # kept entries of the flattened (G*nd,) element forces
    tangent_index: IntArray  # target position in (k*k,) of each kept tangent entry
    tangent_kept: IntArray  # kept entries of the flattened (G*nd*nd,) element tangents
    distinct: bool  # no two element DOFs share a nonlinear DOF (plain assignment)
    complete: bool  # no element DOF was removed (positions >= 0 everywhere)
    member_list: tuple[int, ...]  # members as Python ints (cheap loops)

    def add_forces(self, total: FloatArray, fe: FloatArray, first: bool = False) -> None:
        """``total`` (S, k) += the element forces (S, G*nd) on their nonlinear DOFs
        (``first``: ``total`` is still zero)."""
        self._add(total, fe, self.force_index, self.force_kept, first)

    def add_tangents(self, total: FloatArray, ke: FloatArray, first: bool = False) -> None:
        """``total`` (S, k*k) += the element tangents (S, G*nd*nd)."""
        self._add(total, ke, self.tangent_index, self.tangent_kept, first)

    def _add(self, total: FloatArray, values: FloatArray, index: IntArray,
             kept: IntArray, first: bool) -> None:
        if not self.complete:
            values = values[:, kept]
        if not self.distinct:
            total += _scatter(values, index, total.shape[1])
        elif first:  # each target once into zeros: a plain assignment
            total[:, index] = values
        else:  # each target once: a buffered fancy-index add is exact
            total[:, index] += values

    def take(self, x: FloatArray) -> FloatArray:
        """``x[:, positions]`` as (S * G, nd) with zeros where an element DOF was removed."""
        if self.complete:
            return np.asarray(x.take(self.positions.reshape(-1), axis=1)).reshape(
                -1, self.positions.shape[1])
        return _take(x, self.positions).reshape(-1, self.positions.shape[1])


@dataclass(frozen=True, eq=False)
class NonlinearForces:
    """Restoring force and tangents on the nonlinear DOFs for ``S`` samples.

    Attributes
    ----------
    f : array (S, k)
        Restoring force ``r`` on the nonlinear DOFs [N, N m].
    K, C : arrays (S, k, k)
        ``dr/dq`` and ``dr/dv``.
    element_forces : tuple of arrays (S, nd)
        Each element's force on its own DOFs (``[:, :5]`` is the load its inner ring
        carries, ``[Fx, Fy, Fz, Mx, My]``).
    internal : tuple
        Each group's converged internal state (warm start of the next call).
    """

    f: FloatArray
    K: FloatArray
    C: FloatArray
    element_forces: tuple[FloatArray, ...]
    internal: tuple[Any, ...]


@dataclass(frozen=True, eq=False)
class NonlinearAssembly:
    """The nonlinear elements of a system with their DOF indices (module docstring).

    Use :meth:`build`.
    """

    n_free: int
    elements: tuple[NonlinearElement, ...]
    dofs: IntArray
    groups: tuple[_Group, ...]

    @classmethod
    def build(cls, elements: Sequence[NonlinearElement], full_to_free: IntArray,
              n_nodes: int) -> NonlinearAssembly:
        """Index the ``elements`` on a system with the given DOF map.

        Parameters
        ----------
        elements : sequence of NonlinearElement
        full_to_free : int array (6 n_nodes,)
            Free index of each DOF, -1 when fixed or removed.
        n_nodes : int
            Number of nodes of the system.

        Raises
        ------
        ModelError
            For an object that is not a nonlinear element, a node outside the system, or an
            element with all its DOFs fixed.
        """
        elements = tuple(elements)
        full_dofs = [_element_dofs(el, i, n_nodes) for i, el in enumerate(elements)]
        free = [np.asarray(full_to_free)[d] for d in full_dofs]
        for i, f in enumerate(free):
            if not np.any(f >= 0):
                raise ModelError("all its DOFs are fixed: it can exert no force",
                                 _label(elements[i], i))
        dofs = np.unique(np.concatenate([f[f >= 0] for f in free])) if free \
            else np.zeros(0, dtype=np.int64)
        keys: dict[tuple[Any, ...], list[int]] = {}
        for i, el in enumerate(elements):
            keys.setdefault(_batch_key(el, free[i].size), []).append(i)
        groups = tuple(_group(elements, members, free, dofs) for members in keys.values())
        return cls(_n_free(full_to_free), elements, dofs, groups)

    @property
    def k(self) -> int:
        """Number of nonlinear DOFs."""
        return int(self.dofs.size)

    def gather(self, x: ArrayLike) -> FloatArray:
        """Values on the nonlinear DOFs, ``x[..., dofs]``."""
        return np.asarray(x, dtype=float)[..., self.dofs]

    def evaluate_on(self, positions: NDArray[np.int64], q: NDArray[np.float64],
                    v: NDArray[np.float64], phi: ArrayLike, speed: ArrayLike, damped: bool
                    ) -> tuple[NDArray[np.float64], NDArray[np.float64],
                               NDArray[np.float64] | None]:
        """:meth:`evaluate` with ``q, v (S, p)`` given on the nonlinear DOFs at
        ``positions`` only (the others held at zero, their reactions dropped): force
        ``(S, p)``, ``df/dq`` and ``df/dv`` ``(S, p, p)`` (``None`` when not ``damped``)."""
        S = q.shape[0]
        full = positions.size == self.k
        qf, vf = (q, v) if full else (np.zeros((S, self.k)), np.zeros((S, self.k)))
        if not full:
            qf[:, positions], vf[:, positions] = q, v
        out = self.evaluate(qf, vf, phi, speed)
        if full:
            return out.f, out.K, out.C if damped else None
        ix = np.ix_(np.arange(S), positions, positions)
        return out.f[:, positions], out.K[ix], out.C[ix] if damped else None

    def evaluate(self, q: ArrayLike, v: ArrayLike, phi: ArrayLike, speed: ArrayLike,
                 internal: Sequence[Any] | None = None) -> NonlinearForces:
        """Forces and tangents of all elements for ``S`` samples.

        Parameters
        ----------
        q, v : array-like (S, k) or (k,)
            Displacements and velocities of the nonlinear DOFs [m, rad, m/s, rad/s].
        phi, speed : array-like (S,) or scalar
            Shaft angle [rad] and spin speed [rad/s] of each sample.
        internal : sequence, optional
            The ``internal`` of a previous call (warm start).

        Returns
        -------
        NonlinearForces
        """
        q2, v2 = _two_d(q), _two_d(v)
        S, k = q2.shape
        if k != self.k or v2.shape != (S, k):
            raise ModelError(f"expected (S, {self.k}) displacements and velocities, got "
                             f"{q2.shape} and {v2.shape}", "NonlinearAssembly.evaluate")
        phi_s, speed_s = _per_sample(phi, S), _per_sample(speed, S)
        f = np.zeros((S, k))
        K = np.zeros((S, k * k))
        C = np.zeros((S, k * k))
        per_element: list[FloatArray] = [np.zeros(0)] * len(self.elements)
        states = []
        for gi, g in enumerate(self.groups):
            G, nd = g.positions.shape
            u, w = g.take(q2), g.take(v2)
            warm = None if internal is None else internal[gi]
            phis, speeds = (phi_s, speed_s) if G == 1 else (phi_s.repeat(G),
                                                            speed_s.repeat(G))
            out = g.element.force(u, w, phis, speeds, warm)
            fe = np.asarray(out.f).reshape(S, G * nd)
            first = gi == 0
            g.add_forces(f, fe, first)
            g.add_tangents(K, np.asarray(out.K).reshape(S, G * nd * nd), first)
            g.add_tangents(C, np.asarray(out.C).reshape(S, G * nd * nd), first)
            per_sample = fe.reshape(S, G, nd)
            for j, m in enumerate(g.member_list):
                per_element[m] = per_sample[:, j]
            states.append(out.internal)
        return NonlinearForces(f, K.reshape(S, k, k), C.reshape(S, k, k),
                               tuple(per_element), tuple(states))


def _two_d(x: ArrayLike) -> FloatArray:
    """``np.atleast_2d`` of a float array."""
    arr = np.asarray(x, dtype=float)
    return arr if arr.ndim >= 2 else arr.reshape(1, -1)


def _per_sample(x: ArrayLike, n_samples: int) -> FloatArray:
    """A scalar or (S,) array as (S,) floats (a broadcast view of a scalar)."""
    arr = np.asarray(x, dtype=float)
    if arr.shape == (n_samples,):
        return arr
    if arr.ndim == 0:
        return arr.reshape(1).repeat(n_samples)
    return np.broadcast_to(arr, (n_samples,))


def _n_free(full_to_free: IntArray) -> int:
    return int(np.count_nonzero(np.asarray(full_to_free) >= 0))


def _label(el: Any, i: int) -> str:
    return str(getattr(el, "label", None) or getattr(el, "tag", None) or f"nonlinear[{i}]")


def _element_dofs(el: Any, i: int, n_nodes: int) -> IntArray:
    if not isinstance(el, NonlinearElement):
        raise ModelError(f"not a nonlinear element (needs nodes and force): {el!r}",
                         f"nonlinear[{i}]")
    nodes = np.asarray(el.nodes, dtype=np.int64)
    if nodes.size == 0 or nodes.min() < 0 or nodes.max() >= n_nodes:
        raise ModelError(f"nodes {tuple(nodes.tolist())} outside the system's 0..{n_nodes - 1}"
                         " (a housing node needs a point mass or a linear bearing in the "
                         "rotor)", _label(el, i))
    return (DOFS_PER_NODE * nodes[:, None] + np.arange(DOFS_PER_NODE)).reshape(-1)


def _batch_key(el: Any, nd: int) -> tuple[Any, ...]:
    """Elements with equal keys give equal forces for equal DOF values: everything but
    their node numbers and names (also of nested parameter objects) is equal."""
    return (nd, _parameters(el))


def _parameters(obj: Any) -> Any:
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        skip = {"n", "n_link", "tag", "nodes", "label"}
        return (type(obj), tuple((f.name, _parameters(getattr(obj, f.name)))
                                 for f in dataclasses.fields(obj)
                                 if f.name not in skip and f.init))
    return repr(obj)


def _take(x: FloatArray, positions: IntArray) -> FloatArray:
    """``x[:, positions]`` with zeros where ``positions < 0``: (S, G, nd)."""
    out = x[:, np.where(positions >= 0, positions, 0)]
    out[:, positions < 0] = 0.0
    return out


def _group(elements: tuple[Any, ...], members: list[int], free: list[IntArray],
           dofs: IntArray) -> _Group:
    positions = np.stack([np.where(free[m] >= 0, np.searchsorted(dofs, free[m]), -1)
                          for m in members])
    k = dofs.size
    flat = positions.reshape(-1)
    ok = np.flatnonzero(flat >= 0)
    rows = (positions[:, :, None] * k + positions[:, None, :]).reshape(-1)
    ok2 = np.flatnonzero(((positions[:, :, None] >= 0)
                          & (positions[:, None, :] >= 0)).reshape(-1))
    return _Group(elements[members[0]], np.asarray(members, dtype=np.int64), positions,
                  flat[ok], ok, rows[ok2], ok2, bool(np.unique(flat[ok]).size == ok.size),
                  bool(ok.size == flat.size), tuple(int(m) for m in members))


def _scatter(values: FloatArray, index: IntArray, size: int) -> FloatArray:
    """``out[s, index[j]] += values[s, j]`` (repeated indices add, by one bincount)."""
    S = values.shape[0]
    flat = (np.arange(S)[:, None] * size + index[None, :]).ravel()
    summed = np.bincount(flat, weights=values.ravel(), minlength=S * size)
    return np.asarray(summed, dtype=float).reshape(S, size)
