"""``python -m torsio``: the same as the ``torsio`` command."""

import sys

from torsio.cli import console_main

sys.exit(console_main())
