"""``python -m nodl`` is the ``nodl`` command."""

import sys

from nodl.cli.main import main

sys.exit(main())
