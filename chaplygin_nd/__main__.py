"""``python -m chaplygin_nd``: the ``chaplygin`` command (see :mod:`chaplygin_nd.cli`)."""

import sys

from chaplygin_nd.cli import main

sys.exit(main())
