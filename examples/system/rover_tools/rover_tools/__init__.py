"""Example system: the rover's operator tools (definitions only)."""
