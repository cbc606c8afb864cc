"""A derivation's mutant that changed no row is run against its tests from the test session parked
at the function's first call (ledger/mutation/runtime.py, ``kill`` with ``fork``), as
``chaplygin mutate-derivations`` now does: each mutant gives the answer the whole session run in
the worker gives (killed by the same test, or passing)."""

from __future__ import annotations

import importlib
import sys

import pytest
from chaplygin_nd.ledger.mutation import runtime as mr

TARGET = "def g(x):\n    return 3 * x\n"
TESTS = ("from mutkill_target import g\n\n\ndef test_small():\n    assert g(2) == 6\n\n\n"
         "def test_large():\n    assert g(10) == 30\n")
MUTANTS = {"def g(x):\n    return 3 * x + 0\n": None,   # equivalent: every test passes
           "def g(x):\n    return 2 * x + 2\n": "test_large",  # g(2) = 6 still: the second test
           "def g(x):\n    raise ValueError('mutant')\n": "test_small"}


@pytest.fixture
def target(tmp_path, monkeypatch):
    (tmp_path / "mutkill_target.py").write_text(TARGET, encoding="utf-8")
    (tmp_path / "test_mutkill_probe.py").write_text(TESTS, encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setenv(mr.WORK_ENV, str(tmp_path))
    sys.modules.pop("mutkill_target", None)
    module = importlib.import_module("mutkill_target")
    yield module.g, str(tmp_path / "test_mutkill_probe.py")
    mr.end_parked()
    sys.modules.pop("mutkill_target", None)


def _code(source: str):
    ns: dict = {}
    exec(compile(source, "mutkill_target.py", "exec"), ns)  # noqa: S102 - test mutants
    return ns["g"].__code__


def test_the_parked_session_answers_as_the_whole_session(target):
    g, tests = target
    original = g.__code__
    for source, killer in MUTANTS.items():
        whole = mr.kill(g, _code(source), "probe.g", (tests,), fork=False)
        parked = mr.kill(g, _code(source), "probe.g", (tests,), fork=True)
        assert g.__code__ is original
        assert (whole is None) == (killer is None), (source, whole)
        assert (parked is None) == (whole is None), (source, whole, parked)
        if killer is not None:
            assert killer in whole and killer in parked, (whole, parked)
    assert len(mr._PARKED) == 1  # one session parked for all three mutants
