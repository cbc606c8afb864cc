r"""The runtime target of ``make mutate-derivations``: which tests reach each runtime function, and
how one mutant of it is run against them.

The checks of ``runtime/`` are tests, not rows. :func:`test_map` runs the test files that import
the runtime (:func:`runtime_tests`) once, unmutated, in this process, with the recorder of
:mod:`ledger.reach` watching every public runtime function around each test (its setup, call and
teardown): ``{function: [test id, ...]}`` with each test's seconds. Before each test the
in-memory compiled objects are dropped and the test runs against an empty disk cache, so a test
that builds an integrator is seen calling the builders even when an earlier test built it first.

A mutant of a function is then run (:func:`evaluate`) against only the tests that reach it, fastest
first, with ``pytest -x``: ``killed`` at the first failing test; otherwise the same tests are run
once more computing both versions at every call (:func:`equivalence`): ``equivalent`` when the
mutant's outputs are bit-for-bit the original's at every call, else ``survived``. A test that
reaches the function only through a subprocess, a session fixture filled by another test or
module-level code is not in its list: that can only leave a mutant alive, never kill it falsely.

**Caches.** Compiled heyoka objects are reused between mutants: their key
(:func:`runtime.jit_cache.code_version`) covers the live code of the modules that build the
expression graphs, so a mutant's compile never answers for the original or vice versa; each worker
keeps one private cache folder whose ``heyoka/`` subfolder survives from mutant to mutant while
every other subfolder (evidence, results: keyed by source files, which a mutant in memory does
not change) is emptied before each mutant. A mutant of :mod:`runtime.jit_cache` itself runs
against an empty cache folder and an empty memory (it may store wrong entries).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import shutil
import tempfile
import time
import warnings
from pathlib import Path
from types import FunctionType
from typing import Any

from chaplygin_nd.ledger.catalog import ROOT

_IMPORTS_RUNTIME = re.compile(r"^\s*(from chaplygin_nd\.runtime\b|import chaplygin_nd\.runtime\b|"
                              r"from chaplygin_nd import runtime\b)", re.MULTILINE)
#: The environment variable naming the parent of the workers' cache folders (set by the parent).
WORK_ENV = "CHAPLYGIN_ND_MUTATE_WORK"


def runtime_tests() -> tuple[str, ...]:
    """The tests that check the runtime: every test file that imports it (found, not listed: a
    hand-kept list had missed tests/test_p_coefficients.py, so p_coefficients' mutants looked
    untested)."""
    return tuple(sorted(str(p.relative_to(ROOT)) for p in (ROOT / "tests").glob("test_*.py")
                        if _IMPORTS_RUNTIME.search(p.read_text(encoding="utf-8"))))


def runtime_functions() -> dict[str, FunctionType]:
    """``{"runtime.axisym.zeta": function}`` for every public function of ``runtime/``."""
    import importlib
    import pkgutil

    import chaplygin_nd.runtime as runtime

    out: dict[str, FunctionType] = {}
    for info in sorted(pkgutil.iter_modules(runtime.__path__), key=lambda i: i.name):
        mod = importlib.import_module(f"chaplygin_nd.runtime.{info.name}")
        for attr, obj in sorted(vars(mod).items()):
            if (not attr.startswith("_") and isinstance(obj, FunctionType)
                    and obj.__module__ == mod.__name__ and not obj.__code__.co_freevars):
                out[f"runtime.{info.name}.{attr}"] = obj
    return out


class _InterruptSeen:
    """A pytest plugin noting a real Ctrl-C or SIGTERM: pytest's exit status INTERRUPTED also
    means a collection error, which must stop the run as an error, not as an interrupt."""

    seen = False

    def pytest_keyboard_interrupt(self, excinfo):  # noqa: ARG002 - pytest's hook signature
        self.seen = True


def _pytest(args: list[str], plugins=(), none_ok: bool = False) -> tuple[int, str]:
    """``pytest.main(args)`` in this process from the checkout: (exit status, the first failure's
    line). ``none_ok``: no test collected is a pass (status 0), not an error."""
    import pytest

    buffer = io.StringIO()
    interrupt = _InterruptSeen()
    # the test ids are relative to the checkout: run from there whatever the caller's folder (from
    # elsewhere pytest found no file, and every mutant was reported reached by no test)
    # ResourceWarning: pytest's own numbered temporary folders leave a scandir iterator to the
    # garbage collector, which in a long-lived worker may run inside a later pytest.main whose
    # "error" filter turns it into an exception there (seen once in 80 mutants: an error
    # outcome); it says nothing about a mutant
    with contextlib.chdir(ROOT), contextlib.redirect_stdout(buffer), \
            contextlib.redirect_stderr(buffer), warnings.catch_warnings():
        warnings.simplefilter("ignore", ResourceWarning)
        code = pytest.main(["-q", "-p", "no:cacheprovider", "--no-header", "-W",
                            "ignore::ResourceWarning", *args], plugins=[*plugins, interrupt])
    if code == pytest.ExitCode.INTERRUPTED and interrupt.seen:  # Ctrl-C or SIGTERM reached pytest:
        raise KeyboardInterrupt("pytest was interrupted")  # the run ends, no mutant killed by it
    if none_ok and code == pytest.ExitCode.NO_TESTS_COLLECTED:
        return 0, ""
    lines = [ln for ln in buffer.getvalue().splitlines() if ln.startswith(("FAILED", "ERROR"))]
    note = (lines[0] if lines else f"pytest exit {code}")[:200]
    if code not in (pytest.ExitCode.OK, pytest.ExitCode.TESTS_FAILED):  # usage, internal, none run
        raise RuntimeError(f"pytest could not run {' '.join(args)[:200]}: exit {int(code)}: "
                           + (buffer.getvalue().strip().splitlines() or [''])[-1][:200])
    return int(code), note


@contextlib.contextmanager
def _cache_root(fresh: bool):
    """``$CHAPLYGIN_ND_CACHE`` for one mutant: the worker's folder with only ``heyoka/`` kept, or
    (``fresh``) an empty temporary one with the in-memory objects dropped before and after."""
    from chaplygin_nd.runtime import jit_cache

    from chaplygin_nd.cache import ENV

    saved = os.environ.get(ENV)
    parent = os.environ.get(WORK_ENV) or tempfile.gettempdir()
    with contextlib.ExitStack() as stack:
        if fresh:
            root = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="mutant-", dir=parent)))
            jit_cache.forget_memory()
        else:
            root = Path(parent) / f"worker-{os.getpid()}"
            root.mkdir(mode=0o700, exist_ok=True)
            for sub in root.iterdir():
                if sub.name != "heyoka":
                    shutil.rmtree(sub) if sub.is_dir() and not sub.is_symlink() else sub.unlink()
        os.environ[ENV] = str(root)
        try:
            yield root
        finally:
            if fresh:
                jit_cache.forget_memory()
            if saved is None:
                os.environ.pop(ENV, None)
            else:
                os.environ[ENV] = saved


def _watch(functions: dict[str, FunctionType], reached: dict, phase=None):
    """A pytest plugin recording into ``reached`` ``{test id: (seconds, functions called)}`` for
    each test (setup, call and teardown), every test with empty caches; ``phase``
    (:class:`ledger.phase.Phase`) gets the number of tests collected and counts them as they end."""
    import pytest
    from chaplygin_nd.ledger.reach import Recorder
    from chaplygin_nd.runtime import jit_cache

    class Watch:
        @pytest.hookimpl(hookwrapper=True)
        def pytest_runtest_protocol(self, item, nextitem):  # noqa: ARG002 - pytest's signature
            _empty_caches()
            with _cache_root(fresh=True), Recorder(functions) as rec:
                start = time.perf_counter()
                outcome = yield
            jit_cache.forget_memory()
            reached[item.nodeid] = (time.perf_counter() - start, tuple(sorted(rec.calls)))
            del outcome

        @pytest.hookimpl
        def pytest_collection_finish(self, session):
            if phase is not None:
                phase.total = len(session.items)

        @pytest.hookimpl
        def pytest_runtest_logfinish(self, nodeid, location):  # noqa: ARG002 - pytest's signature
            if phase is not None:
                phase.add()

        @pytest.hookimpl
        def pytest_runtest_logreport(self, report):
            if report.failed:
                failed.add(report.nodeid)

    failed: set[str] = set()
    return Watch(), failed


def _empty_caches() -> None:
    from chaplygin_nd.ledger.mutation.cache_scope import clear

    clear()


def test_map(functions: dict[str, FunctionType] | None = None,
             files: tuple[str, ...] | None = None, phase=None,
             slow: bool = False) -> dict[str, list[tuple[str, float]]]:
    """``{function: [(test id, seconds), ...]}`` (fastest first): the tests of ``files`` (default
    :func:`runtime_tests`) that call each of ``functions`` (default: the runtime's), recorded in
    one unmutated run. A test that fails unmutated reaches nothing (it could not tell a mutant
    apart); tests marked ``slow`` are left out (too long to run once per mutant: a function only
    they reach is reported as reached by no test), or, with ``slow``, they alone are run (none
    collected: none reaches). ``phase`` (:class:`ledger.phase.Phase`) counts the tests as they
    end."""
    functions = runtime_functions() if functions is None else functions
    reached: dict[str, tuple[float, tuple[str, ...]]] = {}
    watch, failed = _watch(functions, reached, phase)
    _pytest(["-m", "slow and not site" if slow else "not slow and not site",
             *(runtime_tests() if files is None else files)], plugins=[watch], none_ok=slow)
    out: dict[str, list[tuple[str, float]]] = {key: [] for key in functions}
    for test, (seconds, calls) in reached.items():
        # calls may name functions not watched here: a cache hit is credited with everything its
        # computation called in any earlier watched run of this process (reach.CALLEES)
        for key in () if test in failed else set(calls) & set(out):
            out[key].append((test, round(seconds, 3)))
    return {key: sorted(tests, key=lambda t: (t[1], t[0])) for key, tests in out.items()}


def mentioning(keys) -> tuple[str, ...]:
    """The test files that name the module of some key ``module.name`` (where a test of a
    derivation no row reaches can be: a test may reach the function through another of the
    module's functions, so the function's own name is not required)."""
    out = []
    for path in sorted((ROOT / "tests").glob("test_*.py")):
        text = path.read_text(encoding="utf-8")
        if any(re.search(rf"\b{re.escape(key.rsplit('.', 1)[0].split('.')[-1])}\b", text)
               for key in keys):
            out.append(str(path.relative_to(ROOT)))
    return tuple(out)


def _bitwise_equal(x, y) -> bool:
    import numpy as np

    if isinstance(x, (tuple, list)) and isinstance(y, (tuple, list)):
        return len(x) == len(y) and all(_bitwise_equal(u, v) for u, v in zip(x, y))
    try:
        xa, ya = np.asarray(x), np.asarray(y)
    except Exception:  # noqa: BLE001 - not array-like: compare as objects
        return x is y or x == y
    if xa.dtype == object or ya.dtype == object:
        return str(x) == str(y)  # e.g. heyoka expressions: the same expression text
    return xa.shape == ya.shape and xa.dtype == ya.dtype and np.array_equal(xa, ya, equal_nan=True)


def _exact_or_bitwise(x, y) -> bool:
    """Exact equality (SymPy values, :func:`.equivalence.same`), bit-for-bit for arrays."""
    from chaplygin_nd.ledger.mutation.equivalence import same

    try:
        return bool(same(x, y))
    except Exception:  # noqa: BLE001 - e.g. NumPy arrays: compared bit for bit
        return _bitwise_equal(x, y)


def _code_objects(code) -> set:
    out = {code}
    for const in code.co_consts:
        if hasattr(const, "co_code"):
            out |= _code_objects(const)
    return out


def equivalence(fn, mutant_code, tests: list[str], fresh: bool, same=_bitwise_equal,
                line: int | None = None) -> tuple[bool, int, bool]:
    """Run ``tests`` once with both versions computed at every call of ``fn``: (all outputs equal
    by ``same``, number of calls, whether the mutant executed source line ``line`` — the mutated
    one — at least once: equal outputs prove nothing about code that never ran). The original's
    output is what the tests see."""
    import sys

    orig = FunctionType(fn.__code__, fn.__globals__, fn.__name__, fn.__defaults__)
    orig.__kwdefaults__ = fn.__kwdefaults__
    mut = FunctionType(mutant_code, fn.__globals__, fn.__name__, fn.__defaults__)
    mut.__kwdefaults__ = fn.__kwdefaults__
    state: dict[str, Any] = {"calls": 0, "same": True, "ran": line is None}
    codes = _code_objects(mutant_code)

    def local(frame, event, arg):
        if event == "line" and frame.f_lineno == line:
            state["ran"] = True
        return None if state["ran"] else local

    def watch(frame, event, arg):
        return local if frame.f_code in codes and not state["ran"] else None

    def hook(*args, **kwargs):
        want = orig(*args, **kwargs)
        state["calls"] += 1
        saved = sys.gettrace()
        sys.settrace(None if state["ran"] else watch)
        try:
            got = mut(*args, **kwargs)
            state["same"] = state["same"] and same(want, got)
        except Exception:  # noqa: BLE001 - raises where the original does not
            state["same"] = False
        finally:
            sys.settrace(saved)
        return want

    from chaplygin_nd.ledger.mutation.replay import calls_through

    with calls_through(fn, hook), _cache_root(fresh):
        _pytest(tests)
    return bool(state["same"]) and state["calls"] > 0, state["calls"], bool(state["ran"])


def _pytest_with(fn, code, key: str, args: list[str], none_ok: bool = False) -> tuple[int, str]:
    """:func:`_pytest` with ``code`` in place of ``fn``'s (restored, and the caches cleared, after:
    e.g. jit_cache.code_version, computed with the mutant in place)."""
    from chaplygin_nd.ledger.mutation.cache_scope import clear

    original = fn.__code__
    fn.__code__ = code
    try:
        with _cache_root(key.startswith("runtime.jit_cache.")):
            return _pytest(args, none_ok=none_ok)
    finally:
        fn.__code__ = original
        clear()


def kill(fn, code, key: str, tests: tuple[str, ...], fork: bool = False) -> str | None:
    """Run ``tests`` (fastest first) with ``code`` in place of ``fn``'s, ``pytest -x``: the first
    failure's line, or None when every test passes. ``fork``: from the test session parked at
    ``fn``'s first call (:func:`_tests_from_fork`) when it answers."""
    answer = _tests_from_fork(fn, code, key, tests) if fork else None
    status, note = answer if answer is not None else _pytest_with(fn, code, key, ["-x", *tests])
    return note if status != 0 else None


#: A copy of the parked test session that has not answered this long is killed and the mutant
#: counted killed, as a row past its budget is (far above what the quick tests that reach one
#: function take; run in the worker, such a mutant holds it with no limit: seen with
#: ``search.multimodular.run``, a worker waiting on the tests' process pool for over ten minutes).
TESTS_GRACE = 600.0
#: This worker's parked test sessions ((function, tests) -> forkpoint.Parked); :func:`end_parked`.
_PARKED: dict = {}


def end_parked() -> None:
    """End this worker's parked test sessions."""
    for parked in _PARKED.values():
        parked.close()
    _PARKED.clear()


def _own_cache_folder() -> None:
    """In a copy of a parked test session: an empty ``$CHAPLYGIN_ND_CACHE`` of its own (what an
    earlier copy, under another mutant, wrote to the session's folder must not be read)."""
    from chaplygin_nd.cache import ENV

    parent = os.environ.get(WORK_ENV) or tempfile.gettempdir()
    os.environ[ENV] = tempfile.mkdtemp(prefix="mutant-", dir=parent)


def _tests_from_fork(fn, code, key: str, tests: tuple[str, ...]) -> tuple[int, str] | None:
    """``pytest -x tests`` with ``code`` in place of ``fn``'s, as :func:`_pytest_with` runs it,
    but from a session run unmutated up to ``fn``'s first call and parked there
    (:mod:`.forkpoint`): (status, first failure's line), or None (then run in the worker). Not for
    ``runtime.jit_cache`` (its tests need a fresh cache root per mutant)."""
    from chaplygin_nd.ledger.mutation import forkpoint
    from chaplygin_nd.ledger.mutation.cache_scope import clear

    if key.startswith("runtime.jit_cache."):
        return None
    if (key, tests) not in _PARKED:
        end_parked()
        clear()

        def session():
            with _cache_root(False):
                return _pytest(["-x", *tests])

        _PARKED[(key, tests)] = forkpoint.Parked(fn, session, on_fork=_own_cache_folder)
    answer = _PARKED[(key, tests)].run(code, budget_grace=TESTS_GRACE)
    if isinstance(answer, tuple) and len(answer) == 2 and isinstance(answer[0], int):
        return answer
    if isinstance(answer, tuple) and answer[:1] == (("timeout",),):  # in the worker it never ended
        return 1, f"the tests ran past {TESTS_GRACE:.0f} s with the mutant in place (stopped)"
    return None


def _runnable(test: str, files: tuple[str, ...]) -> str:
    """A test id pytest finds from the checkout: ids are relative to pytest's root folder, which
    for a file outside the checkout is not the checkout (its file part is then given whole)."""
    path, _, rest = test.partition("::")
    if (ROOT / path).exists():
        return test
    whole = next((f for f in files if str(f).endswith(path)), path)
    return f"{whole}::{rest}"


#: ``(function, its code, test files) -> the slow tests among them that call it``, per process:
#: found once (one instrumented unmutated run) for every mutant of the function.
_SLOW_REACHING: dict[tuple, tuple[str, ...]] = {}


def kill_slow(fn, code, key: str) -> str | None:
    """The last resort for a survivor: the tests marked ``slow`` of the files naming its module
    (:func:`mentioning`) that call ``fn`` (:func:`test_map` with ``slow``, once per process and
    function), ``pytest -x``, with ``code`` in place of ``fn``'s: the first failure's line, or None
    (every one passed, or none calls ``fn``). Not run per mutant otherwise (too long):
    ``family.wedge_n6.h2_residual``'s symbolic check is one. A slow test that does not call ``fn``
    is not run: a test that lists every mutant (it reads each function's source, and a mutant's
    code has none) failed under every mutant and killed them all; one that fails unmutated
    reaches nothing."""
    files = mentioning([key])
    if not files:
        return None
    memo = (key, fn.__code__, files)
    if memo not in _SLOW_REACHING:
        reach = test_map({key: fn}, files, slow=True)
        _SLOW_REACHING[memo] = tuple(_runnable(t, files) for t, _ in reach.get(key, ()))
    tests = _SLOW_REACHING[memo]
    if not tests:
        return None
    status, note = _pytest_with(fn, code, key, ["-x", *tests])
    return note if status != 0 else None


def evaluate(fn, code, key: str, tests: tuple[str, ...], record: dict, fork: bool = False) -> dict:
    """Decide one mutant (``code`` for ``fn``) against ``tests`` alone (the ids that reach it,
    fastest first); fills and returns ``record``. The caller clears the functools caches."""
    from chaplygin_nd.ledger.mutation.cache_scope import clear

    if not tests:
        record.update(outcome="survived", row="tests",
                      reason="no test calls this function (in this process; tests marked slow are "
                             "not run per mutant)"
                      + ("" if key.startswith("runtime.") else " and no ledger row reaches it"))
        return record
    note = kill(fn, code, key, tests, fork)
    if note is not None:
        record.update(outcome="killed", row="tests", reason=note)
        return record
    runtime = key.startswith("runtime.")
    found = re.search(r"\bline (\d+)\b", record.get("mutation", ""))
    same, calls, ran = equivalence(fn, code, list(tests), key.startswith("runtime.jit_cache."),
                                   _bitwise_equal if runtime else _exact_or_bitwise,
                                   int(found.group(1)) if found else None)
    clear()
    how = "bit-for-bit" if runtime else "exactly (SymPy) or bit-for-bit (arrays)"
    passed = f"the {len(tests)} tests that reach it passed"
    if same and ran:
        record.update(row="tests", outcome="equivalent", reason=(
            f"{passed} and the mutant's outputs are {how} the original's at all {calls} calls "
            "they make, the mutated line executed"))
    elif same:
        record.update(row="tests", outcome="survived", reason=(
            f"{passed}; equal outputs at all {calls} calls, but the mutated line never ran "
            "(a branch no test takes)"))
    else:
        record.update(row="tests", outcome="survived", reason=(
            f"{passed}; outputs differ or no call was made ({calls} calls)"))
    return record
