r"""``python -m ledger.mutate`` (``make mutate``) — mutation testing of every printed formula.

A transcription in :mod:`symbolic.printed` is only useful if a ledger row notices when it is
wrong. For every public function there (:func:`ledger.reach.printed_functions`) this tool makes
one-symbol mutants from the function's AST (:func:`mutants`):

* ``sign``     — ``+`` <-> ``-``, and a unary minus dropped or added;
* ``const``    — an integer constant ``c`` -> ``c + 1`` (so ``2`` -> ``3``, ``0`` -> ``1``;
  inside ``Rational(p, q)`` too);
* ``swap``     — one occurrence of a name swapped with its partner (``a`` <-> ``b``,
  ``k`` <-> ``u``, ``q`` <-> ``k``, ``xi`` <-> ``eta``, ...), or the two arguments of a
  two-argument call swapped (``wedge(u, v)`` -> ``wedge(v, u)``: a transposition);
* ``exponent`` — ``x**p`` -> ``x**(p + 1)``;
* ``factor``   — the two factors of a product swapped (matrices do not commute), ``*`` <-> ``/``,
  or one factor of a product dropped.

Each mutant is applied in a worker process by replacing the function's ``__code__`` (every caller
sees it; source files are never written), the rows that reach the function (the reach map of
:mod:`ledger.reach`, cheapest first) are run, and each row's verdict, counterexample and parts
are compared with the unmutated run. Outcomes:

* ``killed``     — a row's verdict or counterexample changed (or the row raised, or it ran past
  its time budget: that is said in the reason);
* ``equivalent`` — no row changed *and* the mutant returns exactly the original value (exact
  SymPy comparison) at every call the cheapest reaching row makes, e.g. a swap inside a
  symmetric term; the reason says so and how many calls were compared;
* ``survived``   — no row changed although the mutant's value differs: the transcription is not
  really checked. The run exits 1.

Writes ``mutation.json`` (``{"mutants": [{"function", "row", "mutation", "outcome", "reason"},
...]}``) atomically at the repository root and prints one summary line.

``--engines flint`` makes SymPy abstain from every exact zero test (FLINT alone decides them,
:mod:`symbolic.exact.flint_engine`) and writes ``mutation-flint.json``; ``--compare mutation.json``
lists the mutants whose outcome differs from the two-engine run; ``--sample K`` runs a seeded
sample of K mutants.
"""

from __future__ import annotations

import ast
import contextlib
import inspect
import multiprocessing as mp
import os
import random
import signal
import sys
import textwrap
import time
import traceback
from dataclasses import dataclass
from pathlib import Path
from types import FunctionType
from typing import Any

import sympy as sp
from chaplygin_nd.ledger.catalog import ROOT, is_checkout
from chaplygin_nd.ledger.phase import Phase
from chaplygin_nd.ledger.reach import (
    kept_seconds,
    printed_functions,
    rows_by_function,
    unreached,
    write_json_atomic,
)
from chaplygin_nd.ledger.reach import load as load_reach
from chaplygin_nd.ledger.reach import save as save_reach
from chaplygin_nd.symbolic.exact.flint_engine import ENGINES_ENV, active_engines, engine_label

from chaplygin_nd import processes
from chaplygin_nd.console import OneLineParser, fail, path_argument, positive_int, say

OUT_PATH = ROOT / "mutation.json"
#: Name pairs swapped by the ``swap`` operator (each direction).
PARTNERS = {"a": "b", "b": "a", "k": "u", "u": "k", "q": "k", "xi": "eta", "eta": "xi",
            "M": "Omega", "Omega": "M", "A": "B", "B": "A", "E": "G", "G": "E",
            "w_i": "w_j", "w_j": "w_i", "gamma0": "M0", "lam": "sig", "sig": "lam",
            "U": "Z", "Z": "U", "M0": "Omega0", "Omega0": "M0", "f2": "h", "h": "f2",
            "x0": "x", "x": "x0", "Omega_dot": "Omega", "gamma": "E", "O3": "O1"}
#: Mutants per function at most (chosen round-robin over the operators, seeded).
PER_FUNCTION = 4
#: A row's time budget under a mutant: this many times its unmutated time, at least MIN_BUDGET s.
BUDGET_FACTOR, MIN_BUDGET = 5.0, 15.0
#: Rows tried per mutant: cheapest first, until the summed unmutated time passes this (s).
ROW_TIME_CAP = 90.0
#: ``--sample``: draw among mutants whose reaching rows took less than this in the saved reach map
SAMPLE_ROW_SECONDS = 8.0


#: Printed functions whose *claim* cannot see a non-zero constant factor of the value: a zero set
#: ({c f = 0} = {f = 0}) or a first integral (c F is conserved iff F is). A mutant equal to c times
#: the original (c a non-zero number) at every call is ``equivalent`` for this reason.
SCALE_INVARIANT = {
    **{f: "a zero set: {c f = 0} = {f = 0} for a constant c != 0"
       for f in ("section3.V_3d", "section3.V_nd", "section3.H_nd", "section5.H_set",
                 "section5.V_set", "section5.H_SO3", "section5.V_SO3")},
    "section5.F1": "a first integral (c F_1 is conserved iff F_1 is; p(lambda, sigma) contains "
                   "F_1 only squared, so only the sign c = -1 can occur unseen)",
    "section2.characteristic_polynomial": "first integrals: the coefficients of c p are conserved "
                                          "iff those of p are (p is not normalised by the claim)",
}
#: Densities of invariant measures: a measure is defined up to a *positive* constant factor
#: (the rows check positivity separately, so only c > 0 counts as equivalent).
POSITIVE_SCALE_INVARIANT = {
    "section5.measure_density": "the density of an invariant measure, defined up to a positive "
                                "constant factor",
}
#: Printed functions whose claim is invariant under a sign change of one argument.
ARGUMENT_SIGN_INVARIANT = {
    "section2.characteristic_polynomial": ("sigma", "the claim (coefficients of p(lambda, sigma) "
                                                    "are first integrals for every sigma) is "
                                                    "invariant under sigma -> -sigma"),
}


@dataclass(frozen=True)
class Mutant:
    """One one-symbol change of one printed function."""

    function: str       # "section4.K"
    operator: str       # sign / const / swap / exponent / factor
    description: str    # "line 133: a * b -> b * a"
    index: int          # position in the function's full mutant list (stable)


# ---------------------------------------------------------------------------------------------
# Generating mutants from the AST
# ---------------------------------------------------------------------------------------------

def _function_ast(fn) -> ast.FunctionDef:
    source = textwrap.dedent(inspect.getsource(fn))
    node = ast.parse(source).body[0]
    assert isinstance(node, ast.FunctionDef)
    first = fn.__code__.co_firstlineno
    ast.increment_lineno(node, first - 1)
    return node


def _body_nodes(fn_node: ast.FunctionDef):
    """Nodes of the body, docstring excluded."""
    body = fn_node.body
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
            and isinstance(body[0].value.value, str):
        body = body[1:]
    for stmt in body:
        yield from ast.walk(stmt)


def _is_int(node) -> bool:
    return isinstance(node, ast.Constant) and type(node.value) is int


def _local_names(fn_node: ast.FunctionDef) -> set[str]:
    """The function's argument names and the names it assigns."""
    a = fn_node.args
    names = {x.arg for x in (*a.posonlyargs, *a.args, *a.kwonlyargs)}
    names |= {n.id for n in ast.walk(fn_node) if isinstance(n, ast.Name)
              and isinstance(n.ctx, ast.Store)}
    return names


def _edits(fn_node: ast.FunctionDef):
    """Yield (operator, node to replace, replacement node) for every candidate edit. A name is
    swapped only with a partner the function defines (no NameError mutants)."""
    local = _local_names(fn_node)
    for node in _body_nodes(fn_node):
        if isinstance(node, ast.BinOp):
            op = type(node.op)
            if op in (ast.Add, ast.Sub):
                new_op = ast.Sub() if op is ast.Add else ast.Add()
                yield "sign", node, ast.BinOp(node.left, new_op, node.right)
            if op is ast.Mult:
                yield "factor", node, ast.BinOp(node.right, ast.Mult(), node.left)
                yield "factor", node, node.left
                yield "factor", node, node.right
            if op is ast.Div:
                yield "factor", node, ast.BinOp(node.left, ast.Mult(), node.right)
            if op is ast.Pow:
                yield "exponent", node, ast.BinOp(node.left, ast.Pow(), ast.BinOp(
                    node.right, ast.Add(), ast.Constant(1)))
        elif isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            yield "sign", node, node.operand
        elif _is_int(node):
            yield "const", node, ast.Constant(node.value + 1)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) \
                and node.id in local and PARTNERS.get(node.id) in local:
            yield "swap", node, ast.Name(PARTNERS[node.id], ast.Load())
        elif isinstance(node, ast.Call) and len(node.args) == 2 and not node.keywords:
            a0, a1 = node.args
            if ast.dump(a0) != ast.dump(a1):
                yield "swap", node, ast.Call(node.func, [a1, a0], [])
        if isinstance(node, ast.Return) and node.value is not None \
                and not isinstance(node.value, (ast.Tuple, ast.Dict)):
            yield "sign", node.value, ast.UnaryOp(ast.USub(), node.value)


class _Replace(ast.NodeTransformer):
    def __init__(self, target, replacement):
        self.target, self.replacement, self.done = target, replacement, False

    def visit(self, node):
        if node is self.target:
            self.done = True
            return self.replacement
        return super().generic_visit(node) or node


def _apply(fn_node: ast.FunctionDef, target, replacement) -> ast.FunctionDef:
    import copy

    # Deep-copy with the target mapped through: copy the tree, locate the twin of ``target``.
    twins: dict[int, ast.AST] = {}
    tree = copy.deepcopy(fn_node, memo=twins)
    twin = twins[id(target)]
    new = ast.copy_location(copy.deepcopy(replacement), twin)  # the mutated code sits where the
    mutated = _Replace(twin, new).visit(tree)                   # target did (LineWatch looks there)
    ast.fix_missing_locations(mutated)
    return mutated


def _describe(target, replacement) -> str:
    line, col = getattr(target, "lineno", "?"), getattr(target, "col_offset", "?")
    return f"line {line} col {col}: {ast.unparse(target)} -> {ast.unparse(replacement)}"


#: ``(key, code object) -> all_mutants(key, fn)``: computed once per process and function (a large
#: function took ~8 s, and each mutant compiled called it again); keyed on the code object, so a
#: function whose code changed is parsed afresh. Forked workers inherit the parent's.
_ALL_MUTANTS: dict[tuple, list] = {}


def all_mutants(key: str, fn) -> list[tuple[Mutant, ast.FunctionDef]]:
    """Every candidate mutant of one printed function, with its mutated AST, in source order.
    Mutants whose source is unchanged or that merely repeat another are dropped."""
    memo = (key, fn.__code__)
    if memo not in _ALL_MUTANTS:
        _ALL_MUTANTS[memo] = _all_mutants(key, fn)
    return _ALL_MUTANTS[memo]


def _all_mutants(key: str, fn) -> list[tuple[Mutant, ast.FunctionDef]]:
    node = _function_ast(fn)
    original = ast.unparse(node)
    out, seen = [], {original}
    for i, (operator, target, replacement) in enumerate(_edits(node)):
        mutated = _apply(node, target, replacement)
        text = ast.unparse(mutated)
        if text in seen:
            continue
        seen.add(text)
        out.append((Mutant(key, operator, _describe(target, replacement), i), mutated))
    return out


def mutants(key: str, fn, per_function: int = PER_FUNCTION, seed: int = 20261123) -> list[Mutant]:
    """A deterministic selection of at most ``per_function`` mutants of ``fn``, round-robin over
    the operators (so every kind present is represented)."""
    cands = [m for m, _ in all_mutants(key, fn)]
    rng = random.Random(f"{seed}:{key}")
    by_op: dict[str, list[Mutant]] = {}
    for m in cands:
        by_op.setdefault(m.operator, []).append(m)
    for lst in by_op.values():
        rng.shuffle(lst)
    chosen: list[Mutant] = []
    while len(chosen) < per_function and any(by_op.values()):
        for op in sorted(by_op):
            if by_op[op] and len(chosen) < per_function:
                chosen.append(by_op[op].pop())
    return sorted(chosen, key=lambda m: m.index)


def compile_mutant(fn, mutant: Mutant):
    """The code object of ``mutant`` (compiled from the mutated AST; nothing is written)."""
    for m, tree in all_mutants(mutant.function, fn):
        if m.index == mutant.index:
            module = ast.Module(body=[tree], type_ignores=[])
            ast.fix_missing_locations(module)
            namespace = dict(fn.__globals__)
            exec(compile(module, f"<mutant {mutant.function} #{mutant.index}>", "exec"), namespace)
            return namespace[fn.__name__].__code__
    raise KeyError(f"no mutant #{mutant.index} of {mutant.function}")


# ---------------------------------------------------------------------------------------------
# Running rows with a mutant
# ---------------------------------------------------------------------------------------------

def signature(verdict, error: str = "") -> tuple:
    """What a mutant must change: the verdict, the counterexample, and each part's."""
    if error:
        return ("error",)
    return (verdict.verdict, verdict.counterexample,
            tuple((p.name, p.verdict, p.counterexample) for p in verdict.parts))


class BudgetExceeded(BaseException):
    """A check under a mutant ran past its budget. Not an ``Exception``: a row's own ``except
    Exception``, or a replay's (a raise is a value there), must not take it for a result."""


def _alarm(signum, frame):
    raise BudgetExceeded()


@contextlib.contextmanager
def time_budget(seconds: float):
    """Within the block, :class:`BudgetExceeded` is raised once ``seconds`` have passed (SIGALRM;
    main thread only). The one time limit of the mutation tools: rows and replays."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


class _PartChanged(BaseException):  # not an Exception: a row's own ``except Exception`` must
    # not turn the stop into a part of its own
    def __init__(self, note: str):
        super().__init__(note)
        self.note = note


class PartContractError(RuntimeError):
    """A row announced a part with ``registry.decided`` that its verdict does not contain."""


def _part_watch(base: tuple):
    """The callback of :func:`registry.observing_parts` for a run compared with ``base`` (a
    signature): raises :class:`_PartChanged` at the first final part that is not the base's
    part of the same name (its k-th occurrence for the k-th announced)."""
    expected: dict[str, list[tuple]] = {}
    for p in base[2] if len(base) == 3 else ():
        expected.setdefault(p[0], []).append(p)
    count: dict[str, int] = {}

    def watch(part) -> None:
        k = count[part.name] = count.get(part.name, 0) + 1
        got = (part.name, part.verdict, part.counterexample)
        want = expected.get(part.name, [])
        if k > len(want):
            raise _PartChanged(f"part '{part.name}' is new (stopped there)")
        if want[k - 1] != got:
            what = f"{want[k - 1][1]} -> {got[1]}" + (
                " (counterexample changed)" if want[k - 1][1] == got[1] else "")
            raise _PartChanged(f"part '{part.name}': {what} (stopped at that part)")

    return watch


def run_row(claim_id: str, budget: float | None = None, base: tuple | None = None,
            ) -> tuple[tuple, str]:
    """Run one ledger row in this process: (signature, note). ``budget``: seconds, else raises.
    ``base`` (the unmutated row's signature): stop at the first part the row announces final
    (``registry.decided``) that differs from the base's; the signature is then ``("part
    changed", name)`` — it differs from the base, as the whole row's would."""
    from chaplygin_nd.ledger.registry import observing_parts, registry

    spec = registry()[claim_id]
    watch = observing_parts(_part_watch(base) if base is not None else (lambda part: None))
    try:
        with watch, (time_budget(budget) if budget else contextlib.nullcontext()):
            verdict = spec.run()
        missing = [p.name for p in watch.seen if p not in verdict.parts]
        if missing:
            raise PartContractError(f"{claim_id}: parts announced final are not in its verdict: "
                                    f"{', '.join(missing)}")
        return signature(verdict), ""
    except _PartChanged as stop:
        return ("part changed", stop.note), stop.note
    except BudgetExceeded:
        return ("timeout",), f"ran past its budget of {budget:.0f} s"
    except PartContractError:
        raise
    except Exception as err:  # noqa: BLE001 - a raising proof is an observed change
        return ("error",), f"raised {type(err).__name__}: {str(err)[:120]}"


def _same(x, y) -> bool:
    """Exact equality of two values a printed function (or a derivation) may return: SymPy values
    mathematically, arrays bit for bit, dataclasses field by field (the fields they compare: a
    ``field(compare=False)``, e.g. a time taken, is not part of the value); never raises."""
    import dataclasses

    import numpy as np
    from chaplygin_nd.ledger.mutate_replay import attributes, identical

    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return type(x) is type(y) and all(_same(getattr(x, f.name), getattr(y, f.name))
                                           for f in dataclasses.fields(x) if f.compare)
    if isinstance(x, (np.ndarray, np.generic)) or isinstance(y, (np.ndarray, np.generic)):
        return identical(x, y)
    if isinstance(x, dict) and isinstance(y, dict):
        return x.keys() == y.keys() and all(_same(x[k], y[k]) for k in x)
    if isinstance(x, (tuple, list)) and isinstance(y, (tuple, list)):
        return len(x) == len(y) and all(_same(u, v) for u, v in zip(x, y))
    if isinstance(x, sp.MatrixBase) or isinstance(y, sp.MatrixBase):
        if not (isinstance(x, sp.MatrixBase) and isinstance(y, sp.MatrixBase)) or x.shape != y.shape:
            return False
        return all(_same(u, v) for u, v in zip(x, y))
    if isinstance(x, (int, sp.Basic)) and isinstance(y, (int, sp.Basic)):
        d = sp.sympify(x) - sp.sympify(y)
        return d == 0 or sp.expand(sp.together(d)) == 0
    if (own := attributes(x)) is not None:  # no equality of its own: attribute by attribute
        other = attributes(y)
        return (type(x) is type(y) and other is not None and own.keys() == other.keys()
                and all(_same(own[k], other[k]) for k in own))
    try:
        return bool(x == y)
    except Exception:  # noqa: BLE001 - no equality that gives one truth value: compare as a row sees it
        return identical(x, y)


def _flat(value) -> list:
    if isinstance(value, dict):
        return [v for k in sorted(value, key=str) for v in _flat(value[k])]
    if isinstance(value, (tuple, list)):
        return [v for item in value for v in _flat(item)]
    if isinstance(value, sp.MatrixBase):
        return list(value)
    return [value]


def _proportional(want, got, positive: bool = False) -> bool:
    """``got`` = c * ``want`` for one number c != 0 (c > 0 if ``positive``), exactly."""
    a, b = _flat(want), _flat(got)
    if len(a) != len(b):
        return False
    try:
        pivot = next(i for i, v in enumerate(a) if sp.expand(sp.sympify(v)) != 0)
    except StopIteration:
        return all(sp.expand(sp.sympify(v)) == 0 for v in b)
    c = sp.cancel(sp.sympify(b[pivot]) / sp.sympify(a[pivot]))
    if c == 0 or c.free_symbols or not c.is_number or (positive and not c.is_positive):
        return False
    return all(sp.expand(sp.together(sp.sympify(v) - c * sp.sympify(u))) == 0 for u, v in zip(a, b))


def _equivalence(fn, mutant_code, claim_id: str, budget: float, key: str = "",
                 line: tuple[int, int] | int | None = None, base: tuple | None = None
                 ) -> tuple[bool, int, str, bool]:
    """Run ``claim_id`` with a wrapper computing both the original and the mutant at every call
    of ``fn``; (all equal, number of calls compared, the kind of equality: "exact", or a declared
    invariance of the claim: "scale", "sign of <argument>"; whether the mutant's source line
    ``line`` — the mutated one — ran at least once). Equal only if the row, which sees the
    original's values, ran to its end as unmutated (its signature ``base``, or no error and no
    timeout): a comparison that raised, or a row cut short, compared only some of the calls."""
    from chaplygin_nd.ledger.mutate_replay import LineWatch, calls_through

    original = fn.__code__
    orig_fn = FunctionType(original, fn.__globals__, fn.__name__, fn.__defaults__)
    orig_fn.__kwdefaults__ = fn.__kwdefaults__
    mut_fn = FunctionType(mutant_code, fn.__globals__, fn.__name__, fn.__defaults__)
    mut_fn.__kwdefaults__ = fn.__kwdefaults__
    kinds = ["exact"] + (["scale"] if key in SCALE_INVARIANT else []) + (
        ["positive scale"] if key in POSITIVE_SCALE_INVARIANT else []) + (
        ["sign"] if key in ARGUMENT_SIGN_INVARIANT else [])
    state: dict[str, Any] = {"calls": 0, "ok": dict.fromkeys(kinds, True)}
    watch = LineWatch(mutant_code, line)

    def hook(*args, **kwargs):
        want = orig_fn(*args, **kwargs)
        state["calls"] += 1
        try:
            with watch:
                got = mut_fn(*args, **kwargs)
        except Exception:  # noqa: BLE001 - a mutant that raises where the original does not
            state["ok"] = dict.fromkeys(kinds, False)
            return want
        for kind in kinds:
            if not state["ok"][kind]:
                continue
            try:
                if kind == "exact":
                    same = _same(want, got)
                elif kind == "scale":
                    same = _proportional(want, got)
                elif kind == "positive scale":
                    same = _proportional(want, got, positive=True)
                else:
                    bound = inspect.signature(orig_fn).bind(*args, **kwargs)
                    name = ARGUMENT_SIGN_INVARIANT[key][0]
                    bound.arguments[name] = -bound.arguments[name]
                    same = _same(orig_fn(*bound.args, **bound.kwargs), got)
                same = bool(same)
            except Exception:  # noqa: BLE001 - values that cannot be compared are not equal
                same = False
            state["ok"][kind] = same
        return want

    with calls_through(fn, hook):
        got, _note = run_row(claim_id, budget)
    whole = got == base if base is not None else got[0] not in ("error", "timeout")
    kind = next((k for k in kinds if state["ok"][k]), "")
    return whole and bool(kind) and state["calls"] > 0, state["calls"], kind, watch.ran


def settle(record: dict, fn, code, rows, tried: list[str], key: str = "",
           line: tuple[int, int] | int | None = None, ran: bool = False) -> dict:
    """A mutant that changed no row: ``equivalent`` only if its value equals the original's (or
    differs by an invariance registered for ``key``) at every call the cheapest row makes and
    the mutated source ``line`` executed there (or ``ran`` says it did elsewhere: equal values
    on a branch no row takes prove nothing), else ``survived``; fills and returns ``record``
    (also used by ``mutate_derivations``)."""
    claim_id, base, seconds = rows[0]
    equal, calls, kind, line_ran = _equivalence(fn, code, claim_id,
                                                max(MIN_BUDGET, BUDGET_FACTOR * seconds), key,
                                                line, base)
    if equal and not (ran or line_ran):
        record.update(outcome="survived", row=", ".join(tried), reason=(
            f"equal values at all {calls} calls of row {claim_id}, but the mutated line never "
            f"ran there (a branch no row takes); no row ({', '.join(tried)}) changed"))
    elif equal:
        what = {"exact": "exactly the original value",
                "scale": "a non-zero constant times the original value ("
                         + SCALE_INVARIANT.get(key, "") + ")",
                "positive scale": "a positive constant times the original value ("
                                  + POSITIVE_SCALE_INVARIANT.get(key, "") + ")",
                "sign": "the original value with its argument negated ("
                        + ARGUMENT_SIGN_INVARIANT.get(key, ("", ""))[1] + ")"}[kind]
        record.update(outcome="equivalent", row=claim_id, reason=(
            f"the mutant returns {what} (exact SymPy comparison) at all {calls} calls made by "
            f"row {claim_id}; no row ({', '.join(tried)}) changed"))
    else:
        record.update(outcome="survived", row=", ".join(tried), reason=(
            f"value differs from the original but no row changed "
            f"({', '.join(tried)}; compared {calls} calls)"))
    return record


def evaluate(task: tuple[Mutant, list[tuple[str, tuple, float]]]) -> dict:
    """Decide one mutant (in a worker): apply it, run its rows, compare, restore."""
    mutant, rows = task
    fn = printed_functions()[mutant.function]
    original = fn.__code__
    record: dict[str, Any] = {"function": mutant.function, "mutation": f"{mutant.operator}: {mutant.description}",
              "row": None, "outcome": "", "reason": ""}
    try:
        code = compile_mutant(fn, mutant)
    except Exception as err:  # noqa: BLE001 - e.g. a swap producing an undefined name
        record.update(outcome="killed", row=rows[0][0] if rows else None,
                      reason=f"the mutant does not compile/define: {type(err).__name__}: {err}")
        return record
    tried = []
    start = time.perf_counter()
    try:
        for claim_id, base, seconds in rows:
            budget = max(MIN_BUDGET, BUDGET_FACTOR * seconds)
            fn.__code__ = code
            try:
                got, note = run_row(claim_id, budget, base)
            finally:
                fn.__code__ = original
            tried.append(claim_id)
            if got != base:
                why = note or _difference(base, got)
                record.update(outcome="killed", row=claim_id, reason=why)
                return record
        from chaplygin_nd.ledger.mutate_replay import mutated_position

        return settle(record, fn, code, rows, tried, mutant.function, mutated_position(mutant.description))
    except Exception:  # noqa: BLE001
        record.update(outcome="error", reason=traceback.format_exc(limit=3))
        return record
    finally:
        fn.__code__ = original
        record["seconds"] = round(time.perf_counter() - start, 2)


def _difference(base: tuple, got: tuple) -> str:
    if got[0] in ("error", "timeout"):
        return f"row {got[0]}"  # (run_row's note, "raised ...", is preferred when present)
    if base[0] != got[0]:
        return f"verdict {base[0]} -> {got[0]}"
    if base[1] != got[1]:
        return "counterexample changed" if base[1] else "a counterexample appeared"
    for p, q in zip(base[2], got[2]):
        if p != q:
            return f"part '{p[0]}': {p[1]} -> {q[1]}" + (
                " (counterexample changed)" if p[1] == q[1] else "")
    return "parts changed"


# ---------------------------------------------------------------------------------------------
# Baseline and driver
# ---------------------------------------------------------------------------------------------

def _init_worker():
    from chaplygin_nd.ledger.catalog import discover

    discover()


def baseline(ids=None, jobs: int = 2, phase=None):
    """Run rows unmutated (all, or ``ids``): {row: (signature, seconds, printed functions)};
    ``phase`` (:class:`ledger.phase.Phase`) counts the rows as they are decided."""
    from chaplygin_nd.ledger.runner import run, select

    rows = select(ids or ())
    if phase is not None:
        phase.total = len(rows)
    results = run(rows, jobs=jobs, on_result=(lambda r: phase.add()) if phase is not None
                  else (lambda r: None), on_wake=phase.tick if phase is not None else None)
    bad = [r.row.id for r in results if r.error]
    if bad:
        raise RuntimeError(f"rows raise without any mutant: {', '.join(bad)}")
    return {r.row.id: (signature(r.verdict), r.seconds, list(r.printed))
            for r in results if r.module}


def plan(base: dict, selection: list[Mutant]) -> list[tuple[Mutant, list]]:
    """Each mutant with the rows reaching its function, cheapest first, capped by ROW_TIME_CAP."""
    reach = rows_by_function({row: info[2] for row, info in base.items()})
    tasks = []
    for m in selection:
        rows = sorted(reach.get(m.function, []), key=lambda r: base[r][1])
        chosen: list = []
        total = 0.0
        for r in rows:
            if chosen and total + base[r][1] > ROW_TIME_CAP:
                break
            chosen.append((r, base[r][0], base[r][1]))
            total += base[r][1]
        if chosen:
            tasks.append((m, chosen))
    return tasks


def run_mutants(tasks, jobs: int = 2, on_record=lambda r: None) -> list[dict]:
    """Evaluate ``tasks`` in ``jobs`` forked worker processes (ordered output)."""
    if jobs <= 1:
        out = []
        for t in tasks:
            out.append(evaluate(t))
            on_record(out[-1])
        return out
    ctx = mp.get_context("fork")
    with processes.pool(jobs, ctx, _init_worker) as pool:
        out = []
        for rec in pool.map(evaluate, tasks):
            out.append(rec)
            on_record(rec)
        return out


def plural(count: int, noun: str) -> str:
    """``1 job``, ``2 jobs``."""
    return f"{count} {noun}{'' if count == 1 else 's'}"


def select_all(per_function: int = PER_FUNCTION) -> list[Mutant]:
    return [m for key, fn in printed_functions().items() for m in mutants(key, fn, per_function)]


def summary(records: list[dict], functions: int, seconds: float) -> str:
    count = {k: sum(r["outcome"] == k for r in records)
             for k in ("killed", "equivalent", "survived", "error")}
    raised = sum(r["outcome"] == "killed" and r["reason"].startswith(("raised", "row error",
                                                                         "the mutant does not"))
                 for r in records)
    covered = len({r["function"] for r in records})
    return (f"{len(records)} mutants of {covered}/{functions} printed functions: "
            f"{count['killed']} killed ({raised} of them because a row raised or timed out), "
            f"{count['equivalent']} equivalent, {count['survived']} "
            f"survived, {count['error']} errors; score {count['killed']}/"
            f"{len(records) - count['equivalent']} non-equivalent killed; {seconds:.0f} s")


def compared_outcomes(other: Path) -> dict[tuple[str, str], str] | str:
    """``(function, mutation) -> outcome`` of the run saved at ``other`` (a mutation.json), or the
    one-line error saying why it cannot be read: checked before the run, so a wrong ``--compare``
    never costs a whole mutation run and its results."""
    import json

    try:
        mutants = json.loads(Path(other).read_text(encoding="utf-8"))["mutants"]
        return {(r["function"], r["mutation"]): r["outcome"] for r in mutants}
    except OSError as exc:
        return f"--compare {other}: cannot read it ({exc.strerror or exc})"
    except (ValueError, KeyError, TypeError) as exc:
        return (f"--compare {other}: not a mutation.json of `chaplygin mutate` ({type(exc).__name__}:"
                f" {exc})")


def _compare(records: list[dict], theirs: dict[tuple[str, str], str]) -> list[str]:
    """Mutants run in both ``records`` and ``theirs`` (:func:`compared_outcomes`) whose outcome
    differs."""
    return [f"{r['function']} {r['mutation']}: {theirs[(r['function'], r['mutation'])]} there, "
            f"{r['outcome']} here" for r in records
            if (r["function"], r["mutation"]) in theirs
            and theirs[(r["function"], r["mutation"])] != r["outcome"]]


def unknown_functions(names: list[str], known, list_option: str) -> str | None:
    """The one-line error for the ``--function`` names not in ``known`` (with "did you mean" for
    a near miss and ``list_option``, the command that lists the names), or None when all are
    known. Checked before anything runs."""
    import difflib

    bad = [name for name in names if name not in known]
    if not bad:
        return None
    hints = [f"{name!r}" + "".join(f" (did you mean {m}?)" for m in
                                   difflib.get_close_matches(name, list(known), n=1)) for name in bad]
    return (f"--function: unknown function {', '.join(hints)}; `{list_option}` lists the "
            f"{len(known)} names it takes")


def main(argv: list[str] | None = None) -> int:
    parser = OneLineParser(prog="chaplygin mutate", description=(
        "Mutation testing of every printed formula: one-symbol mutants, each run against the "
        "ledger rows that reach it; writes mutation.json (make mutate)."))
    parser.add_argument("--jobs", "-j", type=positive_int, default=2)
    parser.add_argument("--per-function", type=positive_int, default=PER_FUNCTION)
    parser.add_argument("--function", action="append", default=[],
                        help="only these printed functions (e.g. section4.K; --list lists them)")
    parser.add_argument("--list", action="store_true",
                        help="list the printed functions (the names --function takes) and exit")
    parser.add_argument("--out", type=path_argument, default=None,
                        help="where to write (default mutation.json; mutation-flint.json with "
                             "--engines flint)")
    parser.add_argument("--engines", choices=("both", "flint"), default="both",
                        help="who decides the exact zero tests: SymPy and FLINT (default), or "
                             "FLINT alone (SymPy abstains: CHAPLYGIN_ND_ENGINES=flint)")
    parser.add_argument("--sample", type=int, default=0,
                        help="run a seeded sample of this many mutants among those whose rows "
                             f"are cheap (< {SAMPLE_ROW_SECONDS:.0f} s in ledger/reach.json), "
                             "with a baseline of those rows only (0: all)")
    parser.add_argument("--compare", type=path_argument, default=None,
                        help="a mutation.json of another run: report mutants whose outcome differs")
    args = parser.parse_args(argv)
    if args.list:
        say("\n".join(printed_functions()))
        return 0
    problem = unknown_functions(args.function, printed_functions(), "chaplygin mutate --list")
    if args.sample < 0:
        problem = f"--sample: {args.sample} is negative; give a number of mutants (0: all)"
    if problem:
        return fail(problem)
    theirs = compared_outcomes(args.compare) if args.compare else {}
    if isinstance(theirs, str):
        return fail(theirs)
    if args.out is None and not is_checkout():
        return fail("chaplygin mutate: give --out FILE (an installed package is never written into)")
    partial = [o for o, given in (("--function", args.function), ("--sample", args.sample)) if given]
    if args.out is None and partial:  # the checked-in record is a whole run
        return fail(f"chaplygin mutate: with {' '.join(partial)} give --out FILE: a partial run "
                    "would replace the record of the full run, mutation.json")
    if args.out is not None and (args.out.exists() or args.out.is_symlink()) and (
            args.out.is_symlink() or isinstance(compared_outcomes(args.out), str)):
        return fail(f"--out {args.out}: exists and is not a mutation.json this program wrote; give "
                    "a new file name (nothing else is replaced)")
    os.environ[ENGINES_ENV] = args.engines
    if args.out is None:
        args.out = OUT_PATH if args.engines == "both" else ROOT / "mutation-flint.json"
    from chaplygin_nd.writing import probe_problem

    folder = args.out.parent
    where = probe_problem(folder) if folder.is_dir() else "no such folder"
    if where:  # before the run, not after it (checked by creating a file there, as root too)
        return fail(f"--out {args.out}: cannot write in {folder} ({where}); give a file in a "
                    "folder you can write")
    start = time.perf_counter()
    from chaplygin_nd.ledger.catalog import discover

    discover()
    listing = Phase(f"listing the mutants of {len(printed_functions())} printed functions")
    sample_rows = None
    if args.sample:
        listing.start()  # a seeded sample among mutants whose rows (saved reach map) are cheap
        saved_rows, saved_seconds = load_reach()
        by_function = rows_by_function(saved_rows)
        cheap = [m for m in select_all(args.per_function)
                 if (not args.function or m.function in args.function) and by_function.get(m.function)
                 and sum(saved_seconds.get(r, 99.0) for r in by_function[m.function]) < SAMPLE_ROW_SECONDS]
        chosen = random.Random(20261123).sample(cheap, min(args.sample, len(cheap)))
        sample_rows = sorted({r for m in chosen for r in by_function[m.function]})
    base = baseline(sample_rows, jobs=args.jobs, phase=Phase(
        f"baseline: running the {'rows of the sample' if sample_rows else 'ledger rows'} unmutated "
        f"({plural(args.jobs, 'job')}; it finds which rows reach each printed function)",
        what="rows done").start())
    reach = {row: info[2] for row, info in base.items()}
    missing = unreached(reach) if not args.sample else []
    if not args.function and args.engines == "both" and not args.sample and is_checkout():
        save_reach(reach, kept_seconds({row: info[1] for row, info in base.items()}))
    if args.sample:
        selection = chosen
    else:
        listing.start()
        selection = [m for m in select_all(args.per_function)
                     if not args.function or m.function in args.function]
    tasks = plan(base, selection)
    print(f"baseline: {len(base)} rows in {time.perf_counter() - start:.0f} s; "
          f"{len(tasks)} mutants to run", flush=True)

    def show(rec):
        if rec["outcome"] != "killed":
            print(f"  {rec['outcome']:<10} {rec['function']:<32} {rec['mutation']}  "
                  f"[{rec['row']}] {rec['reason'][:160]}", flush=True)

    records = run_mutants(tasks, jobs=args.jobs, on_record=show)
    functions = len(printed_functions())
    line = summary(records, functions, time.perf_counter() - start)
    line = f"engines {engine_label(active_engines())}: {line}"
    if args.sample:
        line += f" (seeded sample of {len(selection)} mutants)"
    differ = _compare(records, theirs) if args.compare else []
    write_json_atomic({"summary": line, "engines": args.engines, "mutants": records,
                       "differs_from_compared": differ}, args.out)
    print(line)
    if args.compare:
        print(f"compared with {args.compare}: {len(differ)} mutants with another outcome")
        for d in differ:
            print(f"  {d}")
    print(f"wrote {args.out}")
    problems = [f"printed function {f} is reached by no ledger row" for f in missing]
    problems += [f"{r['function']} {r['mutation']}: {r['outcome']}" for r in records
                 if r["outcome"] in ("survived", "error")]
    if not args.function and not args.sample:
        covered = {r["function"] for r in records}
        problems += [f"printed function {f} has no mutant" for f in printed_functions()
                     if f not in covered]
    for p in problems:
        print(f"PROBLEM: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
