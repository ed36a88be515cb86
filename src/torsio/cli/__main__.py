"""``python -m torsio.cli``: the same as the ``torsio`` command."""

import sys

from torsio.cli import console_main

sys.exit(console_main())
