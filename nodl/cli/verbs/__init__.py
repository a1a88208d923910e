"""The built-in verbs, one module each (registered as ``nodl.verbs`` entry points)."""
