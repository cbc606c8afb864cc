r"""Which ``functools`` caches a mutant of one function can reach: those are emptied around each
mutant, the others stay warm from one mutant to the next.

Every cache is emptied before and after each mutant unless a scope is open (:func:`begin`): a
cached unmutated value would hide the mutant, a cached mutated one would leak into the next; and
a row then re-derives, for every mutant, everything it uses (the inverse of L_gamma, the
invariants, ...), most of which the mutated function has no part in.

While a worker decides the mutants of one derivation ``f`` (:func:`begin`: every cache is emptied
once, then a cache entry is kept only when it is known not to depend on ``f``):

* **tainted** caches: a cached function whose computation (a cache miss) called ``f``, or hit a
  tainted cache, while an unmutated run was watched (:func:`watching`: each miss of a cached
  function of ``symbolic/`` goes through a trampoline that notes it; ``f``'s calls are reported by
  :func:`called`). A tainted cache is emptied at every :func:`clear`; ``f``'s own cache is tainted
  from the start.
* **dirty** caches: any cache that computed an entry (its miss count moved) since it was last
  known clean — during a mutant's run, a replay, a test run: a value computed there may come from
  the mutant. Emptied at every :func:`clear`.
* **clean** caches: the others. Their entries were all computed in watched unmutated runs without
  calling ``f``, directly or through another cache, so they are the same for every mutant of
  ``f`` (a cached function's value depends on its arguments and on what it calls; module-level
  state that is not a ``functools`` cache was never cleared between mutants). Kept.

Caches outside ``symbolic/`` (the runtime, the simulator, the ledger) are emptied at every
:func:`clear`, as before. With no scope open (the printed formulas, the runtime target, the test
suite) :func:`clear` empties every cache (:func:`chaplygin_nd.ledger.reach.clear_caches`).
"""

from __future__ import annotations

import sys
from types import FunctionType
from typing import Any

from chaplygin_nd.ledger.reach import clear_caches

#: The caches whose entries are watched (the derivations').
SCOPED_PREFIX = "chaplygin_nd.symbolic."
_HOOK = "__mutation_cache_scope__"


class _Scope:
    """The state of one worker's scope: the mutated function, the tainted caches, the state
    (:func:`_state`) in which each cache was last known clean, and the misses being computed
    while watching."""

    def __init__(self, function: str, fn: FunctionType):
        self.function = function
        self.caches = _caches()
        self.own = next((k for k, w in self.caches.items() if w.__wrapped__ is fn), None)
        self.tainted: set[str] = {self.own} if self.own else set()
        self.clean: dict[str, tuple[int, int]] = {k: _state(w) for k, w in self.caches.items()}
        self.open: list[list] = []  # [key, tainted?, hits of the tainted caches at its start]


#: ``id(wrapper) -> how many times it was emptied`` (its ``cache_clear`` counts, whoever calls it:
#: a cache emptied and filled again to the same miss count is not the cache that was clean).
_EMPTIED: dict[int, int] = {}


def _counting(wrapper) -> None:
    if id(wrapper) in _EMPTIED:
        return
    _EMPTIED[id(wrapper)] = 0
    empty = wrapper.cache_clear

    def cache_clear() -> None:
        _EMPTIED[id(wrapper)] += 1
        empty()

    wrapper.cache_clear = cache_clear


def _state(wrapper) -> tuple[int, int]:
    """(times emptied, misses since): it changes whenever the cache computes or loses an entry."""
    return _EMPTIED[id(wrapper)], wrapper.cache_info().misses


_SCOPE: _Scope | None = None


def _caches() -> dict[str, Any]:
    """``{"module:name": wrapper}`` for every ``functools`` cache of the loaded modules of
    ``symbolic/`` whose wrapped function is a plain function (the others are always emptied),
    each once (a cache imported into another module is the same cache); their ``cache_clear`` is
    made to count (:data:`_EMPTIED`)."""
    out: dict[str, Any] = {}
    seen: set[int] = set()
    for name, mod in sorted(sys.modules.items()):
        if not name.startswith(SCOPED_PREFIX) or mod is None:
            continue
        for attr, obj in sorted(vars(mod).items()):
            if (id(obj) not in seen and callable(getattr(obj, "cache_clear", None))
                    and hasattr(obj, "cache_info")
                    and isinstance(getattr(obj, "__wrapped__", None), FunctionType)
                    and id(obj.__wrapped__) not in seen
                    and not obj.__wrapped__.__code__.co_freevars):
                seen |= {id(obj), id(obj.__wrapped__)}
                _counting(obj)
                out[f"{name}:{attr}"] = obj
    return out


def begin(function: str, fn: FunctionType) -> None:
    """Open the scope of ``fn`` (key ``function``) in this worker: every cache is emptied, none is
    tainted but ``fn``'s own. Nothing when the scope of ``fn`` is already open."""
    global _SCOPE
    if _SCOPE is not None and _SCOPE.function == function:
        return
    clear_caches()
    _SCOPE = _Scope(function, fn)


def end() -> None:
    """Close the scope (every cache emptied): from here every :func:`clear` empties every cache."""
    global _SCOPE
    if _SCOPE is not None:
        _SCOPE = None
        clear_caches()


def clear() -> None:
    """Empty the caches a mutant of the scope's function can reach (tainted and dirty; all of
    them when no scope is open), keep the clean ones."""
    scope = _SCOPE
    if scope is None:
        clear_caches()
        return
    kept = set()
    for key, wrapper in scope.caches.items():
        if key not in scope.tainted and _state(wrapper) == scope.clean[key]:
            kept.add(id(wrapper))
            continue
        wrapper.cache_clear()
        scope.clean[key] = _state(wrapper)
    for name, mod in list(sys.modules.items()):  # every other cache, as clear_caches does
        if name.startswith("chaplygin_nd.") and mod is not None:
            for obj in list(vars(mod).values()):
                if (id(obj) not in kept and callable(getattr(obj, "cache_clear", None))
                        and hasattr(obj, "cache_info")):
                    obj.cache_clear()


def called() -> None:
    """The scope's function was called (in a watched unmutated run): every cached computation
    open now depends on it."""
    if _SCOPE is not None:
        for frame in _SCOPE.open:
            frame[1] = True


class watching:
    """Within the block (an unmutated run: the recording of a check, after :func:`clear`), every
    miss of a scoped cache is watched for calls of the function (:func:`called`) and for hits of
    tainted caches; on exit the caches it tainted are tainted, and every other cache is clean in
    the state the run left it."""

    def __init__(self):
        self._saved: dict[str, Any] = {}

    def __enter__(self) -> watching:
        scope = _SCOPE
        if scope is None:
            return self
        for key, wrapper in scope.caches.items():
            if key == scope.own:  # the function's own cache: tainted already, its code is the
                continue          # mutation tools' to replace
            inner = wrapper.__wrapped__
            clone = FunctionType(inner.__code__, inner.__globals__, inner.__name__,
                                 inner.__defaults__, inner.__closure__)
            clone.__kwdefaults__ = inner.__kwdefaults__
            hooks = inner.__globals__.setdefault(_HOOK, {"miss": _miss})
            hooks[key] = (key, clone)
            self._saved[key] = inner.__code__
            inner.__code__ = _trampoline(inner, key)
        return self

    def __exit__(self, *exc) -> None:
        scope = _SCOPE
        if scope is None:
            return
        for key, code in self._saved.items():
            inner = scope.caches[key].__wrapped__
            inner.__code__ = code
            inner.__globals__.pop(_HOOK, None)
        self._saved.clear()
        scope.open.clear()
        for key, wrapper in scope.caches.items():
            if key not in scope.tainted:
                scope.clean[key] = _state(wrapper)


def _trampoline(inner: FunctionType, key: str):
    source = (f"def {inner.__name__}(*args, **kwargs):\n"
              f"    return {_HOOK}['miss']({_HOOK}[{key!r}], args, kwargs)\n")
    namespace: dict = {}
    exec(compile(source, f"<cache scope {inner.__name__}>", "exec"), namespace)  # noqa: S102
    return namespace[inner.__name__].__code__


def _miss(entry, args, kwargs):
    """One cache miss while watching: the computation, noted tainted when it called the function
    or hit a tainted cache; a tainted computation taints every computation open around it."""
    key, clone = entry
    scope = _SCOPE
    if scope is None:
        return clone(*args, **kwargs)
    hits = {k: scope.caches[k].cache_info().hits for k in scope.tainted}
    frame = [key, False, hits]
    scope.open.append(frame)
    try:
        return clone(*args, **kwargs)
    finally:
        scope.open.pop()
        if frame[1] or any(scope.caches[k].cache_info().hits != h for k, h in hits.items()):
            scope.tainted.add(key)
            for outer in scope.open:
                outer[1] = True
