"""Shared pytest setup: mpmath precision is reset before every test (mpmath's own habit), so a
test may raise ``mp.dps`` freely without leaking it into the next one."""

import mpmath
import pytest


@pytest.fixture(autouse=True)
def _reset_mpmath_precision():
    mpmath.mp.dps = 15
    yield
    mpmath.mp.dps = 15
