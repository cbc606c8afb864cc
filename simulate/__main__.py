"""``python -m simulate``: see :mod:`simulate.cli`."""

import sys

from simulate.cli import main

sys.exit(main())
