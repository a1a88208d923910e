"""Example system: the rover's navigation nodes (definitions only)."""
