"""``python -m chaplygin_nd``: the ``chaplygin`` command (see :mod:`chaplygin_nd.cli`)."""

import sys

try:
    from chaplygin_nd.cli import entry
except KeyboardInterrupt:  # Ctrl-C in the few lines before entry() takes the signals
    print("interrupted", file=sys.stderr)
    sys.exit(130)

entry()
