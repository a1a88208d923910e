"""Frontends: from text in some syntax to plain data (and positions)."""
