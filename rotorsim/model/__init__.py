"""Materials and the rotor model."""
