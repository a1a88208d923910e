"""Former path of the ``nodl.checks`` extension point: :mod:`nodl.system.checks`.

A check plug-in written against this path keeps working for one release, with a
``DeprecationWarning``; import ``nodl.system.checks`` instead.
"""

from __future__ import annotations

import warnings

from nodl.system.checks import CHECK_GROUP, CheckExtension, load_checks, run_checks

__all__ = ['CHECK_GROUP', 'CheckExtension', 'load_checks', 'run_checks']

warnings.warn('nodl.analysis.checks moved to nodl.system.checks; import it from there',
              DeprecationWarning, stacklevel=2)
