"""Specs of the API 617 checks in model files: ``type = "api_stability"`` (Level I) and
``type = "api_unbalance"``, with the machine data they need (stages, clearances).

The specs are plain data in SI with node numbers resolved (:func:`api_options` resolves
the positions of a validated table); :mod:`rotorsim.io.analysis_runners` maps them onto
:func:`rotorsim.api_level1` and :func:`rotorsim.api_unbalance`.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any, ClassVar

from rotorsim.io.analysis_spec import AnalysisSpec, Grid


@dataclass(frozen=True)
class StageSpec:
    """Machine data of one stage: node, power [W], diameter and flow-path height [m],
    discharge over suction density, tag."""

    node: int
    power: float
    diameter: float
    flow_height: float
    density_ratio: float = 1.0
    tag: str | None = None

    def to_toml(self) -> dict[str, Any]:
        return {k: v for k, v in asdict(self).items() if v is not None}


@dataclass(frozen=True)
class ClearanceSpec:
    """A close clearance: node, diametral running clearance [m], tag."""

    node: int
    clearance: float
    tag: str | None = None

    def to_toml(self) -> dict[str, Any]:
        return {k: v for k, v in asdict(self).items() if v is not None}


@dataclass(frozen=True, kw_only=True)
class ApiStabilitySpec(AnalysisSpec):
    """API 617 Level I stability at the maximum continuous speed ``mcs`` [rad/s]:
    :func:`rotorsim.api_level1`. ``average_density`` [kg/m^3] feeds the Region A/B test."""

    type: ClassVar[str] = "api_stability"
    mcs: float
    stages: tuple[StageSpec, ...]
    machine: str = "compressor"
    apply_at: str = "midspan"
    average_density: float | None = None
    q_max: float | None = None
    num: int = 11
    num_modes: int = 8

    def to_toml(self) -> dict[str, Any]:
        out = super().to_toml()
        out["stages"] = [s.to_toml() for s in self.stages]
        return out


@dataclass(frozen=True, kw_only=True)
class ApiUnbalanceSpec(AnalysisSpec):
    """API 617 unbalance response analysis over ``speeds`` [rad/s] with the operating range
    ``min_speed .. mcs``: :func:`rotorsim.api_unbalance`."""

    type: ClassVar[str] = "api_unbalance"
    speeds: Grid
    min_speed: float
    mcs: float
    num_modes: int = 3
    clearances: tuple[ClearanceSpec, ...] = ()
    probes: tuple[int, ...] | None = None
    plane_mass: float | None = None
    factor: float = 1.0
    spool: str | None = None

    def to_toml(self) -> dict[str, Any]:
        out = super().to_toml()
        out["clearances"] = [c.to_toml() for c in self.clearances]
        if not self.clearances:
            del out["clearances"]
        return out


def api_options(table: Any, nodes: Any, where: str) -> dict[str, Any]:
    """The stage or clearance specs of a validated ``api_*`` table, with positions resolved
    to shaft nodes (``nodes`` is :class:`rotorsim.io.model_nodes.Nodes`)."""
    if table.type == "api_stability":
        return {"stages": tuple(
            StageSpec(nodes.shaft_node(s, f"{where}.stages[{i}]"), s.power, s.diameter,
                      s.flow_height, s.density_ratio, s.tag)
            for i, s in enumerate(table.stages))}
    out: dict[str, Any] = {"clearances": tuple(
        ClearanceSpec(nodes.shaft_node(c, f"{where}.clearances[{i}]"), c.clearance, c.tag)
        for i, c in enumerate(table.clearances))}
    if table.probes is not None:
        out["probes"] = tuple(nodes.check(n, f"{where}.probes[{i}]")
                              for i, n in enumerate(table.probes))
    return out
