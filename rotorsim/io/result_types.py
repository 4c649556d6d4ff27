"""Registration of every rotorsim result type with the HDF5 serializer, with the units of
its physical fields (imported by :mod:`rotorsim.io.hdf5`)."""

from __future__ import annotations

from rotorsim.io.serialize import register_result_type
from rotorsim.results.api import ApiLevel1Result, ApiUnbalanceResult
from rotorsim.results.bearing import BearingEquilibriumResult, EnergyMinimum, StiffnessVariation
from rotorsim.results.bearing_life import BearingLifeResult
from rotorsim.results.campbell import CampbellResult
from rotorsim.results.critical_speeds import (
    CriticalSpeedMapResult,
    CriticalSpeeds,
    MapIntersections,
)
from rotorsim.results.frequency_response import DeflectedShape, FrequencyResponseResult
from rotorsim.results.modal import ModalResult
from rotorsim.results.orbits import Ellipse
from rotorsim.results.order_tracking import OrderTrack, Waterfall
from rotorsim.results.periodic import PeriodicBifurcation, PeriodicPeak, PeriodicResult
from rotorsim.results.quasi_periodic import QuasiPeriodicResult, TorusEvent
from rotorsim.results.spectra import HarmonicFit, Spectrum
from rotorsim.results.static import StaticResult
from rotorsim.results.torus_motion import MotionBeyond
from rotorsim.results.transient import TransientResult
from rotorsim.results.transient_state import TransientState
from rotorsim.time_integration.base import Counters, State

_ANGULAR = "rad/s"
register_result_type(ModalResult, {
    "speed": _ANGULAR, "eigenvalues": _ANGULAR, "wn": _ANGULAR, "wd": _ANGULAR,
    "damping_ratio": "1", "log_dec": "1", "whirl_ratio": "1", "mode_shapes": "1",
    "rigid_body_shapes": "1", "nodes_pos": "m"})
register_result_type(CampbellResult, {
    "speeds": _ANGULAR, "wd": _ANGULAR, "wn": _ANGULAR, "log_dec": "1",
    "damping_ratio": "1", "whirl_ratio": "1", "tracking_mac": "1"})
register_result_type(CriticalSpeeds, {
    "speed": _ANGULAR, "frequency": _ANGULAR, "log_dec": "1", "harmonic": "1",
    "mode_shapes": "1"})
register_result_type(MapIntersections, {"stiffness": "N/m", "speed": _ANGULAR})
register_result_type(CriticalSpeedMapResult, {
    "stiffness": "N/m", "critical_speeds": _ANGULAR, "harmonic": "1", "speeds": _ANGULAR,
    "bearing_kxx": "N/m", "bearing_kyy": "N/m"})
register_result_type(FrequencyResponseResult, {
    "frequencies": _ANGULAR, "speeds": _ANGULAR, "response": "m, rad (per unit input)",
    "nodes_pos": "m"})
register_result_type(DeflectedShape, {
    "frequency": _ANGULAR, "speed": _ANGULAR, "nodes_pos": "m", "ux": "m", "uy": "m"})
register_result_type(StaticResult, {
    "displacement": "m, rad", "load": "N, N m", "nodes_pos": "m", "speed": _ANGULAR,
    "bearing_forces": "N", "bearing_moments": "N m", "constraint_reactions": "N, N m",
    "element_z": "m", "shear_force": "N", "bending_moment": "N m", "axial_force": "N",
    "torque": "N m", "residual": "1"})
register_result_type(Ellipse, {
    "major": "m", "minor": "m", "inclination": "rad", "forward_radius": "m",
    "backward_radius": "m", "whirl_ratio": "1"})
register_result_type(EnergyMinimum, {"displacement": "m, rad", "energy": "J",
                                     "hessian_eigenvalues": "N/m, N, N m/rad"})
register_result_type(BearingEquilibriumResult, {
    "displacement": "m, rad", "load": "N, N m", "force": "N, N m", "phi": "rad",
    "element_angles": "rad", "element_load": "N", "contact_angle": "rad", "deflection": "m",
    "stiffness": "N/m, N, N m/rad", "energy": "J", "strain_energy": "J", "residual": "1"})
register_result_type(StiffnessVariation, {
    "position": "1", "cage_angle": "rad", "shaft_angle": "rad", "displacement": "m, rad",
    "force": "N, N m", "stiffness": "N/m, N, N m/rad", "max_element_load": "N",
    "load": "N, N m"})
register_result_type(BearingLifeResult, {
    "C": "N", "C0": "N", "load": "N, N m", "P": "N", "L10": "1e6 rev", "L10r": "1e6 rev",
    "P_ref": "N", "ring_life": "1e6 rev", "equivalent_load": "N", "reference_load": "N",
    "a1": "1", "a_iso": "1", "Lnmr": "1e6 rev", "Lnm": "1e6 rev", "max_pressure": "Pa",
    "semi_major": "m", "semi_minor": "m", "shoulder_margin": "rad", "slice_pressure": "Pa",
    "slice_xi": "1", "element_angles": "rad", "element_load": "N", "row_life": "1e6 rev"})
register_result_type(TransientResult, {
    "t": "s", "q": "m, rad", "v": "m/s, rad/s", "dofs": "1", "speed": _ANGULAR,
    "angle": "rad", "acceleration": "rad/s^2", "bearing_loads": "N, N m",
    "bearing_elements": "1", "bearing_kappa": "1", "nodes_pos": "m",
    "reduced": "m, rad (revolution indices: 1)", "element_loads": "N", "contact_angles": "rad"})
register_result_type(TransientState, {
    "t": "s", "q": "m, rad", "v": "m/s, rad/s", "a": "m/s^2, rad/s^2", "angle": "rad",
    "speed": _ANGULAR, "dt": "s", "reduction_speed": _ANGULAR})
_STEPPER = " (reduced coordinates after a reduction)"
register_result_type(State, {  # the stepper's own coordinates
    "t": "s", "q": "m, rad" + _STEPPER, "v": "m/s, rad/s" + _STEPPER,
    "a": "m/s^2, rad/s^2" + _STEPPER, "force": "N, N m" + _STEPPER,
    "peak": "m, rad" + _STEPPER, "history": "m/s^2, rad/s^2" + _STEPPER, "dt": "s",
    "error": "1", "factor_dt": "s", "factor_spin": _ANGULAR, "history_dt": "s"})
register_result_type(Counters)
_SIGNAL = "signal units"  # spectra of any signal: m, rad, N... as the input
register_result_type(Spectrum, {
    "frequency": _ANGULAR, "amplitude": _SIGNAL, "phase": "rad", "dt": "s", "t_start": "s"})
register_result_type(HarmonicFit, {
    "frequency": _ANGULAR, "amplitude": _SIGNAL, "phase": "rad", "mean": _SIGNAL,
    "residual_rms": _SIGNAL, "t_start": "s", "t_end": "s"})
register_result_type(Waterfall, {
    "times": "s", "speeds": _ANGULAR, "frequency": _ANGULAR, "amplitude": _SIGNAL,
    "overlap": "1"})
register_result_type(OrderTrack, {
    "orders": "1", "speed": _ANGULAR, "times": "s", "amplitude": _SIGNAL, "phase": "rad",
    "order_axis": "1", "order_spectrum": _SIGNAL})
register_result_type(PeriodicBifurcation, {
    "parameter": _ANGULAR, "multiplier": "1", "max_abs": "m, rad", "peak_to_peak": "m, rad"})
register_result_type(PeriodicPeak, {"parameter": _ANGULAR, "amplitude": "m, rad"})
register_result_type(PeriodicResult, {
    "parameter": _ANGULAR, "speed": _ANGULAR, "fundamental": _ANGULAR, "order": "1",
    "dofs": "1", "coefficients": "m, rad", "max_abs": "m, rad", "peak_to_peak": "m, rad",
    "multipliers": "1", "stability_tol": "1", "iterations": "1", "residuals": "1",
    "held_dofs": "1", "nodes_pos": "m"})
register_result_type(MotionBeyond, {"speed": _ANGULAR, "unexplained": "1",
                                    "frequency": _ANGULAR, "lyapunov": "1/s",
                                    "resolution": "1/s", "departure": "1",
                                    "revolutions": "1"})
register_result_type(TorusEvent, {"parameter": _ANGULAR, "exponents": "1/s",
                                  "frequency": _ANGULAR, "lyapunov": "1/s"})
register_result_type(QuasiPeriodicResult, {
    "speed": _ANGULAR, "vc_frequency": _ANGULAR, "vc_order": "1", "tones": "1", "dofs": "1",
    "coefficients": "m, rad", "max_abs": "m, rad", "peak_to_peak": "m, rad",
    "exponents": "1/s", "iterations": "1", "residuals": "1", "held_dofs": "1",
    "nodes_pos": "m"})
register_result_type(ApiLevel1Result, {
    "mcs": _ANGULAR, "stage_q": "N/m", "q_a": "N/m", "station_share": "1", "applied": "N/m",
    "log_dec": "1", "frequency": _ANGULAR, "log_dec_a": "1", "q0": "N/m", "q_ratio": "1",
    "critical_speed_rigid": _ANGULAR, "csr": "1", "density": "kg/m^3", "csr_limit": "1"})
register_result_type(ApiUnbalanceResult, {
    "speeds": _ANGULAR, "min_speed": _ANGULAR, "mcs": _ANGULAR, "mode_speed": _ANGULAR,
    "mode_log_dec": "1", "unbalance_magnitude": "kg m", "unbalance_phase": "rad",
    "major_pp": "m", "peak_speed": _ANGULAR, "peak_pp": "m", "half_power_low": _ANGULAR,
    "half_power_high": _ANGULAR, "af": "1", "required_margin": "1", "actual_margin": "1",
    "vibration_limit": "m", "probe_peak": "m", "scale_factor": "1", "clearance": "m",
    "clearance_ratio": "1", "nodes_pos": "m"})
