"""The caches kept warm between the mutants of one derivation (ledger/mutation/cache_scope.py):
only a cache whose every entry was computed, in a watched unmutated run, without calling the
mutated function (directly or through another cache) survives a clear; one that computed or lost
an entry since is emptied."""

from __future__ import annotations

import sys
import types

import pytest
from chaplygin_nd.ledger.mutation import cache_scope

SOURCE = '''
import functools

calls = []


def f(x):
    calls.append(("f", x))
    return x + 1


@functools.cache
def uses_f(x):
    calls.append(("uses_f", x))
    return f(x) * 2


@functools.cache
def free(x):
    calls.append(("free", x))
    return x * 3


@functools.cache
def through_cache(x):
    calls.append(("through_cache", x))
    return uses_f(x) + free(x)


@functools.cache
def own(x):
    return f(x)
'''


@pytest.fixture
def module():
    name = "chaplygin_nd.symbolic._cache_scope_example"
    mod = types.ModuleType(name)
    exec(compile(SOURCE, "<cache scope example>", "exec"), mod.__dict__)  # noqa: S102
    sys.modules[name] = mod
    try:
        yield mod
    finally:
        cache_scope.end()
        del sys.modules[name]


def _watched_run(mod, *, hit_first: bool = False):
    """What a recording does: clear, then an unmutated run with the function's calls reported."""
    cache_scope.clear()
    original = mod.f

    def reporting(x):
        cache_scope.called()
        return original(x)

    mod.f = reporting
    try:
        with cache_scope.watching():
            if hit_first:
                mod.uses_f(1)          # computed first: through_cache then only hits it
            mod.through_cache(1)
            mod.free(2)
    finally:
        mod.f = original


def test_only_caches_that_never_called_the_function_stay_warm(module):
    cache_scope.begin("example.f", module.f)
    _watched_run(module, hit_first=True)
    scope = cache_scope._SCOPE
    key = "chaplygin_nd.symbolic._cache_scope_example:{}".format
    assert scope.tainted == {key("uses_f"), key("through_cache")}  # the second through a hit
    cache_scope.clear()
    assert module.free.cache_info().currsize == 2                   # kept
    assert module.uses_f.cache_info().currsize == 0                 # emptied
    assert module.through_cache.cache_info().currsize == 0
    module.calls.clear()
    module.free(2)
    assert module.calls == []                                       # a hit: no recomputation


def test_an_entry_computed_outside_a_watched_run_is_emptied(module):
    cache_scope.begin("example.f", module.f)
    _watched_run(module)
    module.free(5)                       # e.g. under a mutant: the cache is dirty
    cache_scope.clear()
    assert module.free.cache_info().currsize == 0


def test_a_cache_emptied_and_filled_again_to_the_same_count_is_not_taken_for_clean(module):
    cache_scope.begin("example.f", module.f)
    _watched_run(module)
    misses = module.free.cache_info().misses
    module.free.cache_clear()            # by someone else (a test, the regeneration check)
    for x in range(misses):
        module.free(100 + x)             # as many misses as when it was clean
    assert module.free.cache_info().misses == misses
    cache_scope.clear()
    assert module.free.cache_info().currsize == 0


def test_the_function_s_own_cache_and_every_cache_without_a_scope_are_emptied(module):
    cache_scope.begin("example.own", module.own.__wrapped__)
    module.own(1)
    cache_scope.clear()
    assert module.own.cache_info().currsize == 0
    cache_scope.end()
    module.free(1)
    cache_scope.clear()                  # no scope: every cache, as reach.clear_caches
    assert module.free.cache_info().currsize == 0


def test_watching_restores_the_code_of_every_cached_function(module):
    cache_scope.begin("example.f", module.f)
    codes = {name: getattr(module, name).__wrapped__.__code__
             for name in ("uses_f", "free", "through_cache", "own")}
    _watched_run(module)
    assert {name: getattr(module, name).__wrapped__.__code__ for name in codes} == codes
    assert "__mutation_cache_scope__" not in vars(module)
