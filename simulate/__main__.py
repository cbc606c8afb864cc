"""``python -m chaplygin_nd.simulate`` (``chaplygin simulate``): see :mod:`chaplygin_nd.simulate.cli`."""

import sys

from chaplygin_nd.simulate.cli import main

sys.exit(main())
