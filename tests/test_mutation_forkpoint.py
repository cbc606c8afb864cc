"""A row run with a mutant from the process parked at the mutated function's first call
(ledger/mutation/forkpoint.py) gives what the same row run whole with the mutant in place gives;
the work before the first call is done once; a row that never calls the function, a copy that
never answers and the budget are handled."""

from __future__ import annotations

import os
import time

import pytest
from chaplygin_nd.ledger.mutation import checks, forkpoint

PREFIX_RUNS = []  # appended to by every run of the prefix, in whatever process runs it


def f(x):
    return 2 * x + 1


def row():
    """A 'row': work before the first call of f (counted in a file, so that a run in another
    process is seen), then several calls whose results it combines."""
    with open(os.environ["FORKPOINT_TEST_LOG"], "a", encoding="utf-8") as log:
        log.write("prefix\n")
    values = [f(k) for k in range(5)]
    return ("row", tuple(values), sum(values))


def never_calls():
    return ("row", 0)


def _mutant(source: str):
    ns: dict = {}
    exec(compile(source, __file__, "exec"), f.__globals__ | ns, ns)  # noqa: S102 - test mutants
    return ns["f"].__code__


MUTANTS = ["def f(x):\n    return 2 * x - 1\n",
           "def f(x):\n    return x + 1\n",
           "def f(x):\n    return 2 * x + 1\n",
           "def f(x):\n    raise ValueError('mutant')\n"]


def _in_place(code):
    original = f.__code__
    f.__code__ = code
    try:
        return row()
    except ValueError as err:
        return ("raised", str(err))
    finally:
        f.__code__ = original


def _guarded():
    try:
        return row()
    except ValueError as err:
        return ("raised", str(err))


def test_each_mutant_gives_what_the_row_run_in_place_gives(tmp_path, monkeypatch):
    log = tmp_path / "log"
    monkeypatch.setenv("FORKPOINT_TEST_LOG", str(log))
    codes = [_mutant(src) for src in MUTANTS]
    expected = [_in_place(code) for code in codes]
    assert len(set(expected)) == 4  # the mutants differ from one another
    log.write_text("")
    parked = forkpoint.Parked(f, _guarded)
    try:
        assert parked.usable and parked.first_call is not None
        got = [parked.run(code) for code in codes]
        again = parked.run(codes[0])  # a copy leaves nothing behind for the next one
    finally:
        parked.close()
    assert got == expected
    assert again == expected[0]
    assert log.read_text().count("prefix") == 1  # the prefix ran once, for all five
    assert f.__code__ is not codes[0] and f(3) == 7  # the caller's function is untouched


def test_a_row_that_never_calls_the_function_is_left_to_the_caller(tmp_path, monkeypatch):
    monkeypatch.setenv("FORKPOINT_TEST_LOG", str(tmp_path / "log"))
    parked = forkpoint.Parked(f, never_calls)
    assert not parked.usable
    assert parked.run(_mutant(MUTANTS[0])) is None


def test_the_budget_goes_on_in_the_copy(tmp_path, monkeypatch):
    monkeypatch.setenv("FORKPOINT_TEST_LOG", str(tmp_path / "log"))
    endless = _mutant("def f(x):\n    while True:\n        x += 1\n")

    def budgeted():
        try:
            with checks.time_budget(1.0):
                return row()
        except checks.BudgetExceeded:
            return ("timeout",)

    parked = forkpoint.Parked(f, budgeted)
    try:
        time.sleep(1.5)  # parked: its own timer is stopped, so no alarm fires while it waits
        start = time.perf_counter()
        assert parked.run(endless) == ("timeout",)
        assert time.perf_counter() - start < 10
        assert parked.run(_mutant(MUTANTS[1])) == _in_place(_mutant(MUTANTS[1]))
    finally:
        parked.close()


def test_a_copy_that_never_answers_is_killed(tmp_path, monkeypatch):
    monkeypatch.setenv("FORKPOINT_TEST_LOG", str(tmp_path / "log"))
    stuck = _mutant("def f(x):\n    import time\n    time.sleep(600)\n")
    parked = forkpoint.Parked(f, row)  # no budget in the row: only the grace period stops it
    try:
        start = time.perf_counter()
        got = parked.run(stuck, budget_grace=1.0)
        assert got is not None and got[0] == ("timeout",)
        assert time.perf_counter() - start < 30
        assert parked.run(_mutant(MUTANTS[1])) == _in_place(_mutant(MUTANTS[1]))
    finally:
        parked.close()


@pytest.mark.slow
def test_the_verdicts_are_those_of_rows_run_whole():
    """Every mutant of two derivations with cheap rows: decided with the rows run from the
    first call and run whole in the worker, the same outcome and the same row."""
    from chaplygin_nd.bench.bench_mutation import compare

    result = compare(("model.L_matrix", "vertical.chi_coefficient"))
    assert result["mutants"] >= 10
    assert result["verdicts differ"] == []


def test_on_fork_runs_in_each_copy_before_the_mutant(tmp_path, monkeypatch):
    log = tmp_path / "log"
    monkeypatch.setenv("FORKPOINT_TEST_LOG", str(log))

    def mark():
        with open(log, "a", encoding="utf-8") as out:
            out.write("copy\n")

    parked = forkpoint.Parked(f, _guarded, on_fork=mark)
    try:
        codes = [_mutant(src) for src in MUTANTS[:2]]
        assert [parked.run(c) for c in codes] == [_in_place(c) for c in codes]
    finally:
        parked.close()
    assert log.read_text().count("copy") == 2


def test_two_parked_processes_close_in_any_order(tmp_path, monkeypatch):
    """The second parked process holds a copy of the first one's command pipe (forked after
    it): closing the first must still end it (it once waited there for good)."""
    monkeypatch.setenv("FORKPOINT_TEST_LOG", str(tmp_path / "log"))
    first = forkpoint.Parked(f, _guarded)
    second = forkpoint.Parked(f, _guarded)
    start = time.perf_counter()
    first.close()
    second.close()
    assert time.perf_counter() - start < 10
