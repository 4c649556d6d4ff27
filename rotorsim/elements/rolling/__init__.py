"""Nonlinear rolling-element bearings (rigid rings: seed 000; flexible rings: seed 001)."""
