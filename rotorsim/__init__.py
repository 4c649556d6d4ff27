"""rotorsim: rotordynamics with finite elements and nonlinear rolling-element bearings.

The workflow is model -> assemble -> analyse -> save/plot::

    import rotorsim as rs

    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(6)]
    disks = [rs.DiskElement.from_geometry(2, steel, width=0.07, i_d=0.05, o_d=0.28)]
    bearings = [rs.BearingElement(n=0, kxx=1e6), rs.BearingElement(n=6, kxx=1e6)]
    rotor = rs.Rotor(shaft, disks, bearings)

    modes = rs.modal(rotor, speed=0.0, num_modes=8)       # ModalResult
    system = rs.assemble(rotor)                           # sparse M, C, G, K + DofMap
    run = rs.transient(rotor, 0.5, 1e-4, speed=rs.LinearSpeed(0, 300, 0, 0.5),
                       unbalance=[(2, 1e-4, 0.0)])        # TransientResult (run-up)
    branch = rs.periodic(rotor, start=100, stop=500,
                         unbalance=[(2, 1e-4, 0.0)])      # PeriodicResult (HB branch)

The wide verbs group their options by concern (``rs.Excitation``, ``rs.Harmonics``,
``rs.ContinuationOptions``, ``rs.StabilityOptions``, ``rs.Output``, ``rs.Checkpointing``;
:mod:`rotorsim.options`), e.g. ``rs.transient(rotor, 0.5, 1e-4, excitation=rs.Excitation(
gravity=None), output=rs.Output(every=10))``.

Rolling bearings (``rs.RollingBearing``) go into the rotor beside the linear bearings; the
transient and static analyses use them as they are, the linear analyses after
``rs.linearize_rolling_bearings(rotor)`` at the static load.

All quantities are SI (m, kg, s, N, rad, rad/s). Importing rotorsim pulls in numpy and
scipy only; plotting imports matplotlib lazily.
"""

from rotorsim.analyses.linear.campbell import campbell
from rotorsim.analyses.linear.critical_speed_map import critical_speed_map
from rotorsim.analyses.linear.critical_speeds import critical_speeds
from rotorsim.analyses.linear.frequency_response import frequency_response, unbalance_response
from rotorsim.analyses.linear.modal import modal
from rotorsim.analyses.periodic.excitation import HarmonicBase
from rotorsim.analyses.periodic.parameter import periodic_parameter
from rotorsim.analyses.periodic.periodic import periodic
from rotorsim.analyses.statics.bearing_statics import (
    bearing_equilibrium,
    linearize_at_load,
    stiffness_over_pass,
)
from rotorsim.analyses.statics.linearized_rotor import (
    LinearizationPoint,
    LinearizedRotor,
    linearize_rolling_bearings,
)
from rotorsim.analyses.statics.static import static
from rotorsim.analyses.sweep.sweep import (
    Grid,
    Normal,
    Sample,
    Uniform,
    sweep,
)
from rotorsim.analyses.transient.loads import BaseExcitation
from rotorsim.analyses.transient.speed_profile import ConstantSpeed, LinearSpeed, SpeedFunction
from rotorsim.analyses.transient.transient import transient
from rotorsim.assembly.dof_map import DofMap
from rotorsim.assembly.system import RotorSystem, SystemMatrices, assemble
from rotorsim.elements.base import DOF_NAMES, ElementMatrices
from rotorsim.elements.disk import DiskElement, PointMass
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.elements.rolling import (
    BallBearing,
    CentrifugalBearing,
    ReversedBearing,
    RollerBearing,
)
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.elements.rolling.flexible_ring.bearing import FlexibleRingRollerBearing
from rotorsim.elements.rolling.flexible_ring.element import FlexibleRingBearingElement
from rotorsim.elements.rolling.large_rotation import LargeRotationBearing
from rotorsim.elements.shaft import ShaftElement, cowper_shear_coefficient
from rotorsim.errors import (
    ConvergenceError,
    InconsistentModelError,
    ModelError,
    RotorsimError,
    Status,
)
from rotorsim.io.hdf5 import ResultsFileError, load, save
from rotorsim.io.model_file import Model, load_model, run_analysis, save_model
from rotorsim.io.sweep_store import load_sweep
from rotorsim.io.vtk import export_vtk
from rotorsim.model.material import Material
from rotorsim.model.rotor import Rotor
from rotorsim.options import (
    Checkpointing,
    ContinuationOptions,
    Excitation,
    Harmonics,
    Output,
    StabilityOptions,
)
from rotorsim.plotting import plot
from rotorsim.results.bearing import BearingEquilibriumResult, StiffnessVariation
from rotorsim.results.campbell import CampbellResult
from rotorsim.results.critical_speeds import CriticalSpeedMapResult, CriticalSpeeds
from rotorsim.results.frequency_response import FrequencyResponseResult
from rotorsim.results.modal import ModalResult
from rotorsim.results.orbits import Ellipse, ellipse
from rotorsim.results.periodic import PeriodicBifurcation, PeriodicResult
from rotorsim.results.static import StaticResult
from rotorsim.results.sweep import SweepResult
from rotorsim.results.transient import TransientResult
from rotorsim.time_integration.adams import Adams
from rotorsim.time_integration.adaptive import Adaptive
from rotorsim.time_integration.newmark import Newmark

__version__ = "0.1.0"

__all__ = [
    "DOF_NAMES",
    "Adams",
    "Adaptive",
    "BallBearing",
    "BaseExcitation",
    "BearingElement",
    "BearingEquilibriumResult",
    "CampbellResult",
    "CentrifugalBearing",
    "Checkpointing",
    "ConstantSpeed",
    "ContinuationOptions",
    "ConvergenceError",
    "CriticalSpeedMapResult",
    "CriticalSpeeds",
    "DiskElement",
    "DofMap",
    "ElementMatrices",
    "Ellipse",
    "Excitation",
    "FlexibleRingBearingElement",
    "FlexibleRingRollerBearing",
    "FrequencyResponseResult",
    "Grid",
    "HarmonicBase",
    "Harmonics",
    "InconsistentModelError",
    "LargeRotationBearing",
    "LinearSpeed",
    "LinearizationPoint",
    "LinearizedRotor",
    "Material",
    "ModalResult",
    "Model",
    "ModelError",
    "Newmark",
    "Normal",
    "Output",
    "PeriodicBifurcation",
    "PeriodicResult",
    "PointMass",
    "ResultsFileError",
    "ReversedBearing",
    "RollerBearing",
    "RollingBearing",
    "Rotor",
    "RotorSystem",
    "RotorsimError",
    "Sample",
    "ShaftElement",
    "SpeedFunction",
    "StabilityOptions",
    "StaticResult",
    "Status",
    "StiffnessVariation",
    "SweepResult",
    "SystemMatrices",
    "TransientResult",
    "Uniform",
    "assemble",
    "bearing_equilibrium",
    "campbell",
    "cowper_shear_coefficient",
    "critical_speed_map",
    "critical_speeds",
    "ellipse",
    "export_vtk",
    "frequency_response",
    "linearize_at_load",
    "linearize_rolling_bearings",
    "load",
    "load_model",
    "load_sweep",
    "modal",
    "periodic",
    "periodic_parameter",
    "plot",
    "run_analysis",
    "save",
    "save_model",
    "static",
    "stiffness_over_pass",
    "sweep",
    "transient",
    "unbalance_response",
]
