"""Turn a loaded :class:`~rotorsim.io.model.Model` back into model-file content (SI).

The content is chosen so that loading it rebuilds bit-identical elements: a shaft segment
per run of identical consecutive elements (its ``length`` only if ``length / n`` gives the
element length back exactly, else ``element_length``), tapered elements one per segment
with their four diameters, materials with both ``G_s`` and ``nu``. :func:`toml_text` lays
it out as a person would write it: ``[model]``, ``[[materials]]``, ``[[shaft]]``, ...,
``[analyses.<name>]``, with grids and short lists inline.
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import math
import re
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorsim.analyses.statics.linearized_rotor import LinearizationPoint
from rotorsim.elements.disk import PointMass
from rotorsim.elements.linear_bearing import COEFFICIENTS, BearingElement
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.reversed import ReversedBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.profile import (
    CircularCrown,
    LogarithmicProfile,
    StraightProfile,
)
from rotorsim.elements.shaft import ShaftElement
from rotorsim.errors import ModelError
from rotorsim.io.analysis_spec import Loads
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor

if TYPE_CHECKING:
    from rotorsim.io.model import Model


def model_to_dict(model: Model) -> dict[str, Any]:
    """Model-file content of ``model`` as a dict ready for ``tomli_w``."""
    rotor = model.rotor
    names = material_names(rotor)
    info: dict[str, Any] = {"name": model.name}
    if model.description:
        info["description"] = model.description
    out: dict[str, Any] = {
        "model": info,
        "materials": [_material(mat, name) for mat, name in names.items()],
        "shaft": shaft_segments(rotor.shaft_elements, names),
    }
    optional = {
        "disks": [{"node": int(d.n), "m": float(d.m), "Id": float(d.Id), "Ip": float(d.Ip),
                   **_tag(d.tag)} for d in rotor.disk_elements],
        "bearings": [bearing_entry(b) for b in rotor.bearing_elements],
        "rolling_bearings": [rolling_entry(rb, p) for rb, p in zip(
            model.rolling_bearings, model.linearize or [None] * len(model.rolling_bearings),
            strict=True)],
        "point_masses": [_point_mass(pm) for pm in rotor.point_mass_elements],
        "fixed": _fixed(rotor),
    }
    out.update({key: value for key, value in optional.items() if value})
    out["loads"] = _loads(model.loads)
    if model.analyses:
        out["analyses"] = {name: spec.to_toml() for name, spec in model.analyses.items()}
    _system_parts(out, rotor)
    if rotor.multi_line:
        _on_lines(out, rotor, names)
    return out


def _system_parts(out: dict[str, Any], rotor: Rotor) -> None:
    """``[damping]``; foundations are written only as files, which a dict cannot hold."""
    if rotor.foundations:
        raise ModelError("a model with foundations cannot be saved yet: their matrices live "
                         "in .npy/.mtx files; keep the model file that names them",
                         "save_model")
    d = rotor.damping
    if d is not None and d.active:
        out["damping"] = {"alpha": float(d.alpha), "beta": float(d.beta),
                          "modal_ratios": [float(z) for z in d.modal_ratios]}


def _on_lines(out: dict[str, Any], rotor: Rotor, names: dict[Material, str]) -> None:
    """Rewrite a one-line dict as ``[lines.NAME]`` tables whose items name their line and
    local node (housing nodes keep their global number)."""
    del out["shaft"]
    lines: dict[str, Any] = {}
    for line in rotor.layout.lines:
        first = rotor.node(line.name, 0)
        elements = [el for el in rotor.shaft_elements
                    if first <= int(el.nodes[0]) < first + line.n_nodes]
        table: dict[str, Any] = {"speed_ratio": float(line.speed_ratio),
                                 "z0": float(line.z0)}
        if elements:
            table["shaft"] = shaft_segments(elements, names)
        lines[line.name] = table
    out["lines"] = lines

    def place(entry: dict[str, Any]) -> None:
        if "node" in entry:
            entry.update(_line_node(rotor, int(entry.pop("node")), "line", "node"))
        if "n_link" in entry:
            entry.update(_line_node(rotor, int(entry.pop("n_link")), "link_line", "n_link"))

    for key in ("disks", "bearings", "rolling_bearings", "point_masses", "fixed"):
        for entry in out.get(key, []):
            place(entry)
    for key in ("unbalance", "point_loads"):
        for entry in out["loads"].get(key, []):
            place(entry)
    for spec in out.get("analyses", {}).values():
        for key in ("unbalance", "inputs"):
            for entry in spec.get(key) or []:
                if isinstance(entry, dict):
                    place(entry)
        drive = spec.get("drive")
        if isinstance(drive, dict):
            place(drive)
            for key in ("loads", "friction"):
                for entry in drive.get(key, []):
                    place(entry)


def _line_node(rotor: Rotor, node: int, line_key: str, node_key: str) -> dict[str, Any]:
    """``{line_key: name, node_key: local}`` of a line node; the global number off lines."""
    k = int(rotor.node_line[node])
    if k < 0:
        return {node_key: node}
    return {line_key: rotor.layout.lines[k].name,
            node_key: node - int(rotor.layout.first_node[k])}


def material_names(rotor: Rotor) -> dict[Material, str]:
    """Distinct materials of the shaft, each with a unique name."""
    names: dict[Material, str] = {}
    for el in rotor.shaft_elements:
        mat = el.material
        if mat in names:
            continue
        name, k = mat.name, 2
        while name in names.values():
            name, k = f"{mat.name}_{k}", k + 1
        names[mat] = name
    return names


def _material(mat: Material, name: str) -> dict[str, Any]:
    return {"name": name, "E": float(mat.E), "rho": float(mat.rho), "G_s": float(mat.G_s),
            "nu": float(mat.nu)}


def _tag(tag: str | None) -> dict[str, str]:
    return {} if tag is None else {"tag": tag}


def _signature(el: ShaftElement, index: int) -> tuple[Any, ...]:
    key = (el.L, el.idl, el.odl, el.idr, el.odr, el.material, el.shear_effects,
           el.rotary_inertia, el.gyroscopic, el.axial_force, el.shear_coefficient,
           el.alpha, el.beta, el.tag)
    return (*key, index) if el.tapered else key


def shaft_segments(elements: Any, names: dict[Material, str]) -> list[dict[str, Any]]:
    """One segment per run of identical consecutive (untapered) elements."""
    out = []
    runs = itertools.groupby(enumerate(elements), key=lambda item: _signature(item[1], item[0]))
    for _, group in runs:
        run = [el for _, el in group]
        out.append(_segment(run[0], len(run), names[run[0].material]))
    return out


def _segment(el: ShaftElement, count: int, material: str) -> dict[str, Any]:
    total = count * el.L
    seg: dict[str, Any] = ({"length": float(total)} if total / count == el.L
                           else {"element_length": float(el.L)})
    seg["n_elements"] = count
    if el.tapered:
        seg.update(idl=float(el.idl), odl=float(el.odl), idr=float(el.idr),  # type: ignore[arg-type]
                   odr=float(el.odr))  # type: ignore[arg-type]
    else:
        if el.idl:
            seg["id"] = float(el.idl)
        seg["od"] = float(el.odl)
    seg["material"] = material
    for key in ("shear_effects", "rotary_inertia", "gyroscopic"):
        if not getattr(el, key):
            seg[key] = False
    for key in ("axial_force", "alpha", "beta"):
        if getattr(el, key):
            seg[key] = float(getattr(el, key))
    if el.shear_coefficient is not None:
        seg["shear_coefficient"] = float(el.shear_coefficient)
    seg.update(_tag(el.tag))
    return seg


def bearing_entry(b: BearingElement) -> dict[str, Any]:
    """Every coefficient that differs from its default (``kyy = kxx``, others 0)."""
    entry: dict[str, Any] = {"node": int(b.n)}
    if b.n_link is not None:
        entry["n_link"] = int(b.n_link)
    table = {key: np.atleast_1d(np.asarray(getattr(b, key), dtype=float))
             for key in COEFFICIENTS}
    for key in COEFFICIENTS:
        value = table[key]
        default_key = f"{key[0]}xx" if key[1:] == "yy" else None
        if default_key is not None and np.array_equal(value, table[default_key]):
            continue
        if default_key is None and not np.any(value):
            continue
        entry[key] = float(value[0]) if value.size == 1 else [float(v) for v in value]
    if b.frequency is not None:
        entry["frequency"] = [float(v) for v in np.asarray(b.frequency)]
    for key in ("stiffness_matrix", "damping_matrix"):
        matrix = getattr(b, key)
        if matrix is not None:
            entry[key] = [[float(v) for v in row] for row in np.asarray(matrix)]
    entry.update(_tag(b.tag))
    return entry


_ROLLING_KEYS = {
    BallBearing: ("n_balls", "pitch_diameter", "ball_diameter", "Kn", "contact_angle", "f_i",
                  "f_o", "A0", "radial_clearance", "diametral_clearance", "exponent", "psi0",
                  "cage", "groove_center_radius"),
    RollerBearing: ("n_rollers", "pitch_diameter", "roller_diameter", "effective_length", "Kn",
                    "contact_angle", "radial_clearance", "diametral_clearance", "exponent",
                    "model", "n_slices", "psi0", "cage", "slice_model",
                    "influence_pressure"),
}
"""Model-file keys of each rolling-bearing model (the dataclass fields of the same name)."""


def rolling_entry(rb: Any, point: LinearizationPoint | None) -> dict[str, Any]:
    """``[[rolling_bearings]]`` table of a RollingBearing: every parameter that differs from
    its default, SI."""
    model = rb.bearing.bearing if isinstance(rb.bearing, ReversedBearing) else rb.bearing
    keys = _ROLLING_KEYS.get(type(model))
    if keys is None:
        raise ModelError(f"cannot write a {type(model).__name__} to a model file", rb.label)
    entry: dict[str, Any] = {"type": "ball" if isinstance(model, BallBearing) else "roller",
                             "node": int(rb.n)}
    if rb.n_link is not None:
        entry["n_link"] = int(rb.n_link)
    defaults = {f.name: f.default for f in dataclasses.fields(model)}
    unwritten = [f.name for f in dataclasses.fields(model) if f.init and f.name not in keys
                 and f.name not in ("tag", "profile") and getattr(model, f.name) != f.default]
    if unwritten:
        raise ModelError(f"model files have no key for {', '.join(unwritten)}", rb.label)
    for key in keys:
        value = getattr(model, key)
        if value is not None and value != defaults[key]:
            entry[key] = value if isinstance(value, str) else (
                int(value) if key.startswith("n_") else float(value))
    profile = getattr(model, "profile", None)
    if profile is not None and not isinstance(profile, StraightProfile):
        entry["profile"] = _profile_entry(profile)
    if isinstance(rb.bearing, ReversedBearing):
        entry["axial_direction"] = "-z"
    if rb.contact_damping not in ("none", "proportional"):
        raise ModelError(f"model files have no keys for {rb.contact_damping!r} contact "
                         "damping yet", rb.label)
    if rb.contact_damping != "none":
        entry.update(contact_damping=rb.contact_damping, damping_factor=float(rb.damping_factor))
    if point is not None and point.kind != "static":
        entry["linearize"] = {point.kind: list(point.value or ())}
    entry.update(_tag(rb.tag))
    return entry


def _profile_entry(profile: Any) -> dict[str, Any]:
    if isinstance(profile, CircularCrown):
        out: dict[str, Any] = {"type": "crowned", "crown_drop": float(profile.crown_drop)}
        if profile.crown_length is not None:
            out["crown_length"] = float(profile.crown_length)
        return out
    if isinstance(profile, LogarithmicProfile):
        return {"type": "logarithmic", "scale": float(profile.scale),
                "shape": float(profile.shape)}
    raise ModelError(f"cannot write a {type(profile).__name__} profile to a model file",
                     "rolling_bearings")


def _point_mass(pm: PointMass) -> dict[str, Any]:
    entry: dict[str, Any] = {"node": int(pm.n), "m": float(pm.m)}
    for key in ("mx", "my", "mz"):
        if getattr(pm, key) is not None:
            entry[key] = float(getattr(pm, key))
    entry.update(_tag(pm.tag))
    return entry


def _fixed(rotor: Rotor) -> list[dict[str, Any]]:
    by_node: dict[int, list[str]] = {}
    for node, dof in rotor.fixed:
        by_node.setdefault(int(node), []).append(dof)
    return [{"node": node, "dofs": dofs} for node, dofs in by_node.items()]


def _loads(loads: Loads) -> dict[str, Any]:
    out: dict[str, Any] = {
        "gravity": False if loads.gravity is None else float(loads.gravity),
        "gravity_direction": [float(v) for v in loads.gravity_direction],
    }
    if loads.unbalance:
        out["unbalance"] = [{"node": int(n), "magnitude": float(me), "phase": float(a)}
                            for n, me, a in loads.unbalance]
    if loads.point_loads:
        out["point_loads"] = [{"node": int(n), "dof": dof, "value": float(v)}
                              for n, dof, v in loads.point_loads]
    return out


# ---------------------------------------------------------------- TOML text
_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def toml_text(content: dict[str, Any]) -> str:
    """TOML text of model-file content: sections for the first two levels of tables and
    arrays of tables (``[loads]``, ``[[loads.unbalance]]``, ``[analyses.x]``), inline below.

    Examples
    --------
    >>> print(toml_text({"model": {"name": "x"}, "shaft": [{"length": 1.0, "od": 0.05}]}))
    [model]
    name = "x"
    <BLANKLINE>
    [[shaft]]
    length = 1.0
    od = 0.05
    <BLANKLINE>
    """
    lines: list[str] = []
    _emit(lines, (), content, array=False)
    return "\n".join(lines).lstrip("\n") + "\n"


def _is_section(value: Any, depth: int) -> bool:
    if depth >= 2:
        return False
    return isinstance(value, dict) or (isinstance(value, list) and bool(value)
                                       and all(isinstance(v, dict) for v in value))


def _emit(lines: list[str], path: tuple[str, ...], table: dict[str, Any], array: bool) -> None:
    inline = {k: v for k, v in table.items() if not _is_section(v, len(path))}
    if path and (inline or array or not table):
        header = ".".join(_key(p) for p in path)
        lines.extend(["", f"[[{header}]]" if array else f"[{header}]"])
    lines.extend(f"{_key(k)} = {_value(v)}" for k, v in inline.items())
    for key, value in table.items():
        if key in inline:
            continue
        if isinstance(value, dict):
            _emit(lines, (*path, key), value, array=False)
        else:
            for item in value:
                _emit(lines, (*path, key), item, array=True)


def _key(key: str) -> str:
    return key if _BARE_KEY.match(key) else json.dumps(key)


def _value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"cannot write the non-finite number {value} to a model file")
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, dict):
        items = ", ".join(f"{_key(k)} = {_value(v)}" for k, v in value.items())
        return f"{{ {items} }}" if items else "{}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} to a model file")
