"""Read the rotor files of ROSS (``Rotor.save``, TOML or JSON) into a rotorsim
:class:`~rotorsim.model.rotor.Rotor` (:func:`from_ross`).

A ROSS file holds ``ross_version``, ``[parameters]`` (the rotor's Rayleigh damping) and
one table per element named ``"<Class>_<tag>"``. Supported classes and how they map:

- ``ShaftElement``: ``L, idl, odl, idr, odr, n``, its ``material`` (``E, G_s, rho``), the
  ``shear_effects, rotary_inertia, gyroscopic`` switches, ``axial_force``, ``alpha, beta``;
  the Cowper shear coefficient (ROSS's ``shear_method_calc = "cowper"``) is rotorsim's.
  ROSS allows several elements on one node pair (layers, e.g. an impeller hub modelled as a
  sleeve of negligible stiffness around the shaft): the stiffest layer is the element,
  and the others, which must carry no load (bending stiffness below
  :data:`LAYER_STIFFNESS_LIMIT` of the element's), are lumped as disks on the two nodes
  (half the mass each, with the polar and diametral inertia of each half about its node).
- ``DiskElement``: ``n, m, Id, Ip``.
- ``BearingElement`` and ``SealElement``: the coefficients ``k.., c.., m..`` (constant or
  tabulated over ``speed``) and ``n_link``; tables follow ROSS's interpolation
  (:mod:`rotorsim.io.ross_tables`).
- ``PointMass``: ``n, mx, my, mz``.
- ``[parameters] alpha, beta``: ROSS damps the assembled shaft, disks and point masses
  with ``alpha M0 + beta K0`` (bearings excluded); rotorsim's system ``alpha`` and each
  shaft element's ``beta`` give the same matrix (disks and point masses have no stiffness).

Any other element class (magnetic, rolling or fluid-flow bearings computed by ROSS,
couplings, motors), coefficients over whirl frequency, a non-zero ``torque``,
``mzz`` or modal damping raise :class:`RossImportError`, naming the element.
"""

from __future__ import annotations

import json
import math
import os
import tomllib
from collections import defaultdict
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from rotorsim.elements.disk import DiskElement, PointMass
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.io.ross_tables import coefficient_tables
from rotorsim.model.damping import SystemDamping
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

SUPPORTED = ("ShaftElement", "DiskElement", "BearingElement", "SealElement", "PointMass")
LAYER_STIFFNESS_LIMIT = 1e-3
"""Largest bending stiffness E I of a lumped shaft layer, relative to its node pair's
element."""


class RossImportError(ModelError):
    """A ROSS rotor file holds something rotorsim cannot represent (named in the message)."""


def from_ross(source: str | os.PathLike[str] | Mapping[str, Any], *, refine: int = 8,
              speed_range: tuple[float, float] | None = None) -> Rotor:
    """A rotorsim rotor from a ROSS rotor file (``ross.Rotor.save``).

    Parameters
    ----------
    source : path or mapping
        A ``.toml`` or ``.json`` file written by ROSS, or its parsed content.
    refine : int
        Samples inside each interval of a bearing table interpolated by ROSS's cubic
        (:mod:`rotorsim.io.ross_tables`).
    speed_range : (float, float), optional
        Speeds [rad/s] to be analysed: bearing tables are extended to them by ROSS's linear
        extrapolation (rotorsim holds the end values outside a table).

    Returns
    -------
    Rotor
        Tagged with the file's stem (``"ross"`` for a mapping).

    Raises
    ------
    RossImportError
        An element class or option rotorsim does not support, naming the element.
    ModelError
        An unreadable file or invalid element data.

    Examples
    --------
    >>> data = {"ross_version": "3.1.0", "parameters": {"alpha": 0.0, "beta": 0.0},
    ...         "ShaftElement_S0": {"L": 0.5, "idl": 0.0, "odl": 0.05, "n": 0,
    ...             "material": {"name": "steel", "E": 211e9, "G_s": 81.2e9, "rho": 7810.0}},
    ...         "BearingElement_B0": {"n": 0, "kxx": [1e6], "kyy": [1e6]},
    ...         "BearingElement_B1": {"n": 1, "kxx": [1e6], "kyy": [1e6]}}
    >>> rotor = from_ross(data)
    >>> rotor.n_nodes, [b.tag for b in rotor.bearing_elements]
    (2, ['B0', 'B1'])
    """
    data, name = _read(source)
    version = str(data.get("ross_version", "unknown"))
    speed_key = "frequency" if version.split(".")[0] in ("0", "1", "2") else "speed"
    alpha, beta = _damping(data.get("parameters", {}))
    groups: dict[str, list[tuple[str, Mapping[str, Any]]]] = defaultdict(list)
    for key, table in data.items():
        if key in ("parameters", "ross_version") or key.startswith("_"):
            continue
        cls = key.split("_", 1)[0]
        if cls not in SUPPORTED or not isinstance(table, Mapping):
            raise RossImportError(f"ROSS element class '{cls}' is not supported (rotorsim "
                                  f"reads {', '.join(SUPPORTED)})", f"ROSS element '{key}'")
        groups[cls].append((key, table))
    shaft, sleeves = _shaft(groups["ShaftElement"], beta)
    disks = [_disk(key, t) for key, t in groups["DiskElement"]]
    bearings = [_bearing(key, t, speed_key, refine, speed_range)
                for key, t in [*groups["BearingElement"], *groups["SealElement"]]]
    masses = [_point_mass(key, t) for key, t in groups["PointMass"]]
    return Rotor(shaft, [*disks, *sleeves], bearings, masses, fixed=_held(shaft, masses),
                 tag=name, damping=SystemDamping(alpha=alpha) if alpha else None)


def _held(shaft: list[ShaftElement], masses: list[PointMass]) -> list[tuple[int, str]]:
    """The DOFs of support nodes (beyond the shaft) without mass: their rotations, and a
    direction in which the point mass has none (ROSS drops such DOFs from its modes)."""
    held = []
    for pm in masses:
        if pm.n > len(shaft):
            held += [(int(pm.n), dof) for dof in ("rx", "ry", "rz")]
            held += [(int(pm.n), dof) for dof, m in zip(("ux", "uy", "uz"), pm.masses,
                                                        strict=True) if m == 0.0]
    return held


def _read(source: str | os.PathLike[str] | Mapping[str, Any]) -> tuple[Mapping[str, Any], str]:
    if isinstance(source, Mapping):
        return source, "ross"
    path = Path(source)
    text = path.read_text(encoding="utf-8")
    try:
        data = json.loads(text) if path.suffix.lower() == ".json" else tomllib.loads(text)
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as err:
        raise ModelError(f"not a ROSS rotor file: {err}", str(path)) from None
    if not any("_" in key and isinstance(v, Mapping) for key, v in data.items()):
        raise ModelError("no ROSS elements (tables named '<Class>_<tag>')", str(path))
    return data, path.stem


def _damping(parameters: Mapping[str, Any]) -> tuple[float, float]:
    """``(alpha, beta)`` of the rotor; modal damping is refused."""
    if parameters.get("modal_damping_ratio") not in (None, [], 0, 0.0):
        raise RossImportError("modal damping ratios of ROSS are not supported",
                              "ROSS parameters")
    return float(parameters.get("alpha") or 0.0), float(parameters.get("beta") or 0.0)


def _tag(key: str, table: Mapping[str, Any]) -> str:
    return str(table.get("tag") or key.split("_", 1)[1])


def _material(table: Mapping[str, Any], where: str) -> Material:
    mat = table.get("material")
    if not isinstance(mat, Mapping):
        raise ModelError("no material table", where)
    return Material(name=str(mat.get("name", "material")), E=float(mat["E"]),
                    rho=float(mat["rho"]), G_s=float(mat["G_s"]))


def _shaft(items: list[tuple[str, Mapping[str, Any]]], beta: float
           ) -> tuple[list[ShaftElement], list[DiskElement]]:
    """The shaft elements in node order (one per node pair) and the lumped layers."""
    by_node: dict[int, list[ShaftElement]] = defaultdict(list)
    for key, t in items:
        by_node[int(t["n"])].append(_shaft_element(key, t, beta))
    if sorted(by_node) != list(range(len(by_node))):
        raise RossImportError(f"shaft elements must join nodes 0, 1, 2, ... in a row; they "
                              f"start at nodes {sorted(by_node)}", "ROSS shaft")
    shaft, lumps = [], []
    for n in range(len(by_node)):
        layers = sorted(by_node[n], key=_bending_stiffness, reverse=True)
        main = layers[0]
        for layer in layers[1:]:
            if _bending_stiffness(layer) > LAYER_STIFFNESS_LIMIT * _bending_stiffness(main):
                raise RossImportError(
                    f"layers {main.tag!r} and {layer.tag!r} both carry load on nodes {n}, "
                    f"{n + 1}: rotorsim has one shaft element per node pair (only layers of "
                    "negligible stiffness are lumped)", f"ROSS shaft element '{layer.tag}'")
            lumps += _lumped(layer, n)
        shaft.append(main)
    return shaft, _merge_lumps(lumps)


def _shaft_element(key: str, t: Mapping[str, Any], beta: float) -> ShaftElement:
    tag = _tag(key, t)
    where = f"ROSS shaft element '{tag}'"
    if float(t.get("torque", 0.0) or 0.0) != 0.0:
        raise RossImportError("a non-zero torque (geometric stiffness of torque) is not "
                              "supported", where)
    method = str(t.get("shear_method_calc", "cowper"))
    if t.get("shear_effects", True) and method != "cowper":
        raise RossImportError(f"shear_method_calc = '{method}': rotorsim uses Cowper's "
                              "shear coefficient (save the ROSS rotor with 'cowper')", where)
    return ShaftElement(
        L=float(t["L"]), idl=float(t["idl"]), odl=float(t["odl"]),
        idr=float(t.get("idr", t["idl"])), odr=float(t.get("odr", t["odl"])),
        material=_material(t, where), shear_effects=bool(t.get("shear_effects", True)),
        rotary_inertia=bool(t.get("rotary_inertia", True)),
        gyroscopic=bool(t.get("gyroscopic", True)),
        axial_force=float(t.get("axial_force", 0.0) or 0.0),
        alpha=0.0 if beta else float(t.get("alpha", 0.0) or 0.0),
        beta=beta or float(t.get("beta", 0.0) or 0.0), tag=tag)


def _bending_stiffness(el: ShaftElement) -> float:
    """E I of the element's mean section [N m^2]."""
    do = 0.5 * (el.odl + float(el.odr or el.odl))
    di = 0.5 * (el.idl + float(el.idr or el.idl))
    return el.material.E * math.pi * (do**4 - di**4) / 64.0


def _lumped(layer: ShaftElement, n: int) -> list[tuple[int, float, float, float]]:
    """``(node, m, Id, Ip)`` of each half of a layer, the inertias about its node (mean
    diameters for a tapered layer)."""
    half = 0.5 * layer.mass
    ro = 0.25 * (layer.odl + float(layer.odr or layer.odl))
    ri = 0.25 * (layer.idl + float(layer.idr or layer.idl))
    ip = 0.5 * half * (ro**2 + ri**2)
    i_d = half * ((ro**2 + ri**2) / 4.0 + (0.5 * layer.L) ** 2 / 3.0)
    return [(n, half, i_d, ip), (n + 1, half, i_d, ip)]


def _merge_lumps(lumps: list[tuple[int, float, float, float]]) -> list[DiskElement]:
    total: dict[int, list[float]] = defaultdict(lambda: [0.0, 0.0, 0.0])
    for node, m, i_d, ip in lumps:
        acc = total[node]
        acc[0] += m
        acc[1] += i_d
        acc[2] += ip
    return [DiskElement(n=node, m=m, Id=i_d, Ip=ip, tag=f"ross_layers_{node}")
            for node, (m, i_d, ip) in sorted(total.items())]


def _disk(key: str, t: Mapping[str, Any]) -> DiskElement:
    return DiskElement(n=int(t["n"]), m=float(t["m"]), Id=float(t["Id"]), Ip=float(t["Ip"]),
                       tag=_tag(key, t))


def _bearing(key: str, t: Mapping[str, Any], speed_key: str, refine: int,
             speed_range: tuple[float, float] | None) -> BearingElement:
    tag = _tag(key, t)
    where = f"ROSS {key.split('_', 1)[0]} '{tag}'"
    if speed_key == "speed" and t.get("frequency") is not None:
        raise RossImportError("coefficients over whirl frequency are not supported "
                              "(rotorsim tabulates over spin speed)", where)
    if any(float(v) != 0.0 for v in _as_list(t.get("mzz", 0.0))):
        raise RossImportError("axial added mass mzz is not supported", where)
    coefficients, speeds = coefficient_tables(t, where, speed_key=speed_key, refine=refine,
                                              speed_range=speed_range)
    n_link = t.get("n_link")
    return BearingElement(n=int(t["n"]), n_link=None if n_link is None else int(n_link),
                          frequency=speeds, tag=tag, **coefficients)


def _as_list(value: Any) -> list[Any]:
    return list(value) if isinstance(value, list | tuple) else [value]


def _point_mass(key: str, t: Mapping[str, Any]) -> PointMass:
    m = float(t.get("m", 0.0) or 0.0)
    return PointMass(n=int(t["n"]), m=m, mx=float(t.get("mx", m)), my=float(t.get("my", m)),
                     mz=float(t.get("mz", m)), tag=_tag(key, t))


def table_note(rotor: Rotor) -> str | None:
    """Where the bearing tables of an imported rotor end, or None without tables: beyond
    them rotorsim holds the end values where ROSS extrapolates."""
    tables = [b.frequency for b in rotor.bearing_elements if b.frequency is not None]
    if not tables:
        return None
    low = max(float(f[0]) for f in tables)
    high = min(float(f[-1]) for f in tables)
    return (f"bearing and seal tables cover {low:.6g} to {high:.6g} rad/s: outside them "
            "rotorsim holds the end values where ROSS extrapolates linearly; give the "
            "speeds to be analysed (speed_range, --speed-range) to extend them as ROSS does")


def import_ross(source: str | os.PathLike[str], out: str | os.PathLike[str] | None = None, *,
                refine: int = 8, speed_range: tuple[float, float] | None = None) -> Path:
    """Write the rotorsim model file of a ROSS rotor file (``rotorsim import-ross``).

    Parameters
    ----------
    source : path
        The ROSS file (``.toml`` or ``.json``).
    out : path, optional
        The model file to write; default ``source``'s stem with ``_rotorsim.toml`` beside it.
    refine, speed_range
        As :func:`from_ross`.

    Returns
    -------
    Path
        The model file written.
    """
    from rotorsim.io.model_file import save_model

    src = Path(source)
    rotor = from_ross(src, refine=refine, speed_range=speed_range)
    target = src.with_name(f"{src.stem}_rotorsim.toml") if out is None else Path(out)
    return save_model(rotor, target)
