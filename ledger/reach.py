r"""Which printed formulas each ledger row reaches — the map behind ``make mutate``.

DESIGN rule: every printed object a row checks is one function of :mod:`symbolic.printed` and the
row calls it. This module *observes* that while rows run, without decorating anything:

* :func:`printed_functions` lists the public functions of ``symbolic/printed/section*.py``
  (name not starting with ``_``, defined in that module), keyed ``"section4.K"``.
* :class:`Recorder` swaps each function's ``__code__`` for a two-line trampoline that records the
  key and calls an untouched clone of the original. Because the code object of the function
  itself is replaced, every route is seen: ``printed.K(...)`` in a proof, a name imported with
  ``from ... import K``, and calls between printed functions (``Omega_inverse`` calling ``K``).
  The cost is one extra Python call per printed call (unlike ``sys.settrace``, which roughly
  doubled the time of a row). On exit the original code objects are put back.

The runner records, per row, the printed functions it reached (``Result.printed``); a run of the
whole ledger fails when a public printed function is reached by no row (:func:`unreached`).
``python -m chaplygin_nd.ledger.remap`` runs every row and writes ``ledger/reach.json`` (row -> functions and
function -> rows) atomically; ``make mutate`` uses the same map to pick the rows a mutant must
change, and the test suite uses it only to choose which rows to re-run live.

The same recorder watches the *derivations*: the public functions of ``symbolic/`` outside
``printed/`` and the code generator (:func:`derivation_functions`, keyed ``"reduction.reduced_n4.horizontal_blocks"``,
``"codegen.emit.axisym.stable_Delta"``). A function cached with ``functools.cache``/``lru_cache`` is seen
twice over: a miss runs its trampoline, a hit moves its ``cache_info()`` counters; a hit is also
credited with the watched functions the cached one called when it was computed (:data:`CALLEES`,
per process), so a row's record does not depend on which row filled the cache first. The derivations
whose result is emitted into ``generated/`` are found the same way, by building every kernel under
the recorder (:func:`emitted_derivations`); ``make verify`` fails when one of them is reached by no
row (:func:`unreached_emitted`) — a formula the simulator uses that no row compares with anything.
"""

from __future__ import annotations

import importlib
import json
from pathlib import Path
from types import CodeType, FunctionType

from chaplygin_nd.writing import write_atomic

PRINTED_MODULES = ("section2", "section3", "section4", "section5")
MAP_PATH = Path(__file__).resolve().parent / "reach.json"
_HOOK = "__printed_reach_hook__"


def printed_functions() -> dict[str, FunctionType]:
    """``{"sectionN.name": function}`` for every public function of ``symbolic/printed/``."""
    out: dict[str, FunctionType] = {}
    for name in PRINTED_MODULES:
        mod = importlib.import_module(f"chaplygin_nd.symbolic.printed.{name}")
        for attr, obj in sorted(vars(mod).items()):
            if (not attr.startswith("_") and isinstance(obj, FunctionType)
                    and obj.__module__ == mod.__name__):
                out[f"{name}.{attr}"] = obj
    return out


#: Modules of ``symbolic/`` that derive nothing, with the reason (their functions are not watched).
NOT_DERIVATIONS = {
    "codegen.kernels": "the code generator (prints expressions it is given)",
    "codegen.builders": "the code generator's heyoka builders (print expressions they are given)",
    "exact.mpmath_eval": "the tests' 50-digit evaluator of derived expressions (reached by tests)",
    "exact.points": "seeded exact points and the ledger seed (inputs of checks, not formulas)",
    "exact.identity": "the exact zero-test engines (decide identities, build no formula)",
    "exact.flint_engine": "the second exact engine (FLINT): decides zero tests, builds no formula",
    "exact.sympy_fraction": "the SymPy engine's reading of a residual into Q(x) (part of the engine)",
    "exact.tally": "which engine decided which zero test, and in what time (derives nothing)",
    "flint_model": "the second engine's own evaluation of the definitions at exact points",
    "exact.flint_matrix": "the second engine's matrix type: printed formulas evaluated in fmpq",
    "exact.counterexample": "renders a counterexample of the engine (text and LaTeX), derives nothing",
}


def _key(module: str) -> str:
    return module.removeprefix("chaplygin_nd.symbolic.")


def derivation_functions() -> dict[str, FunctionType]:
    """``{"module.name": function}`` for every public function of ``symbolic/`` that derives:
    outside ``printed/`` and :data:`NOT_DERIVATIONS`, and not an emitter's kernel-list builder
    (a function returning ``list[Kernel]`` assembles, it derives nothing); a cached function by
    its ``__wrapped__``."""
    import pkgutil

    import chaplygin_nd.symbolic as symbolic

    out: dict[str, FunctionType] = {}
    for info in sorted(pkgutil.walk_packages(symbolic.__path__, "chaplygin_nd.symbolic."),
                       key=lambda i: i.name):
        key = _key(info.name)
        if info.ispkg or key.startswith("printed.") or key in NOT_DERIVATIONS:
            continue
        mod = importlib.import_module(info.name)
        for attr, obj in sorted(vars(mod).items()):
            fn = getattr(obj, "__wrapped__", obj)
            if (not attr.startswith("_") and isinstance(fn, FunctionType)
                    and fn.__module__ == mod.__name__ and not fn.__code__.co_freevars
                    and fn.__annotations__.get("return") != "list[Kernel]"):
                out[f"{key}.{attr}"] = fn
    return out


def _caches(functions: dict[str, FunctionType]) -> dict[str, object]:
    """The ``functools`` cache wrappers of the watched functions (their hits are calls too)."""
    out = {}
    for key, fn in functions.items():
        wrapper = vars(importlib.import_module(fn.__module__)).get(fn.__name__)
        if wrapper is not fn and hasattr(wrapper, "cache_info"):
            out[key] = wrapper
    return out


def watched_functions() -> dict[str, FunctionType]:
    """Printed functions and derivations: what a ledger row's :class:`Recorder` watches."""
    return printed_functions() | derivation_functions()


def _calls(wrapper) -> int:
    info = wrapper.cache_info()
    return info.hits + info.misses


def _clone(fn: FunctionType) -> FunctionType:
    copy = FunctionType(fn.__code__, fn.__globals__, fn.__name__, fn.__defaults__, fn.__closure__)
    copy.__kwdefaults__ = fn.__kwdefaults__
    return copy


#: Per process: the watched functions a cached function called when it was computed (a miss),
#: so that a later cache hit is credited with them too (the row depends on them all the same).
CALLEES: dict[str, set[str]] = {}


def _trampoline(key: str, fn: FunctionType, cached: bool = False):
    call = (f"{_HOOK}({key!r}, args, kwargs)" if cached
            else f"{_HOOK}({key!r}, None, None)(*args, **kwargs)")
    source = f"def {fn.__name__}(*args, **kwargs):\n    return {call}\n"
    namespace: dict = {}
    exec(compile(source, f"<reach {key}>", "exec"), namespace)  # noqa: S102 - fixed template
    return namespace[fn.__name__].__code__


class Recorder:
    """Context manager recording which watched functions are called inside it (``.calls``;
    default: :func:`watched_functions`; split with :meth:`printed` and :meth:`derived`)."""

    def __init__(self, functions: dict[str, FunctionType] | None = None):
        self.functions = functions if functions is not None else watched_functions()
        self.calls: set[str] = set()
        self._saved: dict[str, CodeType] = {}
        self._caches = _caches(self.functions)
        self._counts: dict[str, int] = {}

    def printed(self) -> tuple[str, ...]:
        """The printed functions called (``"section4.K"``), sorted."""
        return tuple(sorted(c for c in self.calls if c.split(".")[0] in PRINTED_MODULES))

    def derived(self) -> tuple[str, ...]:
        """The derivations called (``"reduction.reduced_n4.horizontal_blocks"``), sorted."""
        return tuple(sorted(c for c in self.calls if c.split(".")[0] not in PRINTED_MODULES))

    def __enter__(self) -> Recorder:
        clones = {key: _clone(fn) for key, fn in self.functions.items()}
        self._counts = {key: _calls(w) for key, w in self._caches.items()}

        open_misses: list[set[str]] = []   # callees of the cached functions being computed

        def hook(key: str, args, kwargs):
            self.calls.add(key)
            for callees in open_misses:
                callees.add(key)
            if args is None:
                return clones[key]
            open_misses.append(set())
            try:
                return clones[key](*args, **kwargs)
            finally:
                CALLEES.setdefault(key, set()).update(open_misses.pop())

        for key, fn in self.functions.items():
            fn.__globals__[_HOOK] = hook
            self._saved[key] = fn.__code__
            fn.__code__ = _trampoline(key, fn, cached=key in self._caches)
        return self

    def __exit__(self, *exc) -> None:
        hits = {k for k, w in self._caches.items() if _calls(w) != self._counts[k]}
        for key in hits:
            self.calls |= {key} | CALLEES.get(key, set())
        for key, code in self._saved.items():
            fn = self.functions[key]
            fn.__code__ = code
            fn.__globals__.pop(_HOOK, None)
        self._saved.clear()


def unreached(printed_by_row: dict[str, list[str]]) -> list[str]:
    """Public printed functions reached by no row of ``printed_by_row`` (row -> functions)."""
    seen = {f for fs in printed_by_row.values() for f in fs}
    return sorted(set(printed_functions()) - seen)


def clear_caches(prefix: str = "chaplygin_nd.") -> None:
    """``cache_clear()`` every ``functools`` cache (private helpers too: a cached helper would hide
    the functions it calls) of the loaded modules whose name starts with ``prefix``, so the next
    calls are misses."""
    import sys

    for name, mod in list(sys.modules.items()):
        if name.startswith(prefix) and mod is not None:
            for obj in list(vars(mod).values()):
                if callable(getattr(obj, "cache_clear", None)) and hasattr(obj, "cache_info"):
                    obj.cache_clear()


def clear_derivation_caches() -> None:
    """Empty every ``functools`` cache of ``symbolic/`` (:func:`clear_caches`), every module of it
    imported first."""
    derivation_functions()  # imports every module of symbolic/
    clear_caches("chaplygin_nd.symbolic.")


def emitted_derivations() -> list[str]:
    """The derivations called while every kernel of ``generated/`` is built (the emitters listed
    in :data:`symbolic.codegen.kernels.MODULES`)."""
    from chaplygin_nd.symbolic.codegen.kernels import MODULES

    functions = derivation_functions()
    clear_derivation_caches()  # computed afresh: every callee is seen
    with Recorder(functions) as rec:
        for _stem, spec in MODULES:
            module, name = spec.split(":")
            getattr(importlib.import_module(module), name)()
    return sorted(rec.calls)


def regenerated_and_emitted() -> tuple[str, list[str]]:
    """``verify --check-generated``'s task beside the rows: generated/ regenerated into a temporary
    folder and compared byte for byte (:func:`symbolic.codegen.kernels.stale_report`; '' when up to
    date), with every derivation that regeneration calls recorded — the list of
    :func:`emitted_derivations` (the same emitters, from cleared caches) out of the same derivation
    of the kernels. ``(stale text, emitted derivations)``."""
    from chaplygin_nd.symbolic.codegen.kernels import KERNELS, stale_report

    functions = derivation_functions()
    clear_derivation_caches()
    KERNELS.clear()
    with Recorder(functions) as rec:
        text = stale_report()
    return text, sorted(rec.calls)


def unreached_emitted(derived_by_row: dict[str, list[str]],
                      emitted: list[str] | None = None) -> list[str]:
    """Emitted derivations (:func:`emitted_derivations`) reached by no row of ``derived_by_row``."""
    seen = {f for fs in derived_by_row.values() for f in fs}
    return sorted(set(emitted_derivations() if emitted is None else emitted) - seen)


def unreached_derivations(derived_by_row: dict[str, list[str]]) -> list[str]:
    """Derivation functions (emitted or not) reached by no row of ``derived_by_row``."""
    seen = {f for fs in derived_by_row.values() for f in fs}
    return sorted(set(derivation_functions()) - seen)


def rows_by_function(printed_by_row: dict[str, list[str]]) -> dict[str, list[str]]:
    """Invert the map: function -> the rows that reach it (ledger order kept)."""
    out: dict[str, list[str]] = {key: [] for key in printed_functions()}
    for row, fs in printed_by_row.items():
        for f in fs:
            out.setdefault(f, []).append(row)
    return out


def write_json_atomic(data: dict, path: Path) -> None:
    """Write ``data`` as JSON to ``path``, whole or not at all, with the mode a plain ``open()``
    gives (or the replaced file's): :func:`chaplygin_nd.writing.write_atomic`."""
    write_atomic(path, json.dumps(data, indent=1, sort_keys=True) + "\n")


def load(path: Path = MAP_PATH) -> tuple[dict[str, list[str]], dict[str, float]]:
    """The stored map (row -> functions, row -> seconds), written by ``python -m chaplygin_nd.ledger.remap``."""
    data = json.loads(path.read_text(encoding="utf-8"))
    return data["rows"], data.get("seconds", {})


def kept_seconds(measured: dict[str, float], path: Path = MAP_PATH) -> dict[str, float]:
    """Each row's stored seconds where the map has them, else ``measured``: what a run that maps
    reach with a warm cache (``make mutate``'s baseline) writes back. The stored seconds were taken
    cold (:mod:`ledger.remap`) and order a cold ``verify --jobs``; warm, the evidence rows take
    0.2-0.8 s instead of 30-130 s, and ``make mutate`` had undone the order."""
    stored = load(path)[1] if path.is_file() else {}
    return {row: stored.get(row, t) for row, t in measured.items()}


def load_derived(path: Path = MAP_PATH) -> tuple[dict[str, list[str]], list[str]]:
    """The stored derivation map: (row -> derivations it calls, the emitted derivations)."""
    data = json.loads(path.read_text(encoding="utf-8"))
    return data.get("derived", {}), data.get("emitted", [])


def cover(printed_by_row: dict[str, list[str]], seconds: dict[str, float]) -> list[str]:
    """A small set of rows reaching every function the map reaches (greedy: most new functions
    per second first) — what a test re-runs live to show every printed function is reached."""
    todo = {f for fs in printed_by_row.values() for f in fs}
    chosen: list[str] = []
    while todo:
        best = max(printed_by_row, key=lambda r: (len(todo & set(printed_by_row[r]))
                                                  / (0.2 + seconds.get(r, 1.0)), r))
        gain = todo & set(printed_by_row[best])
        if not gain:
            break
        chosen.append(best)
        todo -= gain
    return chosen


def save(printed_by_row: dict[str, list[str]], seconds: dict[str, float] | None = None,
         path: Path = MAP_PATH, derived_by_row: dict[str, list[str]] | None = None,
         emitted: list[str] | None = None) -> None:
    """Write the map (and each row's seconds, to choose cheap rows) atomically; the derivation
    map and the emitted derivations are kept from the stored file when not given. Every list is
    sorted (the keys are, by the JSON writer): the same map is the same file, whichever order the
    rows were run or read in."""
    stored_derived, stored_emitted = load_derived(path) if path.is_file() else ({}, [])
    derived_by_row = stored_derived if derived_by_row is None else derived_by_row
    printed_by_row = {r: sorted(fs) for r, fs in printed_by_row.items()}
    derived_by_row = {r: sorted(fs) for r, fs in derived_by_row.items()}
    write_json_atomic({"rows": printed_by_row,
                       "functions": {f: sorted(rs) for f, rs in rows_by_function(printed_by_row).items()},
                       "seconds": {r: round(t, 2) for r, t in (seconds or {}).items()},
                       "derived": derived_by_row,
                       "derivations": {f: sorted(r for r, fs in derived_by_row.items() if f in fs)
                                       for f in derivation_functions()},
                       "emitted": sorted(stored_emitted if emitted is None else emitted)}, path)
