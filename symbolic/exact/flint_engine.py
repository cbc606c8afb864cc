r"""The second exact engine: FLINT (python-flint), independent of SymPy's polynomial code.

Every exact zero test of :mod:`symbolic.exact.identity` is decided twice: by SymPy (its sparse
polynomials, as before) and here, by FLINT. The expression itself is *built by SymPy* (the
derivations are SymPy code); this module reads it by walking the expression tree directly —
``Add``, ``Mul``, ``Pow`` with an integer exponent, ``Symbol``, ``Integer``, ``Rational`` — into
FLINT's multivariate rationals ``fmpq_mpoly`` (a numerator and a denominator), never through
``sympy.Poly`` or SymPy's rings. Anything else (a float, ``sqrt``, ``pi``, a function) is not a
rational function over $\mathbb{Q}$ and raises ``ValueError``, as on the SymPy side.

The normal form modulo the sphere. The context orders the generators with the sphere pivot
$\gamma_p$ first and uses the **lex** order, so the leading monomial of
$g = \gamma_1^2 + \dots + \gamma_n^2 - 1$ is $\gamma_p^2$. A single polynomial is a Gröbner basis of
the ideal it generates (its only S-pair is with itself), so the remainder of the division of the
numerator by $g$ — FLINT's ``divmod``, whose remainder has no term divisible by the leading
monomial $\gamma_p^2$ — is the unique normal form of the numerator modulo $(g)$ for this order;
it is zero iff the numerator lies in $(g)$, i.e. (the ideal is prime, its real points Zariski
dense) iff the identity holds on the real sphere. The denominator must not lie in $(g)$ (else the
expression is undefined on the sphere): that is checked the same way and raises ``ValueError``.

Exact linear algebra at rational points (the heavy steps of the point checks for large $n$):
:func:`solve`, :func:`det`, :func:`rank`, :func:`inverse` take SymPy matrices of rationals and
run in the engine selected by :func:`use_engine` — SymPy's ``DomainMatrix`` over ``QQ`` or FLINT's
``fmpq_mat`` — so one residual function is evaluated by each engine in turn
(:func:`symbolic.exact.identity.zero_at_points`).

Which engines run: both, unless the environment variable ``CHAPLYGIN_ND_ENGINES`` says
``flint`` (SymPy abstains: ``chaplygin mutate --engines flint``) or ``sympy`` (FLINT abstains; a
comparison mode for the bench only).
"""

from __future__ import annotations

import contextlib
import contextvars
import os
from collections.abc import Sequence

import flint
import sympy as sp
from sympy.polys.matrices import DomainMatrix

__all__ = [
    "ENGINES_ENV", "EngineDisagreement", "active_engines", "engine_label", "sympy_ground_types", "FlintRing",
    "use_engine", "current_engine", "solve", "det", "rank", "inverse", "to_fmpq",
    "linear_algebra_calls", "note_call", "to_sympy_matrix", "native", "as_values",
]

ENGINES_ENV = "CHAPLYGIN_ND_ENGINES"
_NAMES = {"sympy": "SymPy", "flint": "FLINT"}


class EngineDisagreement(RuntimeError):
    """SymPy and FLINT decided one exact zero test differently: the run cannot be right."""


def active_engines() -> tuple[str, ...]:
    """The engines that decide zero tests in this process: ``("sympy", "flint")`` unless
    ``CHAPLYGIN_ND_ENGINES`` is ``flint`` or ``sympy``; any other value raises ``ValueError``."""
    value = os.environ.get(ENGINES_ENV, "both").strip().lower()
    if value in ("", "both", "sympy+flint"):
        return ("sympy", "flint")
    if value in ("flint", "sympy"):
        return (value,)
    raise ValueError(f"{ENGINES_ENV}={value!r}: expected both, flint or sympy")


def engine_label(engines: Sequence[str]) -> str:
    """``("sympy", "flint")`` -> ``"SymPy+FLINT"``; says so when SymPy itself runs on FLINT's
    ground types (``SYMPY_GROUND_TYPES=flint``: then the two engines are not independent)."""
    label = "+".join(_NAMES[e] for e in engines)
    if "sympy" in engines and sympy_ground_types() == "flint":
        label += " (SymPy on flint ground types: not independent)"
    return label


def sympy_ground_types() -> str:
    """SymPy's ground types in this process (``gmpy``, ``flint`` or ``python``)."""
    from sympy.external.gmpy import GROUND_TYPES
    return GROUND_TYPES


# --------------------------------------------------------------------------------------------
# Rational functions: a SymPy expression tree -> (numerator, denominator) in fmpq_mpoly.
# --------------------------------------------------------------------------------------------

def to_fmpq(value) -> flint.fmpq:
    """An exact SymPy number (``Integer``/``Rational``, or a Python int) as ``fmpq``;
    ``TypeError`` on a float, ``ValueError`` on anything that is not a rational number."""
    if isinstance(value, flint.fmpq):
        return value
    if isinstance(value, sp.Rational):
        return flint.fmpq(int(value.p), int(value.q))
    if isinstance(value, int):
        return flint.fmpq(value)
    value = sp.sympify(value)
    if value.has(sp.Float):
        raise TypeError(f"inexact value {value}: exact checks need rationals")
    if not value.is_Rational:
        value = sp.expand(value)
        if not value.is_Rational:
            raise ValueError(f"not a rational number: {value}")
    return flint.fmpq(int(value.p), int(value.q))


class FlintRing:
    r"""$\mathbb{Q}[x_1, \dots, x_m]$ in FLINT, lex order, generators in the given order (the sphere
    pivot first when a sphere is given), with a tree-walking reader of SymPy expressions."""

    def __init__(self, gens: Sequence[sp.Symbol], sphere: Sequence[sp.Symbol] | None = None):
        self.gens = list(gens)
        self.index = {s: i for i, s in enumerate(self.gens)}
        names = tuple(f"x{i}" for i in range(len(self.gens))) or ("x0",)
        self.ctx = flint.fmpq_mpoly_ctx.get(names, "lex")
        self.vars = self.ctx.gens()
        self.zero, self.one = self.ctx.from_dict({}), self.ctx.constant(1)
        self.sphere = None
        if sphere:
            self.sphere = sum((self.vars[self.index[s]] ** 2 for s in sphere), self.zero) - 1

    # -- reading ------------------------------------------------------------------------------
    def fraction(self, expr) -> tuple[flint.fmpq_mpoly, flint.fmpq_mpoly]:
        """(numerator, denominator) of a SymPy expression, by walking its tree."""
        memo: dict = {}
        return self._walk(sp.sympify(expr), memo)

    def _walk(self, e, memo):
        hit = memo.get(e)
        if hit is not None:
            return hit
        if e.is_Symbol:
            if e not in self.index:
                raise ValueError(f"symbol {e} is not one of the generators")
            out = (self.vars[self.index[e]], self.one)
        elif e.is_Rational:
            out = (self.ctx.constant(flint.fmpq(int(e.p), int(e.q))), self.one)
        elif e.is_Add:
            out = self._add([self._walk(t, memo) for t in e.args])
        elif e.is_Mul:
            num, den = self.one, self.one
            for t in e.args:
                n, d = self._walk(t, memo)
                num, den = num * n, den * d
            out = (num, den)
        elif e.is_Pow and e.exp.is_Integer:
            n, d = self._walk(e.base, memo)
            k = int(e.exp)
            if k < 0:
                if n.is_zero():
                    raise ValueError(f"division by zero in {e}")
                n, d, k = d, n, -k
            out = (n ** k, d ** k)
        elif isinstance(e, sp.Float):
            raise ValueError(f"inexact number {e}: not a rational function over Q")
        else:
            raise ValueError(f"not a rational function over Q: {type(e).__name__} in {e}")
        memo[e] = out
        return out

    def _add(self, terms):
        poly = self.zero
        groups: list[list] = []  # [denominator, numerator sum]
        for n, d in terms:
            if d.is_one():
                poly += n
                continue
            for group in groups:
                if group[0] == d:
                    group[1] += n
                    break
            else:
                groups.append([d, n])
        if not groups:
            return poly, self.one
        den = groups[0][0]
        for d, _ in groups[1:]:
            den = den * (d / den.gcd(d))   # lcm, by exact division
        num = poly * den
        for d, n in groups:
            num += n * (den / d)
        return num, den

    def from_ring_element(self, element) -> flint.fmpq_mpoly:
        """A SymPy ``PolyElement`` over QQ (built by SymPy ring arithmetic), term by term."""
        pos = [self.index[s] for s in element.ring.symbols]
        width = len(self.gens)
        terms = {}
        for monom, coeff in element.terms():
            exps = [0] * width
            for i, k in zip(pos, monom):
                exps[i] = k
            terms[tuple(exps)] = flint.fmpq(int(coeff.numerator), int(coeff.denominator))
        return self.ctx.from_dict(terms)

    # -- deciding -----------------------------------------------------------------------------
    def normal_form(self, poly: flint.fmpq_mpoly) -> flint.fmpq_mpoly:
        """The remainder of ``poly`` modulo the sphere polynomial (itself without a sphere)."""
        if self.sphere is None:
            return poly
        return divmod(poly, self.sphere)[1]

    def decide(self, num, den) -> flint.fmpq_mpoly:
        """The normal form of the numerator (zero iff the identity holds); ``ValueError`` when
        the denominator vanishes identically (on the sphere)."""
        if self.normal_form(den).is_zero():
            raise ValueError("the denominator vanishes identically (on the sphere): "
                             "the residual is undefined there")
        return self.normal_form(num)

    def value(self, num, den, point: dict) -> flint.fmpq:
        """``num/den`` at an exact point (``point``: symbol -> rational), in fmpq."""
        args = [to_fmpq(point[s]) for s in self.gens] if self.gens else [flint.fmpq(0)]
        d = den(*args)
        if d == 0:
            raise ZeroDivisionError("denominator vanishes at the point")
        return num(*args) / d


# --------------------------------------------------------------------------------------------
# Exact linear algebra at rational points, in the engine of the current evaluation.
# --------------------------------------------------------------------------------------------

_ENGINE: contextvars.ContextVar[str] = contextvars.ContextVar("exact_engine", default="sympy")
_CALLS = {"count": 0}


@contextlib.contextmanager
def use_engine(name: str):
    """Within this block :func:`solve`, :func:`det`, :func:`rank`, :func:`inverse` run in
    ``name`` (``"sympy"``: ``DomainMatrix`` over QQ; ``"flint"``: ``fmpq_mat``)."""
    if name not in _NAMES:
        raise ValueError(f"unknown engine {name!r}")
    token = _ENGINE.set(name)
    try:
        yield
    finally:
        _ENGINE.reset(token)


def current_engine() -> str:
    """The engine :func:`solve` and friends use now."""
    return _ENGINE.get()


def note_call() -> None:
    """Count one engine-dispatched exact computation (see :func:`linear_algebra_calls`); for
    dispatching functions outside this module (``model.angular_velocity``, ...)."""
    _CALLS["count"] += 1


def linear_algebra_calls() -> int:
    """How many engine-dispatched linear-algebra calls this process made (a residual that makes
    none gives the same value in both engines, so it is evaluated once)."""
    return _CALLS["count"]


def _fmpq_mat(A) -> flint.fmpq_mat:
    if isinstance(A, flint.fmpq_mat):
        return A
    if isinstance(getattr(A, "mat", None), flint.fmpq_mat):  # a flint_matrix.FlintMatrix
        return A.mat
    if isinstance(A, DomainMatrix):
        A = A.to_Matrix()
    # the non-zero entries only (todok), not A[i, j] one by one: SymPy's item access dominated
    # the conversion of the sparse n(n-1)/2-square matrices of the all-n rows
    out = flint.fmpq_mat(A.rows, A.cols)
    for (i, j), v in A.todok().items():
        out[i, j] = to_fmpq(v)
    return out


def to_sympy_matrix(X: flint.fmpq_mat) -> sp.Matrix:
    """An ``fmpq_mat`` as a SymPy matrix of ``Rational``."""
    return sp.Matrix(X.nrows(), X.ncols(),
                     [sp.Rational(int(v.p), int(v.q)) for row in X.tolist() for v in row])


def _qq(A) -> DomainMatrix:
    if isinstance(A, DomainMatrix):
        return A.convert_to(sp.QQ)
    return DomainMatrix.from_Matrix(A).convert_to(sp.QQ)


def native(A):
    """A rational matrix in the current engine's own type: ``DomainMatrix`` over QQ (SymPy) or
    ``fmpq_mat`` (FLINT). Arithmetic (``+ - *``) on natives stays in that engine."""
    return _fmpq_mat(A) if current_engine() == "flint" else _qq(A)


def as_values(X):
    """A native matrix as the value of a point residual: ``fmpq_mat`` stays (FLINT's zero test
    reads it directly), a ``DomainMatrix`` becomes a SymPy matrix."""
    return X.to_Matrix() if isinstance(X, DomainMatrix) else X


def solve(A: sp.Matrix, B: sp.Matrix) -> sp.Matrix:
    r"""$X$ with $AX = B$ for an invertible square rational $A$ (exact)."""
    _CALLS["count"] += 1
    if current_engine() == "flint":
        return to_sympy_matrix(_fmpq_mat(A).solve(_fmpq_mat(B)))
    return _qq(A).lu_solve(_qq(B)).to_Matrix()


def det(A: sp.Matrix) -> sp.Rational:
    r"""$\det A$ of a square rational matrix (exact)."""
    _CALLS["count"] += 1
    if current_engine() == "flint":
        # clear denominators: fmpz_mat.det is multimodular (FLINT's fmpq_mat.det was 10x slower
        # on L_gamma at n = 24); det(A) = det(N) / d^rows for A = N/d
        Aq = _fmpq_mat(A)
        N, d = Aq.numer_denom()
        value = flint.fmpq(N.det()) / flint.fmpq(d) ** Aq.nrows()
        return sp.Rational(int(value.p), int(value.q))
    return sp.QQ.to_sympy(_qq(A).det())


def rank(A: sp.Matrix) -> int:
    """The rank over QQ of a rational matrix (exact)."""
    _CALLS["count"] += 1
    if current_engine() == "flint":
        return _fmpq_mat(A).rank()
    return _qq(A).rank()


def inverse(A: sp.Matrix) -> sp.Matrix:
    r"""$A^{-1}$ of an invertible square rational matrix (exact)."""
    _CALLS["count"] += 1
    if current_engine() == "flint":
        return to_sympy_matrix(_fmpq_mat(A).inv())
    return _qq(A).inv().to_Matrix()
