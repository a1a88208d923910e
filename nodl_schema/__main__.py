"""``python -m nodl_schema`` is the ``nodl`` command."""

import sys

from nodl_schema.cli.main import main

sys.exit(main())
