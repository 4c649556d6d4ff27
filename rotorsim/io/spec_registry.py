"""The analysis ``type`` names of model files and their spec classes.

Examples
--------
>>> SPEC_TYPES["campbell"].__name__
'CampbellSpec'
"""

from __future__ import annotations

from rotorsim.io.analysis_spec import AnalysisSpec
from rotorsim.io.api_specs import ApiStabilitySpec, ApiUnbalanceSpec
from rotorsim.io.linear_specs import (
    CampbellSpec,
    CriticalSpeedMapSpec,
    CriticalSpeedsSpec,
    FrequencyResponseSpec,
    ModalSpec,
    StaticSpec,
    UnbalanceSpec,
)
from rotorsim.io.long_specs import PeriodicParameterSpec, PeriodicSpec, SweepSpec, TransientSpec

SPEC_TYPES: dict[str, type[AnalysisSpec]] = {
    cls.type: cls for cls in (ModalSpec, CampbellSpec, CriticalSpeedsSpec,
                              CriticalSpeedMapSpec, UnbalanceSpec, FrequencyResponseSpec,
                              StaticSpec, TransientSpec, PeriodicSpec, PeriodicParameterSpec,
                              SweepSpec, ApiStabilitySpec, ApiUnbalanceSpec)
}
"""Analysis ``type`` names of model files and their spec classes."""
