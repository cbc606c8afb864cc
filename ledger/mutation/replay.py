r"""Record a derivation's calls in a ledger row once, then replay them on each mutant.

A mutant of a derivation ``f`` can change a ledger row only through the values ``f`` returns
there (and what it does to its arguments). :func:`record` runs one row unmutated, with every call
of ``f`` recorded: its arguments before the call, its value, and its arguments after it.
:func:`replay` calls a mutant on the recorded arguments. When the mutant returns exactly the
recorded value (and leaves the arguments as the original did) at **every** recorded call, the row
run with the mutant makes the same calls and sees the same values as the unmutated one, so its
verdict, counterexample and parts are the baseline's — the row cannot kill that mutant and need
not be run with it. When some value differs, the row is run with the mutant, as before.

The argument needs ``f`` to be a function of its arguments alone. Two guards, both conservative
(a function they refuse is simply run against its rows as before):

* **syntactic** (:func:`impure`): the code of ``f`` writes no global and names nothing that acts
  outside its arguments (``print``, ``open``, ``write*``, ``mkdir``, ``unlink``, ``os.environ``,
  ``seed``); the module-level lists, dicts and sets it reads must be left as they were by every
  call, recorded or replayed (:func:`mutable_globals`);
* **dynamic**: right after recording, the *original* code is replayed on the recorded arguments
  and must give back every recorded value; a function that depends on state the row changes, on a
  clock or on an unseeded generator fails this and is not replayed.

A recording is abandoned (``None``) past :data:`MAX_CALLS` calls or when an argument or value
cannot be copied. Values are compared as a row would see them (:func:`identical`: same type and structure, floats and
arrays bit for bit). While replaying, a tracer on the mutant's own code notes whether the mutated
expression ran (:class:`LineWatch`: its line and column): equal values on a branch no call takes
prove nothing.
"""

from __future__ import annotations

import contextlib
import copy
import dataclasses
import dis
import sys
from dataclasses import dataclass, field
from types import CodeType, FunctionType
from typing import Any

#: Past this many calls of ``f`` in one row, the row is run with the mutant instead of replayed.
MAX_CALLS = 20_000
#: Names whose use in ``f`` means it may act outside its arguments and value.
_EFFECTS = frozenset({"print", "open", "input", "exec", "eval", "setattr", "delattr", "globals",
                      "environ", "write", "write_text", "write_bytes", "writelines", "mkdir",
                      "unlink", "rmdir", "rename", "replace_file", "write_json_atomic", "seed",
                      "putenv", "system", "popen"})
_MUTABLE = (dict, list, set, bytearray)
_IMMUTABLE = (int, float, complex, str, bytes, bool, type(None), frozenset)


@dataclass
class Recording:
    """The calls of one function in one row: ``(args, kwargs, value, args_after, kwargs_after)``
    (copies; a value that raised is ``_Raised``)."""

    calls: list = field(default_factory=list)
    problem: str = ""  # why it cannot be replayed ("" when it can)
    seconds: float = 0.0  # the time of the recorded run


@dataclass(frozen=True)
class _Raised:
    kind: type
    text: str


def _code_objects(code: CodeType) -> list[CodeType]:
    out = [code]
    for const in code.co_consts:
        if isinstance(const, CodeType):
            out += _code_objects(const)
    return out


def impure(fn: FunctionType) -> str:
    """Why ``fn`` may act beyond its arguments and value (a name of :data:`_EFFECTS`, a global
    store), or "" when its code shows none. (The mutable module-level containers it reads are
    watched call by call instead: :func:`mutable_globals`.)"""
    for code in _code_objects(fn.__code__):
        for ins in dis.get_instructions(code):
            if ins.opname in ("STORE_GLOBAL", "DELETE_GLOBAL"):
                return f"writes the global {ins.argval}"
            if ins.opname in ("LOAD_GLOBAL", "LOAD_NAME", "LOAD_ATTR", "LOAD_METHOD"):
                name = ins.argval if isinstance(ins.argval, str) else str(ins.argval)
                if name in _EFFECTS:
                    return f"uses {name}"
    return ""


def mutable_globals(fn: FunctionType) -> tuple[str, ...]:
    """The module-level lists, dicts, sets and bytearrays ``fn``'s code names: each call (recorded
    or replayed) must leave them as it found them."""
    names = {ins.argval for code in _code_objects(fn.__code__) for ins in dis.get_instructions(code)
             if ins.opname == "LOAD_GLOBAL"}
    return tuple(sorted(n for n in names if isinstance(fn.__globals__.get(n), _MUTABLE)))


def _globals_state(fn: FunctionType, names: tuple[str, ...]) -> tuple:
    return tuple(_snapshot(fn.__globals__[n]) for n in names)


def _frozen(value: Any) -> bool:
    """Whether nothing can change ``value`` in place (scalars, strings, SymPy expressions and
    immutable matrices, and tuples of those)."""
    import sympy as sp

    if isinstance(value, _IMMUTABLE) or (isinstance(value, sp.Basic)):
        return True
    return isinstance(value, tuple) and all(_frozen(v) for v in value)


def _snapshot(value: Any) -> Any:
    """A copy of ``value`` that later changes to the original cannot reach (``value`` itself
    when nothing can change it)."""
    from sympy.polys.rings import PolyElement

    if _frozen(value):
        return value
    if type(value) is tuple:
        return tuple(_snapshot(v) for v in value)
    if type(value) is list:
        return [_snapshot(v) for v in value]
    if type(value) is dict:
        return {k: _snapshot(v) for k, v in value.items()}
    if isinstance(value, PolyElement):  # a dict of its ring; deepcopy fails on the ring
        return value.copy()
    return copy.deepcopy(value)


def attributes(x) -> dict | None:
    """The attributes of an object whose class has no equality of its own (``==`` would be
    identity): its ``__dict__`` and its ``__slots__``, by name; None for any other object. A
    small value class with ``__slots__`` (wedge_integrals' dual numbers) compared by identity made
    every value differ)."""
    if type(x).__eq__ is not object.__eq__:
        return None
    slots: list[str] = []
    for cls in type(x).__mro__:
        names = cls.__dict__.get("__slots__", ())
        slots += [names] if isinstance(names, str) else [s for s in names
                                                         if s not in ("__dict__", "__weakref__")]
    if not slots and not hasattr(x, "__dict__"):
        return None
    out = {name: getattr(x, name) for name in slots if hasattr(x, name)}
    out.update(getattr(x, "__dict__", {}))
    return out


def identical(x, y) -> bool:
    """Whether a row could tell ``x`` from ``y``: same type and structure (SymPy's structural
    ``==``, not mathematical equality: ``x*(x+1)`` and ``x**2 + x`` differ in what a row prints),
    floats and arrays bit for bit, containers element by element in their iteration order,
    dataclasses field by field over the fields they compare (``field(compare=False)``, e.g. the
    seconds a computation took, is no part of the value)."""
    import numpy as np
    import sympy as sp

    if type(x) is not type(y):
        return False
    if isinstance(x, (tuple, list)):
        return len(x) == len(y) and all(identical(u, v) for u, v in zip(x, y))
    if isinstance(x, (set, frozenset)):
        return len(x) == len(y) and all(identical(u, v) for u, v in zip(x, y))
    if isinstance(x, dict):
        return (len(x) == len(y) and all(identical(a, b) for a, b in zip(x, y))
                and all(identical(x[k], y[k]) for k in x))
    if isinstance(x, (float, complex, np.ndarray, np.generic)):
        xa, ya = np.asarray(x), np.asarray(y)
        if xa.dtype == object:
            return xa.shape == ya.shape and all(identical(u, v) for u, v in zip(xa.flat, ya.flat))
        return xa.shape == ya.shape and xa.dtype == ya.dtype and xa.tobytes() == ya.tobytes()
    if isinstance(x, sp.MatrixBase) and not isinstance(x, sp.Basic):
        return x.shape == y.shape and all(identical(u, v) for u, v in zip(x, y))
    if isinstance(x, np.random.Generator):  # its state is what a later draw depends on
        return identical(x.bit_generator.state, y.bit_generator.state)
    if dataclasses.is_dataclass(x):  # field by field, the fields it compares (its own ``==``
        return all(identical(getattr(x, f.name), getattr(y, f.name))  # cannot compare arrays;
                   for f in dataclasses.fields(x) if f.compare)      # compare=False: a time taken)
    if (own := attributes(x)) is not None:  # no equality of its own: attribute by attribute
        return identical(own, attributes(y))
    try:
        return bool(x == y)  # SymPy: structural; FLINT, dataclasses, _Raised: exact
    except Exception:  # noqa: BLE001 - cannot be compared: treated as different
        return False


def _call(fn: FunctionType, args, kwargs):
    try:
        return fn(*args, **kwargs)
    except Exception as err:  # noqa: BLE001 - a raise is a value the row may catch
        return _Raised(type(err), str(err))


def _clone(fn: FunctionType, code: CodeType) -> FunctionType:
    out = FunctionType(code, fn.__globals__, fn.__name__, fn.__defaults__, fn.__closure__)
    out.__kwdefaults__ = fn.__kwdefaults__
    return out


@contextlib.contextmanager
def calls_through(fn: FunctionType, hook):
    """Within the block every call of ``fn`` — from anywhere: its code object itself is replaced
    by a two-line trampoline — goes to ``hook(*args, **kwargs)``; ``fn``'s code is restored on
    exit. The one mechanism of the mutation tools' recorders and comparers."""
    name = f"__mutate_hook_{fn.__name__}__"  # one per function: several may be hooked at once
    src = f"def {fn.__name__}(*args, **kwargs):\n    return {name}(*args, **kwargs)\n"
    ns: dict = {}
    exec(compile(src, "<mutate hook>", "exec"), ns)  # noqa: S102 - fixed template
    original = fn.__code__
    fn.__globals__[name] = hook
    fn.__code__ = ns[fn.__name__].__code__
    try:
        yield
    finally:
        fn.__code__ = original
        fn.__globals__.pop(name, None)


def recorder(fn: FunctionType, rec: Recording, on_call=lambda: None):
    """The hook (for :func:`calls_through`) that appends each call of ``fn`` to ``rec``: its
    arguments before, its value (or raise) and its arguments after, copied; ``rec.problem`` says
    why the calls cannot be replayed (an argument or value that cannot be copied, a module-level
    container changed, more than :data:`MAX_CALLS` calls). ``on_call()`` first, at every call."""
    orig = _clone(fn, fn.__code__)
    names = mutable_globals(fn)

    def hook(*args, **kwargs):
        on_call()
        if rec.problem:
            return orig(*args, **kwargs)
        try:
            before = (_snapshot(args), _snapshot(kwargs))
            state = _globals_state(fn, names)
        except Exception as err:  # noqa: BLE001 - e.g. an object deepcopy cannot copy
            rec.problem = f"an argument cannot be copied ({type(err).__name__})"
            return orig(*args, **kwargs)
        try:
            value = orig(*args, **kwargs)
        except Exception as err:
            rec.calls.append((*before, _Raised(type(err), str(err)), _snapshot(args),
                              _snapshot(kwargs)))
            raise
        finally:
            if not identical(state, _globals_state(fn, names)):
                rec.problem = "a call changes a module-level container"
        try:
            rec.calls.append((*before, _snapshot(value), _snapshot(args), _snapshot(kwargs)))
        except Exception as err:  # noqa: BLE001
            rec.problem = f"a value cannot be copied ({type(err).__name__})"
        if len(rec.calls) > MAX_CALLS:
            rec.problem, rec.calls = f"more than {MAX_CALLS} calls", []
        return value

    return hook


def record(fn: FunctionType, run) -> Recording:
    """Run ``run()`` (one ledger row, unmutated) with every call of ``fn`` recorded; then replay
    the original on the records (the dynamic guard). ``fn``'s code is restored on return. The
    run is watched for the caches that depend on ``fn`` (:mod:`.cache_scope`, when a scope is
    open): the others keep what it computed."""
    from chaplygin_nd.ledger.mutation import cache_scope

    rec = Recording()
    why = impure(fn)
    if why:
        rec.problem = why
        return rec
    original = fn.__code__
    hook = recorder(fn, rec, cache_scope.called)
    try:
        with calls_through(fn, hook):
            cache_scope.clear()
            with cache_scope.watching():
                run()
    finally:
        cache_scope.clear()
    if not rec.problem and not rec.calls:
        rec.problem = "not called"
    if not rec.problem:
        same, _ran = replay(fn, original, rec)
        cache_scope.clear()
        if not same:
            rec.problem = "the original itself gives other values on replay (depends on state)"
    if rec.problem:
        rec.calls = []
    return rec


class LineWatch:
    """Notes whether the mutated code of ``code`` (a mutant) runs while watching (``with
    watch:``; nested code objects too). ``where``: ``(line, col)`` of the mutated expression
    (:func:`mutated_position`) — an instruction the compiler placed there must run (a branch of a
    one-line conditional that no call takes does not count); when the compiler placed none there
    (e.g. a constant folded into its parent), or ``where`` is a line number: any instruction of
    that line. ``None``: counted as run."""

    def __init__(self, code: CodeType, where):
        line, col = where if isinstance(where, tuple) else (where, None)
        self.line, self.ran = line, line is None
        self._codes = set(_code_objects(code))
        self._saved: list = []  # a stack: the watched code may call itself through the watch
        self._at: dict[CodeType, set[int]] | None = None
        if col is not None:
            at = {c: {2 * i for i, pos in enumerate(c.co_positions())
                      if pos[0] == line and pos[2] == col} for c in self._codes}
            self._at = at if any(at.values()) else None

    def _local(self, frame, event, arg):
        if self._at is None:
            if event == "line" and frame.f_lineno == self.line:
                self.ran = True
        elif event == "opcode" and frame.f_lasti in self._at.get(frame.f_code, ()):
            self.ran = True
        return None if self.ran else self._local

    def _watch(self, frame, event, arg):
        if frame.f_code not in self._codes or self.ran:
            return None
        frame.f_trace_opcodes = self._at is not None
        return self._local

    def __enter__(self) -> LineWatch:
        self._saved.append(sys.gettrace())
        sys.settrace(None if self.ran else self._watch)
        return self

    def __exit__(self, *exc) -> None:
        sys.settrace(self._saved.pop())


def mutated_line(description: str) -> int | None:
    """The source line a mutant's description names (``"... line 80 col 24: ..."``)."""
    import re

    found = re.search(r"\bline (\d+)\b", description)
    return int(found.group(1)) if found else None


def mutated_position(description: str) -> tuple[int, int] | int | None:
    """``(line, col)`` of the mutated expression a description names (``"line 80 col 24: ..."``),
    its line alone when it names no column."""
    import re

    found = re.search(r"\bline (\d+) col (\d+)\b", description)
    return (int(found.group(1)), int(found.group(2))) if found else mutated_line(description)


def replay(fn: FunctionType, code: CodeType, rec: Recording, line=None) -> tuple[bool, bool]:
    """Call ``code`` (a mutant of ``fn``, installed as ``fn`` so recursive calls take it too) on
    every recorded call, caches emptied first: (every value and every argument afterwards equal
    to the recording, whether the mutated code at ``line`` — a line, or ``(line, col)``:
    :class:`LineWatch` — ran). Stops at the first difference."""
    from chaplygin_nd.ledger.mutation.cache_scope import clear

    mutant = _clone(fn, code)
    watch = LineWatch(code, line)
    names = mutable_globals(fn)
    original = fn.__code__
    fn.__code__ = code
    clear()
    try:
        for args, kwargs, value, args_after, kwargs_after in rec.calls:
            a, k = _snapshot(args), _snapshot(kwargs)
            state = _globals_state(fn, names)
            with watch:
                got = _call(mutant, a, k)
            if not (identical(value, got) and identical(args_after, a)
                    and identical(kwargs_after, k)
                    and identical(state, _globals_state(fn, names))):
                return False, watch.ran
    finally:
        fn.__code__ = original
        clear()
    return True, watch.ran
