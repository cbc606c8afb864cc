r"""One-token mutants of a function, generated from its AST (:func:`mutants`, :func:`all_mutants`).

* ``sign``     — ``+`` <-> ``-``, and a unary minus dropped or added;
* ``const``    — an integer constant ``c`` -> ``c + 1`` (so ``2`` -> ``3``, ``0`` -> ``1``;
  inside ``Rational(p, q)`` too);
* ``swap``     — one occurrence of a name swapped with its partner (``a`` <-> ``b``,
  ``k`` <-> ``u``, ``q`` <-> ``k``, ``xi`` <-> ``eta``, ...), or the two arguments of a
  two-argument call swapped (``wedge(u, v)`` -> ``wedge(v, u)``: a transposition);
* ``exponent`` — ``x**p`` -> ``x**(p + 1)``;
* ``factor``   — the two factors of a product swapped (matrices do not commute), ``*`` <-> ``/``,
  or one factor of a product dropped.

A mutant is named by its function, operator and description (``"line 133 col 8: a * b -> b *
a"``); :func:`compile_mutant` gives its code object, to put in place of the function's
``__code__``. :func:`source_digest` fingerprints a function's source, so that a record of a
mutant made on other code is recognised as stale (:mod:`.record`).
"""

from __future__ import annotations

import ast
import hashlib
import inspect
import random
import textwrap
from dataclasses import dataclass

#: Name pairs swapped by the ``swap`` operator (each direction).
PARTNERS = {"a": "b", "b": "a", "k": "u", "u": "k", "q": "k", "xi": "eta", "eta": "xi",
            "M": "Omega", "Omega": "M", "A": "B", "B": "A", "E": "G", "G": "E",
            "w_i": "w_j", "w_j": "w_i", "gamma0": "M0", "lam": "sig", "sig": "lam",
            "U": "Z", "Z": "U", "M0": "Omega0", "Omega0": "M0", "f2": "h", "h": "f2",
            "x0": "x", "x": "x0", "Omega_dot": "Omega", "gamma": "E", "O3": "O1"}
#: Mutants per function at most (chosen round-robin over the operators, seeded).
PER_FUNCTION = 4


@dataclass(frozen=True)
class Mutant:
    """One one-symbol change of one function (printed, a derivation, or the runtime)."""

    function: str       # "section4.K"
    operator: str       # sign / const / swap / exponent / factor
    description: str    # "line 133: a * b -> b * a"
    index: int          # position in the function's full mutant list (stable)


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
    """The code object of ``mutant`` (compiled from the mutated AST; nothing is written). The
    function's decorators are left out: ``fn`` is the plain function (a cached one's
    ``__wrapped__``), whose code the mutant replaces; compiled with its ``@functools.cache``, the
    name bound was the cache wrapper, which has no code, and every mutant of a cached derivation
    was recorded killed ("does not compile") without being run."""
    for m, tree in all_mutants(mutant.function, fn):
        if m.index == mutant.index:
            bare = ast.FunctionDef(**{name: getattr(tree, name) for name in tree._fields})
            bare.decorator_list = []
            module = ast.Module(body=[ast.copy_location(bare, tree)], type_ignores=[])
            ast.fix_missing_locations(module)
            namespace = dict(fn.__globals__)
            exec(compile(module, f"<mutant {mutant.function} #{mutant.index}>", "exec"), namespace)
            return namespace[fn.__name__].__code__
    raise KeyError(f"no mutant #{mutant.index} of {mutant.function}")


def source_digest(fn) -> str:
    """A fingerprint of ``fn``'s source (its AST unparsed: comments, blank lines and where the
    function sits in its file do not count): a record of a mutant of ``fn`` decided when the
    digest was another was decided on other code."""
    return hashlib.sha256(ast.unparse(_function_ast(fn)).encode()).hexdigest()[:16]
