"""``python -m torsio.cli``: the same as the ``torsio`` command."""

import sys

from torsio.cli import main

sys.exit(main())
