r"""A mutant that changed no row: is it equivalent? (:func:`settle`)

The row is run once more with both versions computed at every call of the function
(:func:`compare_on_row`); ``equivalent`` only when the mutant returns exactly the original value
(exact SymPy comparison, arrays bit for bit: :func:`same`) — or differs by an invariance the
claim declares (:data:`SCALE_INVARIANT`, :data:`POSITIVE_SCALE_INVARIANT`,
:data:`ARGUMENT_SIGN_INVARIANT`) — at every call, and the mutated line ran.
"""

from __future__ import annotations

import inspect
from types import FunctionType
from typing import Any

import sympy as sp
from chaplygin_nd.ledger.mutation.checks import BUDGET_FACTOR, MIN_BUDGET, run_row

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


def same(x, y) -> bool:
    """Exact equality of two values a printed function (or a derivation) may return: SymPy values
    mathematically, arrays bit for bit, dataclasses field by field (the fields they compare: a
    ``field(compare=False)``, e.g. a time taken, is not part of the value); never raises."""
    import dataclasses

    import numpy as np
    from chaplygin_nd.ledger.mutation.replay import attributes, identical

    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return type(x) is type(y) and all(same(getattr(x, f.name), getattr(y, f.name))
                                           for f in dataclasses.fields(x) if f.compare)
    if isinstance(x, (np.ndarray, np.generic)) or isinstance(y, (np.ndarray, np.generic)):
        return identical(x, y)
    if isinstance(x, dict) and isinstance(y, dict):
        return x.keys() == y.keys() and all(same(x[k], y[k]) for k in x)
    if isinstance(x, (tuple, list)) and isinstance(y, (tuple, list)):
        return len(x) == len(y) and all(same(u, v) for u, v in zip(x, y))
    if isinstance(x, sp.MatrixBase) or isinstance(y, sp.MatrixBase):
        if not (isinstance(x, sp.MatrixBase) and isinstance(y, sp.MatrixBase)) or x.shape != y.shape:
            return False
        return all(same(u, v) for u, v in zip(x, y))
    if isinstance(x, (int, sp.Basic)) and isinstance(y, (int, sp.Basic)):
        d = sp.sympify(x) - sp.sympify(y)
        return d == 0 or sp.expand(sp.together(d)) == 0
    if (own := attributes(x)) is not None:  # no equality of its own: attribute by attribute
        other = attributes(y)
        return (type(x) is type(y) and other is not None and own.keys() == other.keys()
                and all(same(own[k], other[k]) for k in own))
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


def compare_on_row(fn, mutant_code, claim_id: str, budget: float, key: str = "",
                 line: tuple[int, int] | int | None = None, base: tuple | None = None
                 ) -> tuple[bool, int, str, bool]:
    """Run ``claim_id`` with a wrapper computing both the original and the mutant at every call
    of ``fn``; (all equal, number of calls compared, the kind of equality: "exact", or a declared
    invariance of the claim: "scale", "sign of <argument>"; whether the mutant's source line
    ``line`` — the mutated one — ran at least once). Equal only if the row, which sees the
    original's values, ran to its end as unmutated (its signature ``base``, or no error and no
    timeout): a comparison that raised, or a row cut short, compared only some of the calls."""
    from chaplygin_nd.ledger.mutation.replay import LineWatch, calls_through

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
                    equal = same(want, got)
                elif kind == "scale":
                    equal = _proportional(want, got)
                elif kind == "positive scale":
                    equal = _proportional(want, got, positive=True)
                else:
                    bound = inspect.signature(orig_fn).bind(*args, **kwargs)
                    name = ARGUMENT_SIGN_INVARIANT[key][0]
                    bound.arguments[name] = -bound.arguments[name]
                    equal = same(orig_fn(*bound.args, **bound.kwargs), got)
                equal = bool(equal)
            except Exception:  # noqa: BLE001 - values that cannot be compared are not equal
                equal = False
            state["ok"][kind] = equal
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
    (also used for the derivations)."""
    claim_id, base, seconds = rows[0]
    equal, calls, kind, line_ran = compare_on_row(fn, code, claim_id,
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

