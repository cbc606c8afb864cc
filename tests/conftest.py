"""Shared pytest setup: mpmath precision is reset before every test (mpmath's own habit), so a
test may raise ``mp.dps`` freely without leaking it into the next one; our cache of compiled
heyoka integrators (runtime/jit_cache.py) is one temporary folder per test session, shared by the
xdist workers (each system compiles once per run; the tests never write into the user's
chaplygin-nd cache). heyoka's own
cache of compiled code (~/.cache/heyoka, heyoka's default) is left as the user configured it;
with it off, the heyoka tests add about 15 s of JIT to a run on 2 cores. The wheel that
tests/test_wheel.py and tests/test_site_packages.py run is built once per pytest process."""

import os

# before any test module imports SymPy: the same ground types as the package (chaplygin_nd/__init__)
os.environ.setdefault("SYMPY_GROUND_TYPES", "gmpy")

# before any test module imports matplotlib: its configuration and font cache go to the project's
# cache folder, as the commands place them, not to ~/.config/matplotlib or ~/.cache/matplotlib
from chaplygin_nd.cache import place_matplotlib_cache  # noqa: E402

place_matplotlib_cache()

import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import mpmath  # noqa: E402
import pytest  # noqa: E402


def shared_session_folder(config) -> Path | None:
    """A private folder shared by every pytest-xdist worker of this run (None in a run without
    workers): the controller's base temporary folder, the parent of each worker's own, removed
    with it after a green run."""
    if not hasattr(config, "workerinput"):
        return None
    folder = config._tmp_path_factory.getbasetemp().parent / "shared"
    folder.mkdir(mode=0o700, exist_ok=True)
    return folder


def derived_once(config, name: str, derive):
    """``derive()``, computed by the first worker of the run that asks and unpickled by the
    others (a lock in :func:`shared_session_folder` orders them; without workers, computed here).
    Only for values of this run's own code: the folder lives and dies with the run."""
    import fcntl
    import pickle

    folder = shared_session_folder(config)
    if folder is None:
        return derive()
    path = folder / f"{name}.pickle"
    with open(folder / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if path.exists():
            return pickle.loads(path.read_bytes())
        value = derive()
        part = folder / f"{name}.part"
        part.write_bytes(pickle.dumps(value))
        os.replace(part, path)
        return value


@pytest.fixture(scope="session", autouse=True)
def _session_heyoka_cache(tmp_path_factory, request):
    """The project cache (compiled integrators, heyoka's object code, evidence) is one temporary
    folder for the run, shared by the xdist workers (each system compiles once per run, not once
    per worker: the cache's writes are atomic and its entries keyed, as for parallel rows)."""
    from chaplygin_nd.runtime import jit_cache as heyoka_cache

    old = os.environ.get(heyoka_cache.ENV)
    shared = shared_session_folder(request.config)
    if shared is not None:
        folder = shared / "project-cache"
        folder.mkdir(mode=0o700, exist_ok=True)
    else:
        folder = tmp_path_factory.mktemp("heyoka-cache")
    os.environ[heyoka_cache.ENV] = str(folder)
    heyoka_cache.forget_memory()
    yield
    heyoka_cache.forget_memory()
    if old is None:
        os.environ.pop(heyoka_cache.ENV, None)
    else:
        os.environ[heyoka_cache.ENV] = old


@pytest.fixture(scope="session", autouse=True)
def _session_temp_dir(tmp_path_factory):
    """``TMPDIR`` (and :mod:`tempfile`'s cached choice) is one folder of pytest's base temporary
    folder for the whole session, in this process and in every process the tests start: what
    multiprocessing (``pymp-*``), Dask (``dask-scratch-space``), a mutation worker or a killed
    command leaves there goes with pytest's own folder (removed after a green run:
    ``tmp_path_retention_policy`` in pyproject.toml), never into the user's ``/tmp``."""
    import tempfile

    folder = str(tmp_path_factory.mktemp("tmp"))
    saved_env, saved_cached = os.environ.get("TMPDIR"), tempfile.tempdir
    os.environ["TMPDIR"], tempfile.tempdir = folder, folder
    yield
    # multiprocessing removes its pymp-* folder at interpreter exit, after pytest has removed this
    # one (a FileNotFoundError traceback at exit): run its own finalizer for that folder now
    from multiprocessing import util as mp_util

    for finalizer in list(getattr(mp_util, "_finalizer_registry", {}).values()):
        if getattr(finalizer, "_callback", None) is getattr(mp_util, "_remove_temp_dir", None):
            finalizer()
    tempfile.tempdir = saved_cached
    if saved_env is None:
        os.environ.pop("TMPDIR", None)
    else:
        os.environ["TMPDIR"] = saved_env


@pytest.hookimpl(trylast=True)
def pytest_sessionfinish(session):
    """After a green run pytest has removed its base folder (``tmp_path_retention_policy``); its
    per-user parent ``pytest-of-<user>`` goes too when nothing else is left in it."""
    factory = getattr(session.config, "_tmp_path_factory", None)
    basetemp = getattr(factory, "_basetemp", None)
    if hasattr(session.config, "workerinput") or basetemp is None or basetemp.exists():
        return
    if basetemp.parent.name.startswith("pytest-of-"):
        try:
            basetemp.parent.rmdir()  # only if empty: another run's folders stay
        except OSError:
            pass


@pytest.fixture(scope="session")
def installed(tmp_path_factory):
    """(wheel, install folder, scratch folder): built and installed once per pytest process (used by
    tests/test_wheel.py and tests/test_site_packages.py)."""
    base = tmp_path_factory.mktemp("wheel")
    dist, target, source = base / "dist", base / "site", base / "source"
    # build from a copy: setuptools writes build/ and *.egg-info into the source folder
    root = Path(__file__).resolve().parent.parent
    shutil.copytree(root, source, symlinks=True, ignore=shutil.ignore_patterns(
        ".venv", ".git", "build", "*.egg-info", "out", "__pycache__", ".pytest_cache",
        ".hypothesis"))
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-v", "-w", str(dist),
                        str(source)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    (base / "build.log").write_text(r.stdout + r.stderr)
    (wheel,) = dist.glob("chaplygin_nd-*.whl")
    r = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target",
                        str(target), str(wheel)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return wheel, target, base


@pytest.fixture(autouse=True)
def _reset_mpmath_precision():
    mpmath.mp.dps = 15
    yield
    mpmath.mp.dps = 15


@pytest.fixture(autouse=True)
def _restore_signal_handlers():
    """A test that runs the program in-process leaves this process's handlers as it found them
    (cli.main does so itself; the program's entry takes them; a scene's own
    handlers may not): else
    a Ctrl-C of the test run, or a SIGTERM of a mutation run whose tests run in-process, was
    ignored for the rest of the session (seen: make mutate-derivations ran to the end after a
    SIGTERM)."""
    import signal

    from chaplygin_nd import signals

    saved = {sig: signal.getsignal(sig) for sig in (signal.SIGINT, signal.SIGTERM)}
    yield
    for sig, handler in saved.items():
        if signal.getsignal(sig) is not handler:
            signal.signal(sig, handler)
    signals.forget_received()


def pytest_terminal_summary(terminalreporter):
    """Report the worst measured error (ulps of the condition scale) per kernel over the hard
    cases. Each hard-case test asserts its own bound; this only summarises what they measured."""
    import sys

    rows = []
    for name, module in sorted(sys.modules.items()):
        if name.rsplit(".", 1)[-1] not in ("test_kernels_axisym", "test_kernels_fourd"):
            continue
        for key, value in getattr(module, "MEASURED", {}).items():
            worst = value if isinstance(value, list) else list(value.values())
            label = " ".join(str(k) for k in (key if isinstance(key, tuple) else (key,)))
            rows.append(f"{label:40s} worst {max(worst):.2f} ulps")
    if rows:
        terminalreporter.section("kernel errors over the hard cases (measured)")
        for row in rows:
            terminalreporter.write_line(row)


#: the modules of `make test` whose tests take longest (seconds of a run on 2 cores):
#: run first, so that pytest-xdist's work stealing (make test: --dist worksteal) shares out the
#: many short tests after them instead of waiting at the end for one long test
LONGEST_FIRST = ("test_simulate_accuracy", "test_mutate", "test_section4_mutations",
                 "test_codegen", "test_evidence_cache", "test_orphans", "test_ledger_cli",
                 "test_report", "test_site_packages", "test_wheel")


def pytest_collection_modifyitems(items):
    """Whole modules of :data:`LONGEST_FIRST` move to the front, in that order (the order within
    a module, and of the other modules, is kept): a schedule, never a selection."""
    def rank(item) -> int:
        stem = item.path.stem
        return LONGEST_FIRST.index(stem) if stem in LONGEST_FIRST else len(LONGEST_FIRST)

    items[:] = sorted(items, key=rank)  # sorted() is stable
