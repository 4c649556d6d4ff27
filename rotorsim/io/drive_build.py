"""The :class:`rotorsim.TorqueDrive` of a model file's drive spec
(:class:`~rotorsim.io.long_specs.DriveSpec`)."""

from __future__ import annotations

from rotorsim.analyses.transient.torque_drive import TorqueDrive
from rotorsim.analyses.transient.torque_laws import (
    ConstantTorque,
    InductionMotor,
    PulsatingTorque,
    QuadraticTorque,
    TorqueCurve,
    TorqueLaw,
    ViscousTorque,
)
from rotorsim.io.long_specs import DriveSpec, Law


def torque_drive(spec: DriveSpec, initial_speed: float, name: str = "drive") -> TorqueDrive:
    """The drive with initial speed ``initial_speed`` [rad/s]; ``name`` names it in
    messages."""
    return TorqueDrive(
        motor=torque_law(spec.motor), drive_node=spec.node,
        loads=[(node, torque_law(law)) for node, law in spec.loads],
        friction=[(node, torque_law(law)) for node, law in spec.friction],
        initial_speed=float(initial_speed), inertia=spec.inertia,
        torque_damping=spec.torque_damping, name=name)


def torque_law(law: Law) -> TorqueLaw:
    """The law object of a model file's ``{"type": ..., ...}`` (SI)."""
    kind = law["type"]
    reactive = bool(law.get("reactive", True))
    out: TorqueLaw
    if kind == "constant":
        out = ConstantTorque(float(law["torque"]), reactive)
    elif kind == "quadratic":
        out = QuadraticTorque(float(law["coefficient"]))
    elif kind == "viscous":
        out = ViscousTorque(float(law["coefficient"]))
    elif kind == "curve":
        out = TorqueCurve(law["speeds"], law["torques"], reactive)
    else:
        out = InductionMotor(float(law["breakdown_torque"]), float(law["breakdown_slip"]),
                             float(law["synchronous_speed"]))
    ripple = law.get("ripple")
    if ripple is not None:
        out = PulsatingTorque(out, float(ripple["amplitude"]), float(ripple["order"]),
                              float(ripple.get("phase", 0.0)))
    return out
