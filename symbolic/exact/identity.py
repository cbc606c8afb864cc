r"""The exact identity engine: every symbolic verdict of the ledger comes from here.

Two routes, both exact (no floating point anywhere):

1. :func:`rational_identity` — *proof*. The residual (an expression or a matrix of them) is
   converted into the field of rational functions $\mathbb{Q}(x_1,\dots,x_m)$ with SymPy's sparse
   polynomial arithmetic; its numerator is reduced modulo $\lVert\gamma\rVert^2 - 1$ when the
   identity is claimed on the sphere. The single polynomial $g = \gamma_1^2+\dots+\gamma_n^2-1$ is
   a Gröbner basis of the ideal it generates, so the remainder of the division by $g$ (lex order
   with the pivot $\gamma_p$ first, leading monomial $\gamma_p^2$) is zero **iff** the numerator lies
   in $(g)$. The ideal is prime ($g$ is irreducible for $n \ge 2$) and its real points are
   Zariski-dense in its complex points, so this holds iff the numerator vanishes on the real
   sphere: the identity holds wherever it is defined on $S^{n-1}$.

2. :func:`zero_at_points` — *evidence at seeded exact points* (Schwartz–Zippel). A residual
   function is evaluated with exact rationals at ``count`` points drawn from
   :mod:`symbolic.exact.points`; a non-zero rational polynomial of degree $d$ vanishes at a random point
   of $S^m$ with probability $\le d/|S|$. Used where the symbolic object is too large (general
   $n$ up to 12, where $\Omega = L_\gamma^{-1} M$ is an exact linear solve at the point).

A false identity always comes back with an exact :class:`Counterexample`: a rational point
inside the stated domain (on the sphere where asked) and the exact non-zero value there.

Two engines. Every zero test above is decided by SymPy (its sparse polynomials / ``DomainMatrix``)
and, independently, by FLINT (:mod:`symbolic.exact.flint_engine`: the SymPy-built expression read by a
tree walk into ``fmpq_mpoly``, ``divmod`` by the sphere polynomial, ``fmpq_mat`` at points). The
two must agree — on the verdict, and at a counterexample on its exact value — or
:class:`~symbolic.exact.flint_engine.EngineDisagreement` is raised (an ``error`` row). Each check records
which engines decided it (:func:`engine_tally`); the ledger prints it in the row's method.
``CHAPLYGIN_ND_ENGINES=flint`` makes SymPy abstain (the FLINT-only mutation run).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from random import Random

import flint
import sympy as sp
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.counterexample import Counterexample
from chaplygin_nd.symbolic.exact.flint_engine import (
    EngineDisagreement,
    FlintRing,
    active_engines,
    engine_label,
    linear_algebra_calls,
    to_fmpq,
    use_engine,
)
from chaplygin_nd.symbolic.exact.sympy_fraction import reduced_fraction
from chaplygin_nd.symbolic.exact.tally import (  # noqa: F401  (re-exported: the runner reads them here)
    dimension,
    engine_note,
    engine_tally,
    point_timings,
    record,
    reset_engine_tally,
    timing,
)
from sympy.polys.fields import field as fraction_field
from sympy.polys.orderings import lex
from sympy.polys.rings import PolyElement

__all__ = [
    "Check", "Counterexample", "rational_identity", "zero_at_points", "exact_zero",
    "numerator_polynomial", "Sampler", "engine_tally", "reset_engine_tally", "engine_note",
    "SYMPY_POINT_MAX_N", "SYMPY_INVERSE_MAX_N", "point_engines", "point_timings",
]

#: Above this n the seeded point checks are decided by FLINT alone (SymPy's dense QQ linear
#: algebra grows as n^4..n^6: its n = 24 determinant took 46 s); at and below it, by both.
SYMPY_POINT_MAX_N = 12


#: For the rows whose point step is a full exact inverse of L_gamma (SymPy's costs grow as n^6:
#: 5.5 s at n = 12 for one divergence point under load), SymPy decides up to this n.
SYMPY_INVERSE_MAX_N = 8


def point_engines(n: int, sympy_max: int | None = None) -> tuple[str, ...]:
    """The engines of a seeded point check at dimension ``n``: both up to ``sympy_max``
    (default :data:`SYMPY_POINT_MAX_N`), FLINT alone above."""
    top = SYMPY_POINT_MAX_N if sympy_max is None else min(sympy_max, SYMPY_POINT_MAX_N)
    return ("sympy", "flint") if n <= top else ("flint",)

#: A sampler draws one exact value (number or matrix) for one symbol or name.
Sampler = Callable[[Random], sp.Expr]


@dataclass(frozen=True)
class Check:
    """The outcome of one exact check. Truthy iff the identity holds."""

    ok: bool
    method: str
    counterexample: Counterexample | None = None
    seconds: float = field(default=0.0, compare=False)
    #: which engines decided it ("SymPy+FLINT", "FLINT"); empty for a check made by a proof itself
    engines: str = field(default="", compare=False)

    def __bool__(self) -> bool:
        return self.ok


# --------------------------------------------------------------------------------------------
# Route 1: rational-function identity, optionally modulo ||gamma||^2 = 1.
# --------------------------------------------------------------------------------------------

def _entry(e):
    return e if isinstance(e, PolyElement) else sp.sympify(e)


def _entries(expr) -> list[tuple[str, sp.Expr | PolyElement]]:
    if isinstance(expr, sp.MatrixBase):
        return [(f"entry ({i + 1}, {j + 1})", expr[i, j])
                for i in range(expr.rows) for j in range(expr.cols)]
    if isinstance(expr, (list, tuple)):
        return [(f"component {i + 1}", _entry(e)) for i, e in enumerate(expr)]
    return [("", _entry(expr))]


def _free_symbols(entries: Iterable[tuple[str, sp.Expr]]) -> set[sp.Symbol]:
    out: set[sp.Symbol] = set()
    for _, e in entries:
        out |= set(e.ring.symbols) if isinstance(e, PolyElement) else e.free_symbols
    return out


def _ordered_gens(symbols: set[sp.Symbol], sphere: Sequence[sp.Symbol] | None) -> list[sp.Symbol]:
    rest = sorted(symbols - set(sphere or ()), key=sp.default_sort_key)
    if not sphere:
        return rest
    # Pivot first, so that lex makes pivot**2 the leading monomial of the sphere polynomial.
    pivot, *others = list(sphere)[::-1]
    return [pivot, *others, *rest]


def numerator_polynomial(expr: sp.Expr, gens: Sequence[sp.Symbol],
                         sphere: Sequence[sp.Symbol] | None = None):
    r"""The numerator of ``expr`` in $\mathbb{Q}[\text{gens}]$ (sparse ``PolyElement``), reduced modulo
    $\sum \gamma_i^2 - 1$ when ``sphere`` is given, and the denominator. ``gens`` must start with
    the sphere pivot (see :func:`rational_identity`). Raises ``ValueError`` if ``expr`` is not a
    rational function of ``gens`` with rational coefficients."""
    K, *_ = fraction_field(list(gens), sp.QQ, lex)
    try:
        f = reduced_fraction(K, expr)   # = K.from_expr(expr), one cancellation instead of one per node
    except Exception as err:  # CoercionFailed / GeneratorsError: not a rational function
        raise ValueError(f"not a rational function over Q of {list(gens)}: {err}") from err
    num, den = f.numer, f.denom
    if sphere:
        R = num.ring
        g = R(sum(s**2 for s in sphere) - 1)
        num = num.rem(g)
    return num, den


def rational_identity(residual, *, sphere: Sequence[sp.Symbol] | None = None,
                      samplers: Mapping[sp.Symbol, Sampler] | None = None,
                      seed: int | None = None, label: str = "") -> Check:
    r"""Prove ``residual == 0`` as an identity of rational functions over $\mathbb{Q}$, or refute it.

    ``residual``: a SymPy expression, a matrix, or a list of expressions or of sparse polynomials
    (``PolyElement`` of a SymPy ``ring`` over QQ: reduced in their own ring, which is much faster
    than converting large expanded polynomials through SymPy expressions).
    ``sphere``: symbols $\gamma_1..\gamma_n$ with the identity claimed on $\lVert\gamma\rVert = 1$.
    ``samplers``: for the counterexample search only, how to draw each parameter (e.g. $a \in
    [-1,1]$, $b > 0$); other symbols are drawn from small rationals, sphere symbols on $S^{n-1}$.
    ``seed``: of the counterexample search; default :func:`symbolic.exact.points.ledger_seed`.
    """
    start = time.perf_counter()
    seed = points.ledger_seed() if seed is None else seed
    entries = _entries(residual)
    symbols = _free_symbols(entries)
    if sphere and not set(sphere) <= symbols:
        symbols |= set(sphere)
    gens = _ordered_gens(symbols, sphere)
    where_sphere = f" modulo ||{','.join(map(str, sphere))}||^2 = 1" if sphere else ""
    method = (f"exact rational-function identity in {len(gens)} variables{where_sphere}" if gens
              else "exact: the residual expands to zero")
    engines = active_engines()
    ring = FlintRing(gens, sphere) if "flint" in engines else None
    who = engine_label(engines)
    spent = dict.fromkeys(engines, 0.0)
    for where, e in entries:
        sympy_cx = flint_cx = None
        if "sympy" in engines:
            t0 = time.perf_counter()
            sympy_cx = _sympy_entry(e, gens, sphere, samplers or {}, seed, label, where)
            spent["sympy"] += time.perf_counter() - t0
        if ring is not None:
            t0 = time.perf_counter()
            flint_cx = _flint_entry(ring, e, gens, sphere, samplers or {}, seed, label, where,
                                    check_at=sympy_cx)
            spent["flint"] += time.perf_counter() - t0
        if "sympy" in engines and ring is not None and (sympy_cx is None) != (flint_cx is None):
            raise EngineDisagreement(
                f"{label or 'identity'} {where}: SymPy says "
                f"{'holds' if sympy_cx is None else 'fails'}, FLINT says "
                f"{'holds' if flint_cx is None else 'fails'}")
        cx = sympy_cx if "sympy" in engines else flint_cx
        if cx is not None:
            record("identity", who, label, len(gens), spent)
            return Check(False, method, cx, time.perf_counter() - start, engines=who)
    record("identity", who, label, len(gens), spent)
    return Check(True, method, None, time.perf_counter() - start, engines=who)


def _sympy_entry(e, gens, sphere, samplers, seed, label, where) -> Counterexample | None:
    """SymPy's decision on one entry: None if it vanishes (on the sphere), else a counterexample."""
    if isinstance(e, PolyElement):
        # Already a sparse polynomial: reduce it in its own ring. {g} is a Groebner basis of
        # (g) for every monomial order, so the remainder criterion is the same as above.
        ring_gens = list(e.ring.symbols)
        num = e.rem(e.ring(sum(s**2 for s in sphere) - 1)) if sphere else e
        if num:
            return _counterexample(e, num, e.ring.one, ring_gens, sphere, samplers, seed,
                                   label, where)
        return None
    if not gens:
        return Counterexample((), e, where) if sp.expand(e) != 0 else None
    num, den = numerator_polynomial(e, gens, sphere)
    if num:
        return _counterexample(e, num, den, gens, sphere, samplers, seed, label, where)
    return None


def _flint_entry(ring: FlintRing, e, gens, sphere, samplers, seed, label, where,
                 check_at: Counterexample | None) -> Counterexample | None:
    """FLINT's decision on one entry (the expression read by a tree walk, its numerator reduced
    by ``divmod``): None if it vanishes, else a counterexample. At SymPy's counterexample
    ``check_at`` the exact value must be the same in both engines."""
    if isinstance(e, PolyElement):
        num, den = ring.from_ring_element(e), ring.one
    else:
        num, den = ring.fraction(e)
    normal = ring.decide(num, den)
    if normal.is_zero():
        return None
    if check_at is not None:
        named = dict(check_at.point)
        point = {s: named[str(s)] for s in gens}
        try:
            mine = ring.value(num, den, point)
        except ZeroDivisionError:  # FLINT's uncancelled denominator vanishes there: no value
            return check_at
        if mine != to_fmpq(check_at.residual):
            raise EngineDisagreement(f"{label or 'identity'} {where}: at SymPy's counterexample "
                                     f"SymPy's residual is {check_at.residual}, FLINT's {mine}")
        return check_at
    return _flint_counterexample(ring, num, den, normal, gens, sphere, samplers, seed, label,
                                 where)


def _flint_counterexample(ring, num, den, normal, gens, sphere, samplers, seed, label, where
                          ) -> Counterexample:
    """The same seeded search as :func:`_counterexample`, every value computed in fmpq."""
    rng = points.generator(seed, "counterexample", label, where)
    sphere = list(sphere or ())
    for attempt in range(400):
        values: dict[sp.Symbol, sp.Expr] = {}
        if sphere:
            values.update(zip(sphere, points.sphere_point(rng, len(sphere))))
        for s in gens:
            if s in values:
                continue
            draw = samplers.get(s)
            values[s] = draw(rng) if draw else points.rational(rng, -2, 2, 4 + attempt // 20)
        args = {s: to_fmpq(values[s]) for s in gens}
        if not gens:
            value = ring.value(num, den, {})
            return Counterexample((), sp.Rational(int(value.p), int(value.q)), where)
        at = [args[s] for s in gens]
        if den(*at) == 0 or normal(*at) == 0:
            continue
        value = num(*at) / den(*at)
        pt = tuple((str(s), values[s]) for s in gens)
        return Counterexample(pt, sp.Rational(int(value.p), int(value.q)), where)
    raise RuntimeError("normal form is non-zero but no rational point found a non-zero value")


def _counterexample(expr, num, den, gens, sphere, samplers, seed, label, where) -> Counterexample:
    rng = points.generator(seed, "counterexample", label, where)
    sphere = list(sphere or ())
    for attempt in range(400):
        values: dict[sp.Symbol, sp.Expr] = {}
        if sphere:
            gamma = points.sphere_point(rng, len(sphere))
            values.update(zip(sphere, gamma))
        for s in gens:
            if s in values:
                continue
            draw = samplers.get(s)
            values[s] = draw(rng) if draw else points.rational(rng, -2, 2, 4 + attempt // 20)
        args = [values[s] for s in gens]
        if den(*args) == 0 or num(*args) == 0:
            continue
        if isinstance(expr, PolyElement):
            value = sp.Rational(expr.ring.domain.to_sympy(expr(*args)))
        else:
            value = sp.expand(sp.sympify(expr).xreplace(values))
        if value == 0:  # the reduced numerator is not zero here but the residual is: impossible
            raise AssertionError("inconsistent reduction; please report")
        pt = tuple((str(s), values[s]) for s in gens)
        return Counterexample(pt, value, where)
    raise RuntimeError("numerator is non-zero but no rational point found a non-zero value")


# --------------------------------------------------------------------------------------------
# Route 2: exact evaluation at seeded random rational points.
# --------------------------------------------------------------------------------------------

def exact_zero(value) -> tuple[bool, str, object]:
    """Whether an exact value (number, matrix, or list) is zero; returns (zero, where, entry).

    Raises ``TypeError`` on a float: evidence at points must be exact."""
    for where, e in _entries(value):
        if e.has(sp.Float):
            raise TypeError(f"inexact value {e} {where}: points must carry exact rationals")
        if e != 0 and sp.expand(e) != 0:
            return False, where, e
    return True, "", 0


def _fmpq_entries(value) -> list:
    """The entries of an exact value as FLINT rationals (``TypeError`` on a float); an
    ``fmpq_mat`` (a value computed by the FLINT engine) is read directly."""
    if isinstance(value, flint.fmpq_mat):
        return [(f"entry ({i + 1}, {j + 1})", value[i, j], value[i, j])
                for i in range(value.nrows()) for j in range(value.ncols())]
    out = []
    for where, e in _entries(value):
        if isinstance(e, PolyElement):
            raise TypeError(f"a point value must be a number, not a polynomial ({where})")
        if e.has(sp.Float):
            raise TypeError(f"inexact value {e} {where}: points must carry exact rationals")
        out.append((where, e, e if e.is_Rational else None))
    ring = None
    values = []
    for where, e, rational in out:
        if rational is not None:
            values.append((where, e, to_fmpq(rational)))
            continue
        ring = ring or FlintRing([])
        num, den = ring.fraction(e)
        values.append((where, e, ring.value(num, den, {})))
    return values


def zero_at_points(residual: Callable[[dict], object], sample: Callable[[Random], dict], *,
                   count: int, seed: int | None = None, label: str,
                   describe: str = "", engines: Sequence[str] = ("sympy", "flint")) -> Check:
    r"""Evaluate ``residual(point)`` exactly at ``count`` seeded points ``sample(rng)``; it must be 0.

    ``sample`` returns a dict name -> exact value (numbers, vectors, matrices); ``residual``
    returns an exact number, matrix or list. ``describe`` names the space sampled (for the
    method string). A non-zero value stops the check and becomes the counterexample. ``seed``:
    default :func:`symbolic.exact.points.ledger_seed` (the seed of the ledger run).

    ``engines``: who evaluates. The residual runs once per engine inside
    :func:`~symbolic.exact.flint_engine.use_engine`, so its exact linear algebra (``solve``, ``det``,
    ``rank``, ``inverse`` of :mod:`symbolic.exact.flint_engine`) is SymPy's ``DomainMatrix`` in one run
    and FLINT's ``fmpq_mat`` in the other; SymPy tests its value with ``expand``, FLINT converts
    it to ``fmpq``; the two values must be equal. A residual that makes no such call is evaluated
    once (the value is the same SymPy arithmetic) and tested by both. Engines not active in this
    process (``CHAPLYGIN_ND_ENGINES``) abstain; if none of ``engines`` is active, the active ones
    decide.
    """
    start = time.perf_counter()
    seed = points.ledger_seed() if seed is None else seed
    method = f"exact at {count} seeded rational points{' of ' + describe if describe else ''} (seed {seed})"
    active = active_engines()
    engines = tuple(e for e in engines if e in active) or active
    who = engine_label(engines)
    for i in range(count):
        rng = points.generator(seed, label, i)
        pt = sample(rng)
        value = _evaluate(residual, pt, engines, label)
        record("points", who)
        zero, where, entry = value
        if not zero:
            cx = Counterexample(tuple(pt.items()), entry, where)
            return Check(False, method, cx, time.perf_counter() - start, engines=who)
    return Check(True, method, None, time.perf_counter() - start, engines=who)


def _evaluate(residual, pt, engines, label) -> tuple[bool, str, object]:
    """(zero, where, first non-zero entry) of ``residual(pt)``, decided by each engine; with
    both engines the two values must be equal entry by entry."""
    values, value, reuse, n = {}, None, False, dimension(pt)
    decided: dict = {}
    for engine in engines:
        t0 = time.perf_counter()
        if not reuse:
            before = linear_algebra_calls()
            with use_engine(engine):
                value = residual(pt)
            reuse = linear_algebra_calls() == before
        values[engine] = value
        if engine == "sympy":
            decided["sympy"] = exact_zero(value)
        else:
            flint_values = _fmpq_entries(value)
        timing("points", label, n, engine, time.perf_counter() - t0)
    if "flint" in values:
        bad = next(((w, sp.Rational(int(v.p), int(v.q))) for w, _, v in flint_values if v != 0),
                   None)
        decided["flint"] = (True, "", 0) if bad is None else (False, *bad)
        if "sympy" in values:
            same = values["sympy"] is values["flint"] or (
                [v for _, _, v in _fmpq_entries(values["sympy"])]
                == [v for _, _, v in flint_values])
            if decided["sympy"][0] != decided["flint"][0] or not same:
                raise EngineDisagreement(
                    f"{label}: SymPy says zero={decided['sympy'][0]}, FLINT says "
                    f"zero={decided['flint'][0]}" + ("" if same else "; the values differ"))
    return decided["sympy" if "sympy" in decided else "flint"]
