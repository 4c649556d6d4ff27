"""Public names of rotorsim, for type checkers and for the lazy loader of
``rotorsim/__init__.py`` (each is imported on first use)."""

from . import hb
from .analyses.linear.campbell import campbell
from .analyses.linear.critical_speed_map import critical_speed_map
from .analyses.linear.critical_speeds import critical_speeds
from .analyses.linear.frequency_response import frequency_response, unbalance_response
from .analyses.linear.modal import modal
from .analyses.periodic.bearing_life import periodic_life
from .analyses.periodic.excitation import HarmonicBase
from .analyses.periodic.parameter import periodic_parameter
from .analyses.periodic.periodic import periodic
from .analyses.periodic.switching import switch_branch
from .analyses.quasiperiodic import (
    QuasiPeriodicBranch,
    QuasiPeriodicPoint,
    motion_beyond,
    quasi_periodic,
    quasi_periodic_point,
)
from .analyses.standards.api_formulas import (
    anticipated_cross_coupling,
    level1_screening,
    required_separation_margin,
    residual_unbalance,
)
from .analyses.standards.api_stability import ApiStage, api_level1
from .analyses.standards.api_unbalance import Clearance, api_unbalance
from .analyses.statics.bearing_life import bearing_life, duty_cycle_life
from .analyses.statics.bearing_statics import (
    bearing_equilibrium,
    linearize_at_load,
    stiffness_over_pass,
)
from .analyses.statics.linearized_rotor import (
    LinearizationPoint,
    LinearizedRotor,
    linearize_rolling_bearings,
)
from .analyses.statics.static import static
from .analyses.statics.torus_life import quasi_periodic_life
from .analyses.sweep.sweep import (
    Grid,
    Normal,
    Sample,
    Uniform,
    sweep,
)
from .analyses.transient.bearing_life import transient_life
from .analyses.transient.loads import BaseExcitation
from .analyses.transient.speed_profile import ConstantSpeed, LinearSpeed, SpeedFunction
from .analyses.transient.torque_drive import TorqueDrive
from .analyses.transient.torque_laws import (
    ConstantTorque,
    InductionMotor,
    PulsatingTorque,
    QuadraticTorque,
    TorqueCurve,
    TorqueFunction,
    ViscousTorque,
)
from .analyses.transient.transient import transient
from .assembly.dof_map import DofMap
from .assembly.system import RotorSystem, SystemMatrices, assemble
from .elements.base import DOF_NAMES, ElementMatrices
from .elements.disk import DiskElement, PointMass
from .elements.foundation import Foundation
from .elements.linear_bearing import BearingElement
from .elements.rolling import (
    BallBearing,
    CentrifugalBearing,
    ReversedBearing,
    RollerBearing,
)
from .elements.rolling.contact.exponent_fit import kn_for_exponent
from .elements.rolling.contact.iso_spring import iso16281_ball_constant
from .elements.rolling.double_row import DoubleRowBearing
from .elements.rolling.element import RollingBearing
from .elements.rolling.flexible_ring.bearing import FlexibleRingRollerBearing
from .elements.rolling.flexible_ring.element import FlexibleRingBearingElement
from .elements.rolling.large_rotation import LargeRotationBearing
from .elements.rolling.rating.clearance import (
    MountingConditions,
    operating_clearance,
    with_operating_clearance,
)
from .elements.rolling.rating.double_row import DoubleRowRating
from .elements.rolling.rating.friction import PalmgrenFriction, friction_torque
from .elements.rolling.rating.hertz_pressure import contact_pressures
from .elements.rolling.rating.iso281 import BearingRating
from .elements.rolling.rating.options import RatingOptions
from .elements.rolling.roller.half_space import HalfSpaceLineContact, roller_pressure_field
from .elements.shaft import ShaftElement, cowper_shear_coefficient
from .errors import (
    ConvergenceError,
    InconsistentModelError,
    ModelError,
    RotorsimError,
    Status,
)
from .io.hdf5 import ResultsFileError, load, save
from .io.model_file import Model, load_model, run_analysis, save_model
from .io.ross_import import RossImportError, from_ross, import_ross
from .io.sweep_store import load_sweep
from .io.vtk import export_vtk
from .model.damping import SystemDamping
from .model.lines import ShaftLine
from .model.material import Material
from .model.rotor import Rotor
from .options import (
    Checkpointing,
    ContinuationOptions,
    Excitation,
    Harmonics,
    Output,
    StabilityOptions,
    SteadyStop,
)
from .plotting import plot
from .report.build import write_report
from .results.api import ApiLevel1Result, ApiUnbalanceResult
from .results.bearing import BearingEquilibriumResult, StiffnessVariation
from .results.bearing_life import BearingLifeResult
from .results.campbell import CampbellResult
from .results.critical_speeds import CriticalSpeedMapResult, CriticalSpeeds
from .results.event_verification import EventCheck, EventVerification, SideCheck
from .results.frequency_response import FrequencyResponseResult
from .results.modal import ModalResult
from .results.orbits import Ellipse, ellipse
from .results.periodic import PeriodicBifurcation, PeriodicPeak, PeriodicResult
from .results.quasi_periodic import QuasiPeriodicResult, TorusEvent
from .results.static import StaticResult
from .results.sweep import SweepResult
from .results.torus_motion import MotionBeyond
from .results.transient import TransientResult
from .time_integration.adams import Adams
from .time_integration.adaptive import Adaptive
from .time_integration.newmark import Newmark
from .verification.periodic_events import verify_events

__version__: str

__all__ = [
    "DOF_NAMES",
    "Adams",
    "Adaptive",
    "ApiLevel1Result",
    "ApiStage",
    "ApiUnbalanceResult",
    "BallBearing",
    "BaseExcitation",
    "BearingElement",
    "BearingEquilibriumResult",
    "BearingLifeResult",
    "BearingRating",
    "CampbellResult",
    "CentrifugalBearing",
    "Checkpointing",
    "Clearance",
    "ConstantSpeed",
    "ConstantTorque",
    "ContinuationOptions",
    "ConvergenceError",
    "CriticalSpeedMapResult",
    "CriticalSpeeds",
    "DiskElement",
    "DofMap",
    "DoubleRowBearing",
    "DoubleRowRating",
    "ElementMatrices",
    "Ellipse",
    "EventCheck",
    "EventVerification",
    "Excitation",
    "FlexibleRingBearingElement",
    "FlexibleRingRollerBearing",
    "Foundation",
    "FrequencyResponseResult",
    "Grid",
    "HalfSpaceLineContact",
    "HarmonicBase",
    "Harmonics",
    "InconsistentModelError",
    "InductionMotor",
    "LargeRotationBearing",
    "LinearSpeed",
    "LinearizationPoint",
    "LinearizedRotor",
    "Material",
    "ModalResult",
    "Model",
    "ModelError",
    "MotionBeyond",
    "MountingConditions",
    "Newmark",
    "Normal",
    "Output",
    "PalmgrenFriction",
    "PeriodicBifurcation",
    "PeriodicPeak",
    "PeriodicResult",
    "PointMass",
    "PulsatingTorque",
    "QuadraticTorque",
    "QuasiPeriodicBranch",
    "QuasiPeriodicPoint",
    "QuasiPeriodicResult",
    "RatingOptions",
    "ResultsFileError",
    "ReversedBearing",
    "RollerBearing",
    "RollingBearing",
    "RossImportError",
    "Rotor",
    "RotorSystem",
    "RotorsimError",
    "Sample",
    "ShaftElement",
    "ShaftLine",
    "SideCheck",
    "SpeedFunction",
    "StabilityOptions",
    "StaticResult",
    "Status",
    "SteadyStop",
    "StiffnessVariation",
    "SweepResult",
    "SystemDamping",
    "SystemMatrices",
    "TorqueCurve",
    "TorqueDrive",
    "TorqueFunction",
    "TorusEvent",
    "TransientResult",
    "Uniform",
    "ViscousTorque",
    "anticipated_cross_coupling",
    "api_level1",
    "api_unbalance",
    "assemble",
    "bearing_equilibrium",
    "bearing_life",
    "campbell",
    "contact_pressures",
    "cowper_shear_coefficient",
    "critical_speed_map",
    "critical_speeds",
    "duty_cycle_life",
    "ellipse",
    "export_vtk",
    "frequency_response",
    "friction_torque",
    "from_ross",
    "hb",
    "import_ross",
    "iso16281_ball_constant",
    "kn_for_exponent",
    "level1_screening",
    "linearize_at_load",
    "linearize_rolling_bearings",
    "load",
    "load_model",
    "load_sweep",
    "modal",
    "motion_beyond",
    "operating_clearance",
    "periodic",
    "periodic_life",
    "periodic_parameter",
    "plot",
    "quasi_periodic",
    "quasi_periodic_life",
    "quasi_periodic_point",
    "required_separation_margin",
    "residual_unbalance",
    "roller_pressure_field",
    "run_analysis",
    "save",
    "save_model",
    "static",
    "stiffness_over_pass",
    "sweep",
    "switch_branch",
    "transient",
    "transient_life",
    "unbalance_response",
    "verify_events",
    "with_operating_clearance",
    "write_report",
]
