"""``python -m torsio``: the same as the ``torsio`` command."""

import sys

from torsio.cli import main

sys.exit(main())
