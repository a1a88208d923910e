"""Moved to :mod:`nodl.registry.overlay` (the registry consults the definitions folders first).

Temporary: importers are being updated while other work is in progress; this module goes
when none is left (tests/test_import_contracts.py lists what still imports it).
"""

from nodl.registry.overlay import *  # noqa: F401,F403
from nodl.registry.overlay import __all__  # noqa: F401
