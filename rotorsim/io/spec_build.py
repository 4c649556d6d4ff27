"""Typed analysis specs from the validated analysis tables of a model file (the nodes,
unbalances and bearings they name resolved against the built model)."""

from __future__ import annotations

from typing import Any

from rotorsim.errors import ModelError
from rotorsim.io import analysis_spec as spec
from rotorsim.io.api_specs import api_options
from rotorsim.io.drive_schema import drive_spec
from rotorsim.io.model_build import unbalance_list
from rotorsim.io.model_nodes import Nodes
from rotorsim.io.schema_types import format_path
from rotorsim.io.spec_registry import SPEC_TYPES
from rotorsim.model.rotor import Rotor


def build_spec(table: Any, loc: tuple[str | int, ...], nodes: Nodes,
               rotor: Rotor, loads: spec.Loads, rolling_tags: tuple[str | None, ...] = ()
               ) -> spec.AnalysisSpec:
    """The typed spec of one validated analysis table (``rolling_tags``: tags of the rolling
    bearings, appended to the rotor's bearings once linearised)."""
    where = format_path(loc)
    common: dict[str, Any] = {
        "description": table.description, "units": table.units, "dofs": tuple(table.dofs),
        "nodes": None if table.nodes is None else tuple(
            nodes.check(n, f"{where}.nodes[{i}]") for i, n in enumerate(table.nodes)),
    }
    cls = SPEC_TYPES[table.type]
    options: dict[str, Any] = {}
    for key in cls.option_keys():  # its fields and the flat keys of its option groups
        if key not in common and hasattr(table, key):
            options[key] = getattr(table, key)
    if table.type in ("unbalance", "transient", "periodic", "periodic_parameter"):
        options["unbalance"] = _analysis_unbalance(table, nodes, loads, where)
    if table.type == "transient" and table.drive is not None:
        options["drive"] = drive_spec(table.drive, nodes, f"{where}.drive")
    elif table.type == "frequency_response":
        options["inputs"] = tuple((nodes.any_node(item, f"{where}.inputs[{i}]"), str(item.dof))
                                  for i, item in enumerate(table.inputs))
    elif table.type in ("critical_speed_map", "sweep"):
        options["bearings"] = _bearing_indices(options["bearings"], rotor, rolling_tags,
                                               f"{where}.bearings")
    elif table.type == "campbell":
        options["harmonics"] = tuple(options["harmonics"])
    elif table.type in ("api_stability", "api_unbalance"):
        options.update(api_options(table, nodes, where))
    elif table.type == "critical_speeds" and table.spool is not None:
        names = [name for name, _, _ in nodes.lines] or ["shaft"]
        if table.spool not in names:
            raise ModelError(f"no line named {table.spool!r} (lines: {', '.join(names)})",
                             f"{where}.spool")
    return cls.from_flat(**common, **options)


def _analysis_unbalance(table: Any, nodes: Nodes, loads: spec.Loads, where: str
                        ) -> spec.Unbalance | None:
    if table.unbalance is None:
        if not loads.unbalance and table.type == "unbalance":
            raise ModelError("no unbalance given: add [[loads.unbalance]] or unbalance = "
                             "[...] to this analysis", where)
        return None
    return unbalance_list(table.unbalance, nodes, f"{where}.unbalance")


def _bearing_indices(refs: tuple[int | str, ...] | None, rotor: Rotor,
                     rolling_tags: tuple[str | None, ...], where: str) -> tuple[int, ...] | None:
    if refs is None:
        return None
    tags = [*(b.tag for b in rotor.bearing_elements), *rolling_tags]
    out = []
    for i, ref in enumerate(refs):
        if isinstance(ref, str):
            if ref not in tags:
                raise ModelError(f"no bearing tagged '{ref}' (tags: "
                                 f"{', '.join(str(t) for t in tags)})", f"{where}[{i}]")
            out.append(tags.index(ref))
        elif ref >= len(tags):
            raise ModelError(f"bearing index {ref} out of range (the model has {len(tags)})",
                             f"{where}[{i}]")
        else:
            out.append(ref)
    return tuple(out)
