"""``make mutate-derivations``: the mutants of the derivations and the runtime are drawn
deterministically, and a mutant of an emitted derivation is killed by a row that checks it.

Here: the selection of the seeded sample (150 derivation and 40 runtime mutants), and the mutant the issue describes (the frequency of the horizontal closed
form changed) killed by S5:H-linear.
"""

from __future__ import annotations

import re
import time

import pytest
from chaplygin_nd.ledger.catalog import discover
from chaplygin_nd.ledger.mutation import checks, equivalence, operators, record, runloop
from chaplygin_nd.ledger.mutation import derivations as md


@pytest.mark.slow  # ~30 s: each draw enumerates every mutant of symbolic/ (ledger/mutation/operators.all_mutants)
def test_the_sample_is_deterministic_and_covers_both_targets():
    for target in ("derivations", "runtime"):
        first = md.sample(target, 30)
        assert first == md.sample(target, 30) and len(first) == 30
        assert len({m.function for m in first}) > 5
    assert "runtime.axisym.vertical_solution" in md.functions("runtime")
    assert "reduction.reduced_n4.horizontal_frequency_squared" in md.functions("derivations")
    assert not any(k.split(".")[-1].startswith("_") for k in md.functions("runtime"))


def test_a_mutant_of_the_emitted_frequency_is_killed_by_its_row():
    discover()
    key = "reduction.reduced_n4.horizontal_frequency_squared"
    fn = md.functions("derivations")[key]
    m = next(m for m, _ in operators.all_mutants(key, fn) if "2 * b * h" in m.description
             and m.operator == "sign")
    original = fn.__code__
    base = checks.baseline(["S5:H-linear"], jobs=1)
    task = md.Task("derivations", m, (("S5:H-linear", base["S5:H-linear"][0],
                                       base["S5:H-linear"][1]),))
    record = md.evaluate(task)
    assert record["outcome"] == "killed", record
    assert record["row"] == "S5:H-linear"
    assert fn.__code__ is original  # restored


def test_the_compiled_objects_key_covers_code_replaced_in_memory():
    """A runtime mutant is a function whose ``__code__`` was replaced in memory (its file did not
    change): the key of the compiled heyoka objects changes with it, so a mutant's compile never
    answers for the original, nor the original's for the mutant, and the memory token too."""
    from chaplygin_nd.runtime import expressions, jit_cache

    fn = expressions.unvec
    original = fn.__code__
    jit_cache.code_version.cache_clear()
    before = jit_cache.code_version()
    obj = object()
    jit_cache.load_or_build({"kind": "mutate-test"}, lambda: obj, use_disk=False,
                            token=("mutate-test",))
    assert jit_cache.memory_hit(("mutate-test",)) is obj
    namespace: dict = {}
    exec(compile("def unvec(m, n):\n    return m\n", "<mutant test>", "exec"), namespace)
    try:
        fn.__code__ = namespace["unvec"].__code__
        jit_cache.code_version.cache_clear()
        assert jit_cache.code_version() != before
        assert jit_cache.memory_hit(("mutate-test",)) is None
        other, _, how = jit_cache.load_or_build({"kind": "mutate-test"}, object, use_disk=False)
        assert how == "cold compile" and other is not obj
    finally:
        fn.__code__ = original
        jit_cache.code_version.cache_clear()
    assert jit_cache.code_version() == before
    assert jit_cache.memory_hit(("mutate-test",)) is obj
    jit_cache.forget_memory()


def test_a_runtime_mutant_runs_only_the_tests_given_and_is_killed_by_a_failing_one(tmp_path,
                                                                                   monkeypatch):
    from chaplygin_nd.ledger.mutation import runtime as mr

    monkeypatch.setenv(mr.WORK_ENV, str(tmp_path))
    key = "runtime.axisym.vec"
    fn = md.functions("runtime")[key]
    m = next(m for m, _ in operators.all_mutants(key, fn) if m.operator == "sign")
    code = operators.compile_mutant(fn, m)
    test = "tests/test_runtime_batches.py::test_vec_and_unvec_are_inverse_on_skew_matrices"
    record = mr.evaluate(fn, code, key, (test,), {})
    assert record["outcome"] == "killed" and test in record["reason"], record
    assert fn.__code__ is not code
    untested = mr.evaluate(fn, code, key, (), {})
    assert untested["outcome"] == "survived" and "no test calls" in untested["reason"]


def test_a_phase_prints_its_line_then_progress_at_most_every_30_s(monkeypatch):
    """Nothing is silent before "N mutants to run": a phase prints what it does when it starts,
    and a long one its progress (done of total, at most one line per 30 s of the clock)."""
    import io
    import itertools

    from chaplygin_nd.ledger import phase as phase_module

    clock = itertools.count(0.0, 4.0)  # 4 s a reading
    monkeypatch.setattr(phase_module.time, "perf_counter", lambda: next(clock))
    out = io.StringIO()
    p = phase_module.Phase("planning: running the 3 rows", what="rows done", stream=out).start()
    p.total = 40
    for _ in range(40):
        p.add()
    lines = out.getvalue().splitlines()
    assert lines[0] == "planning: running the 3 rows ..."
    done = [int(x) for x in re.findall(r"\.\.\. (\d+) of 40 rows done in", out.getvalue())]
    assert len(lines) == 1 + len(done) and 4 <= len(done) <= 6, lines  # 160 s of clock
    assert done == sorted(done) and "min left" in lines[-1]
    waiting = phase_module.Phase("one long row", total=2, what="rows done", stream=out)
    out.truncate(0)
    for _ in range(20):  # no row ends for 80 s of the clock: the waiting loop's wakes still report
        waiting.tick()
    assert 2 <= out.getvalue().count("... 0 of 2 rows done in") <= 3, out.getvalue()


def test_planning_says_what_it_runs_and_counts_rows_and_tests(capsys):
    """The two long phases of the planning, counted: the unmutated rows (the runner's results)
    and the instrumented test run (pytest's collected tests, each as it ends)."""
    from chaplygin_nd.ledger.mutation import runtime as mr
    from chaplygin_nd.ledger.phase import Phase

    discover()
    key = "reduction.reduced_n4.horizontal_frequency_squared"
    m = next(iter(operators.all_mutants(key, md.functions("derivations")[key])))[0]
    tasks = md.plan("derivations", [m], jobs=1)
    out = capsys.readouterr().out
    assert re.search(r"^planning: running the (\d+) rows that reach the mutants, unmutated", out,
                     re.M), out
    assert [r for r, _, _ in tasks[0].rows][:1] == ["S5:H-linear"]
    phase = Phase("tests", every=0.0, what="tests done").start()
    fn = md.functions("runtime")["runtime.axisym.vec"]
    reach = mr.test_map({"runtime.axisym.vec": fn}, ("tests/test_runtime_batches.py",),
                        phase=phase)
    assert phase.total and phase.done == phase.total >= len(reach["runtime.axisym.vec"]) > 0
    out = capsys.readouterr().out
    assert f"... {phase.total} of {phase.total} tests done" in out, out


def test_values_holding_arrays_are_compared_field_by_field_and_never_raise():
    """The comparers of the mutation tools on a derivation's dataclass of arrays
    (candidate_basis.Coordinates): the dataclass's own ``==`` raises on arrays, which once aborted the
    row that compared, and the few calls compared before were reported "equivalent". Field by
    field, arrays bit for bit; a ``field(compare=False)`` (a time taken) is no part of the value."""
    import dataclasses

    import numpy as np
    from chaplygin_nd.ledger.mutation.replay import identical
    from chaplygin_nd.symbolic.search import candidate_basis

    one, same = candidate_basis.coordinates(5, 2), candidate_basis.coordinates(5, 2)
    other = dataclasses.replace(one, re=2 * one.re)
    for compare in (identical, equivalence.same):
        assert compare(one, same) is True
        assert compare(one, other) is False
        assert compare({"a": np.arange(3)}, {"a": np.arange(3)}) is True
        assert compare({"a": np.arange(3)}, {"a": np.arange(3) + 1}) is False

    @dataclasses.dataclass
    class Timed:
        value: int
        seconds: float = dataclasses.field(compare=False)

    for compare in (identical, equivalence.same):
        assert compare(Timed(1, 0.5), Timed(1, 2.5)) and not compare(Timed(1, 0.5), Timed(2, 0.5))


def test_an_equivalence_check_cut_short_is_not_equal(monkeypatch):
    """``compare_on_row`` runs the row with a comparer at every call; when the row does not run to
    its end as unmutated (here: it raises after one call), the calls compared are not all the
    row's calls, so the mutant is not equivalent."""
    from chaplygin_nd.symbolic.search import sampled_field

    fn = sampled_field.mod
    original = fn.__code__

    def row_that_dies(claim_id, budget=None, base=None):
        sampled_field.mod(1, 5)
        return ("error",), "raised"

    monkeypatch.setattr(equivalence, "run_row", row_that_dies)
    equal, calls, _kind, ran = equivalence.compare_on_row(fn, original, "S6:first-integrals", 10,
                                                   base=("holds", None, ()))
    assert (equal, calls, ran) == (False, 1, True)
    assert fn.__code__ is original


def test_the_watch_sees_which_branch_of_a_one_line_conditional_ran():
    """A mutant inside the branch of a one-line conditional that no call takes has not run,
    although its line did (search_degree's ``... if prods else np.zeros(...)``: such a mutant
    was once called equivalent): the watch looks at the mutated expression's line and column."""
    from chaplygin_nd.ledger.mutation.replay import LineWatch, mutated_position

    ns: dict = {}
    exec(compile("def f(x):\n    return x + 1 if x else 7\n", "<watch test>", "exec"), ns)
    code = ns["f"].__code__
    col = "    return x + 1 if x else 7".index("7")
    assert mutated_position(f"const: line 2 col {col}: 7 -> 8") == (2, col)
    for arg, ran in ((1, False), (0, True)):
        with (watch := LineWatch(code, (2, col))):
            ns["f"](arg)
        assert watch.ran is ran
    with (whole_line := LineWatch(code, 2)):
        ns["f"](1)
    assert whole_line.ran


def test_kept_records_of_mutants_the_code_no_longer_has_are_dropped(monkeypatch, capsys):
    """--resume / --rerun keep an earlier run's records only for mutants the code still has: a
    record whose line moved (here: a line the function does not have) is dropped, with one line,
    and its function's mutants as they are now run as undecided."""
    key = "reduction.reduced_n4.horizontal_frequency_squared"
    mutants = [m for m, _ in operators.all_mutants(key, md.functions("derivations")[key])]
    monkeypatch.setattr(md, "sample", lambda target, size, seed=md.SEED: mutants)
    real = {"target": "derivations", "function": key, "outcome": "killed",
            "mutation": f"{mutants[0].operator}: {mutants[0].description}"}
    moved = dict(real, mutation="const: line 9999 col 1: 1 -> 2")
    assert record.current([real, moved]) == [real]
    assert f"dropped 1 record of mutants the code no longer has ({key})" in capsys.readouterr().out


def test_one_functions_mutants_are_split_so_every_worker_has_work_and_progress_comes_early():
    """A new user's trial: a run of one function's 21 mutants was one group, so one core worked and
    nothing was reported (or kept on Ctrl-C) until it ended. Groups are now at most a quarter of
    each worker's share, and at most GROUP for a whole run."""
    from types import SimpleNamespace as NS

    def tasks(count, function="f"):
        return [NS(target="derivations", mutant=NS(function=function), rows=(("r", None, 1.0),))
                for _ in range(count)]

    small = runloop.groups(tasks(21), jobs=2)
    assert len(small) == 7 and max(map(len, small)) == 3 and sum(map(len, small)) == 21
    whole = runloop.groups([t for f in "abcdefgh" for t in tasks(400, f)], jobs=2)
    assert max(map(len, whole)) == runloop.GROUP and sum(map(len, whole)) == 3200


def test_a_group_s_mutants_are_kept_as_they_are_decided_not_when_the_group_ends(tmp_path,
                                                                               monkeypatch):
    """Seen in a run: a group was reported (and kept in --out) only when it ended, and the costliest
    groups took more than 16 min. Here the second mutant of a one-group run waits until the
    parent has written the first into --out: it is decided only if the parent kept the first
    while the group was still running (a bounded wait, then the record says it was not)."""
    import json
    from types import SimpleNamespace as NS

    out = tmp_path / "run.json"

    def evaluate(task):
        record = {"target": "derivations", "function": "f", "index": task.mutant.index,
                  "mutation": f"m{task.mutant.index}", "row": None, "outcome": "killed",
                  "reason": ""}
        if task.mutant.index == 1:
            deadline = time.monotonic() + 120
            while not (out.is_file() and json.loads(out.read_text())["mutants"]):
                if time.monotonic() > deadline:
                    return dict(record, outcome="error", reason="the first was not kept")
                time.sleep(0.05)
        return record

    monkeypatch.setattr(md, "evaluate", evaluate)
    monkeypatch.setattr(runloop, "WRITE_SECONDS", 0.0)
    monkeypatch.setattr(runloop, "init_worker", lambda: None)
    tasks = [NS(target="derivations", mutant=NS(function="f", index=i), rows=()) for i in range(8)]
    first = runloop.groups(tasks, 1)[0]
    assert [t.mutant.index for t in first] == [0, 1]   # 0 and 1 are decided in one task
    args = NS(out=out, seed=0, sample=None)
    records, runs, run = [], [], {}
    mine = runloop.run_tasks(tasks, 1, records, runs, args, run, time.perf_counter(), 0.0)
    assert [r["outcome"] for r in mine] == ["killed"] * 8
    assert [r["index"] for r in records] == list(range(8))   # each once


def test_a_time_budget_is_not_taken_for_a_result_by_except_exception():
    """A row or a replay catches ``Exception`` (a raise is a value there); the budget must pass
    through it."""
    with pytest.raises(checks.BudgetExceeded), checks.time_budget(0.05):
        try:
            while True:
                pass
        except Exception:  # noqa: BLE001 - what a row may do
            pass


def test_a_replay_that_never_returns_is_cut_at_the_budget_and_the_check_is_run(monkeypatch):
    """Seen in a run: a mutant of reduced5_invariants.products recursed without end inside a replay,
    which had no budget, and held a worker. The replay now has the check's budget; past it, the
    check itself is run (with its own budget) and decides."""
    from types import SimpleNamespace as NS

    from chaplygin_nd.ledger.mutation.replay import Recording

    def forever(*args, **kwargs):
        while True:
            pass

    ran = []
    monkeypatch.setattr(checks, "MIN_BUDGET", 0.1)
    monkeypatch.setattr(md, "_recording", lambda *a: Recording(calls=[((), {}, 1, (), {})]))
    monkeypatch.setattr(md, "replay", forever)
    monkeypatch.setattr(md, "_run_check",
                        lambda fn, code, original, check, base, seconds, key='': (ran.append(check) or True,
                                                                          "ran past its budget"))
    fn = md.functions("derivations")["reduction.reduced_n4.horizontal_frequency_squared"]
    m = operators.all_mutants("reduction.reduced_n4.horizontal_frequency_squared", fn)[0][0]
    task = NS(mutant=m, rows=(("S5:H-linear", ("holds",), 0.01),), emitted=frozenset())
    record = {}
    md._decide_by_rows(task, fn, fn.__code__, record)
    assert ran == ["S5:H-linear"]
    assert record["outcome"] == "killed" and record["not replayed"] == {"S5:H-linear": "replay past 0 s"}


def test_values_of_a_slots_class_without_equality_are_compared_attribute_by_attribute():
    """Seen in a run: wedge_integrals' dual numbers (``__slots__``, no ``__eq__``) were compared by
    identity, so a mutant that only swapped the factors of a product (the same dual number)
    "differed" at every call and survived."""
    from chaplygin_nd.ledger.mutation.replay import identical
    from chaplygin_nd.symbolic.family.wedge_integrals import _Dual

    x, y = _Dual(2, 3), _Dual(5, 7)
    assert identical(x * y, y * x) and equivalence.same(x * y, y * x)
    assert not identical(x * y, x * x) and not equivalence.same(x * y, x * x)
    assert not identical(_Dual(2, 3), _Dual(2, 4)) and not equivalence.same(_Dual(2, 3), _Dual(2, 4))


def test_a_survivor_meets_the_slow_tests_of_its_module_last(tmp_path, monkeypatch):
    """The mutation run leaves slow tests out per mutant; a survivor is tried against them last
    (wedge_n6.h2_residual's symbolic check is a slow test). Here a slow test of
    algebra.so_dim fails on a mutant of it and passes on the original; a file with no slow test
    kills nothing."""
    from chaplygin_nd.ledger.mutation import runtime as mr

    key = "algebra.so_dim"
    fn = md.functions("derivations")[key]
    mutant = next(m for m, _ in operators.all_mutants(key, fn) if m.operator == "const")
    code = operators.compile_mutant(fn, mutant)
    slow = tmp_path / "test_slow_so_dim.py"
    slow.write_text("import pytest\nfrom chaplygin_nd.symbolic import algebra\n\n\n"
                    "@pytest.mark.slow\ndef test_so_dim():\n"
                    "    assert [algebra.so_dim(n) for n in range(2, 7)] == [1, 3, 6, 10, 15]\n")
    quick = tmp_path / "test_quick_so_dim.py"
    quick.write_text("from chaplygin_nd.symbolic import algebra\n\n\n"
                     "def test_so_dim():\n    assert algebra.so_dim(4) == 6\n")
    monkeypatch.setattr(mr, "mentioning", lambda keys: (str(slow),))
    assert mr.kill_slow(fn, code, key) is not None
    assert mr.kill_slow(fn, fn.__code__, key) is None
    monkeypatch.setattr(mr, "mentioning", lambda keys: (str(quick),))
    assert mr.kill_slow(fn, code, key) is None
    broken = tmp_path / "test_broken_slow.py"   # fails unmutated: it can kill nothing
    broken.write_text("import pytest\n\n\n@pytest.mark.slow\ndef test_broken():\n    assert False\n")
    monkeypatch.setattr(mr, "mentioning", lambda keys: (str(broken),))
    assert mr.kill_slow(fn, code, key) is None


def test_resume_names_stale_records_and_keeps_each_mutant_once(monkeypatch, capsys):
    """--resume keeps a record only for the code as it is now: one decided on another source of
    its function (its digest differs) is stale and decided again, a mutant recorded twice keeps
    its latest record, a record without a digest (written before digests were kept) is kept and
    stamped, and every kept record takes its mutant's index now."""
    key = "reduction.reduced_n4.horizontal_frequency_squared"
    fn = md.functions("derivations")[key]
    mutants = [m for m, _ in operators.all_mutants(key, fn)]
    monkeypatch.setattr(md, "sample", lambda target, size, seed=md.SEED: mutants)
    digest = operators.source_digest(fn)

    def rec(m, **extra):
        return {"target": "derivations", "function": key, "index": 99, "outcome": "killed",
                "mutation": f"{m.operator}: {m.description}", "source": digest, **extra}

    fresh, stale = rec(mutants[0]), rec(mutants[1], source="0" * 16)
    older, latest = rec(mutants[2], outcome="equivalent"), rec(mutants[2])
    assert record.current([fresh, stale, older, latest]) == [fresh, latest]
    assert fresh["index"] == mutants[0].index and latest["index"] == mutants[2].index
    out = capsys.readouterr().out
    assert f"dropped 1 record decided on another source of their function ({key})" in out
    assert f"dropped 1 record of a mutant recorded twice ({key})" in out
    unstamped = {k: v for k, v in rec(mutants[3]).items() if k != "source"}
    assert record.current([dict(unstamped)]) == [dict(unstamped, index=mutants[3].index,
                                                      source=digest)]
    assert "written without the digest of their function's source" in capsys.readouterr().out
    found = record.consistency([fresh], targets=("derivations",))
    assert not found["gone"] and not found["stale"] and len(found["undecided"]) == len(mutants) - 1


def test_a_slow_test_that_does_not_call_the_function_kills_none_of_its_mutants(tmp_path, monkeypatch):
    """A slow test of a file that names the module but never calls the function (here: one that
    reads the function's source, which a mutant's code does not have, as the test listing every
    mutant does) failed under each of wedge_n6.h2_residual's mutants and killed all 11 that
    survived the quick test. Only the slow tests that call the function are run."""
    from chaplygin_nd.ledger.mutation import runtime as mr

    key = "algebra.so_dim"
    fn = md.functions("derivations")[key]
    mutant = next(m for m, _ in operators.all_mutants(key, fn) if m.operator == "const")
    code = operators.compile_mutant(fn, mutant)
    reads = tmp_path / "test_slow_reads_source.py"
    reads.write_text("import inspect\n\nimport pytest\nfrom chaplygin_nd.symbolic import algebra\n\n\n"
                     "@pytest.mark.slow\ndef test_reads_source():\n"
                     "    assert 'def so_dim' in inspect.getsource(algebra.so_dim)\n")
    monkeypatch.setattr(mr, "mentioning", lambda keys: (str(reads),))
    assert mr.kill_slow(fn, code, key) is None


def test_a_mutant_of_a_cached_derivation_compiles_to_the_plain_function_s_code():
    """The mutated AST of a cached derivation kept its ``@functools.cache``: the name it bound
    was the cache wrapper, which has no code, and every such mutant was recorded killed ("does
    not compile") without being run (360 mutants of 21 cached derivations)."""
    key = "axisymmetric.frame_coefficients"
    fn = md.functions("derivations")[key]
    assert fn is not vars(__import__(fn.__module__, fromlist=["_"]))[fn.__name__]  # it is cached
    for m, _ in operators.all_mutants(key, fn)[:5]:
        code = operators.compile_mutant(fn, m)
        assert code.co_name == fn.__name__ and code.co_argcount == fn.__code__.co_argcount
