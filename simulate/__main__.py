"""``python -m chaplygin_nd.simulate`` (``chaplygin simulate``): see :mod:`chaplygin_nd.simulate.scene.cli`."""

import sys

from chaplygin_nd.simulate.scene.cli import main

sys.exit(main())
