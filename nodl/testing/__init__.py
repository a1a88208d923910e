"""Helpers for a package's own tests: assert that a running node conforms to its definition."""

from nodl.testing.conformance import NodeDrift, assert_conforms

__all__ = ['NodeDrift', 'assert_conforms']
