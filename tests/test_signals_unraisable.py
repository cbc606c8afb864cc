"""A signal whose exception cannot propagate (raised inside a weakref callback during garbage
collection: CI printed "Exception ignored in: <function WeakSet.__init__.<locals>._remove>" with a
traceback before ``interrupted``) is not printed and still interrupts the main thread
(chaplygin_nd.signals)."""

from __future__ import annotations

import subprocess
import sys

CODE = """
import signal, time, weakref
from chaplygin_nd import signals
signals.take_signals()

class Thing:
    pass

def callback(ref):  # a signal handled here: the handler's exception cannot propagate
    signals.handler(signal.SIGINT, None)

thing = Thing()
keep = weakref.ref(thing, callback)
try:
    del thing  # runs the callback
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        time.sleep(0.01)
    print("not interrupted")
except signals.Interrupted:
    print("interrupted in the main thread")
"""


def test_an_interrupt_in_a_weakref_callback_is_not_printed_and_not_lost():
    r = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, timeout=60)
    assert r.stdout.strip() == "interrupted in the main thread", (r.stdout, r.stderr)
    assert "Traceback" not in r.stderr and "Exception ignored" not in r.stderr, r.stderr
