r"""The axisymmetric field for any $n$ as an expression graph over any arithmetic (runtime around
``generated.expression_builders``).

:mod:`runtime.axisym` applies the generated NumPy kernels to batches of $n\times n$ arrays; this
module does the same assembly on *scalars of any kind* — heyoka expressions (to build a Taylor
integrator or a compiled function), floats or mpmath numbers (to test the assembly) — from the
generated builder of the derived coefficients $c_0..c_5$ (P:inversion):

.. math::
    \Omega = L_\gamma^{-1}M = c_0M + c_1(M\gamma)\wedge\gamma + c_2(ME_n)\wedge E_n + c_3(M\gamma)\wedge E_n
    + c_4(ME_n)\wedge\gamma + c_5\langle M\gamma, E_n\rangle\,\gamma\wedge E_n,

    \dot M = [M, \Omega], \quad \dot\gamma = -\Omega\gamma, \quad
    (\text{reconstruction}) \ \dot g = g\Omega, \ \dot c = r\,g\Omega\gamma \quad (\text{eq:motion-general}).

The field itself is assembled without the matrix $\Omega$, in $O(n^2)$ operations
(:func:`structured_field`, row S4:structured-field): $\dot M = \sum w_{ij}V_i\wedge V_j$,
$\dot\gamma = \sum u_iV_i$ over $V = (M^2\gamma, M^2E_n, M\gamma, ME_n, \gamma, E_n)$ with the generated
weights ``structured_field_weights`` — heyoka's decomposition is about $9n^2$ operations (216 at
$n = 4$, 9 456 at $n = 32$) where $M\Omega - \Omega M$ took $2n^3$ (69 535 at $n = 32$). Only the
reconstruction forms $\Omega$ (for $g\Omega$, which is $O(n^3)$ anyway).

Matrices are nested lists; a structural zero is the Python integer ``0`` and is never multiplied
(so the graph has no ``0*x`` nodes). ``ops`` supplies ``rational(p, q)`` and ``sqrt`` in the
target arithmetic (see :mod:`symbolic.codegen.builders`). The state order is that of
:class:`simulate.dynamics.field.FullField`: $\mathrm{vec}\,M$ (entries $i<j$, lexicographic), $\gamma$,
then $g$ row-major and $c$.
"""

from __future__ import annotations

from chaplygin_nd.generated import expression_builders as eb

__all__ = ["pairs", "unvec", "angular_velocity", "structured_field", "vector_field", "HeyokaArithmetic"]


def pairs(n: int) -> list[tuple[int, int]]:
    """The basis order of vec: $(i, j)$, $i<j$, lexicographic."""
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


def _zero(v) -> bool:
    return isinstance(v, int) and v == 0


def _mul(*factors):
    out = 1
    for f in factors:
        if _zero(f):
            return 0
        out = f if (isinstance(out, int) and out == 1) else out * f
    return out


def _sum(terms):
    terms = [t for t in terms if not _zero(t)]
    if not terms:
        return 0
    out = terms[0]
    for t in terms[1:]:
        out = out + t
    return out


def _neg(v):
    return 0 if _zero(v) else -v


def unvec(m, n: int) -> list[list]:
    """The skew $n\\times n$ matrix (nested lists) with vec-coordinates ``m``."""
    M = [[0] * n for _ in range(n)]
    for v, (i, j) in zip(m, pairs(n)):
        M[i][j] = v
        M[j][i] = _neg(v)
    return M


def _matvec(A, v):
    return [_sum(_mul(A[i][k], v[k]) for k in range(len(v))) for i in range(len(A))]


def _matmul(A, B):
    n = len(B)
    return [[_sum(_mul(A[i][k], B[k][j]) for k in range(n)) for j in range(len(B[0]))]
            for i in range(len(A))]


def angular_velocity(M, gamma, a, b, ops) -> list[list]:
    r"""$\Omega = L_\gamma^{-1}M$ (P:inversion) as a skew nested list; $M$ skew (nested lists),
    $\gamma$ on $S^{n-1}$, $x = \gamma_n$; domain $\Delta(x)(2+a+b) \ne 0$; any $n \ge 3$."""
    n = len(gamma)
    c = eb.inverse_coefficients(gamma[-1], a, b, ops)
    Mg = _matvec(M, gamma)
    Me = [M[i][n - 1] for i in range(n)]
    e = [0] * (n - 1) + [1]

    def wedge(u, v, i, j):
        return _sum([_mul(u[i], v[j]), _neg(_mul(v[i], u[j]))])

    Omega = [[0] * n for _ in range(n)]
    for i, j in pairs(n):
        w = _sum([_mul(c[0], M[i][j]), _mul(c[1], wedge(Mg, gamma, i, j)),
                  _mul(c[2], wedge(Me, e, i, j)), _mul(c[3], wedge(Mg, e, i, j)),
                  _mul(c[4], wedge(Me, gamma, i, j)), _mul(c[5], Mg[n - 1], wedge(gamma, e, i, j))])
        Omega[i][j] = w
        Omega[j][i] = _neg(w)
    return Omega


#: The vectors and pairs of the structured field (the order of ``structured_field_weights``,
#: symbolic.structured_field.VECTORS / PAIRS): V = (M^2 gamma, M^2 E_n, M gamma, M E_n, gamma, E_n).
STRUCTURED_VECTORS = 6
STRUCTURED_PAIRS = [(i, j) for i in range(STRUCTURED_VECTORS) for j in range(i + 1, STRUCTURED_VECTORS)]


def structured_field(M, gamma, a, b, ops) -> tuple[list, list]:
    r"""$(\dot M, \dot\gamma)$ of eq:motion-general in $O(n^2)$ operations (S4:structured-field):
    $\dot M = \sum_{i<j} w_{ij}V_i\wedge V_j$, $\dot\gamma = \sum_i u_iV_i$ with
    $V = (M^2\gamma, M^2E_n, M\gamma, ME_n, \gamma, E_n)$ (three matrix-vector products) and the
    generated weights. Returns ($\mathrm{vec}\,\dot M$, $\dot\gamma$); $M$ skew nested lists, any
    $n \ge 3$; domain as :func:`angular_velocity` (any $\gamma$, not only on the sphere)."""
    n = len(gamma)
    Mg = _matvec(M, gamma)
    Me = [M[i][n - 1] for i in range(n)]
    e = [0] * (n - 1) + [1]
    V = [_matvec(M, Mg), _matvec(M, Me), Mg, Me, list(gamma), e]
    gg = _sum([_mul(v, v) for v in gamma])
    weights = eb.structured_field_weights(gamma[-1], Mg[-1], gg, a, b, ops)
    w, u = weights[:len(STRUCTURED_PAIRS)], weights[len(STRUCTURED_PAIRS):]
    # Group the wedges by their second vector: sum_i w_ij V_i ^ V_j = A_j ^ V_j, A_j = sum_i w_ij V_i.
    grouped: dict[int, list] = {}
    for (i, j), wij in zip(STRUCTURED_PAIRS, w):
        if not _zero(wij):
            grouped.setdefault(j, []).append((wij, V[i]))
    A = {j: [_sum([_mul(wij, Vi[k]) for wij, Vi in terms]) for k in range(n)]
         for j, terms in grouped.items()}
    Mdot = [_sum([term for j in A for term in (_mul(A[j][p], V[j][q]), _neg(_mul(V[j][p], A[j][q])))])
            for p, q in pairs(n)]
    gdot = [_sum([_mul(ui, Vi[k]) for ui, Vi in zip(u, V) if not _zero(ui)]) for k in range(n)]
    return Mdot, gdot


def vector_field(m, gamma, a, b, ops, g=None, radius=None) -> list:
    r"""The right-hand side of eq:motion-general in the state order of FullField: $\mathrm{vec}[M, \Omega]$,
    $-\Omega\gamma$ (in the structured $O(n^2)$ form, :func:`structured_field`) and, when ``g``
    (nested $n\times n$) is given, $g\Omega$ row-major and $r\,g\Omega\gamma$. ``m``: vec-coordinates
    of $M$. Domain as :func:`angular_velocity`."""
    n = len(gamma)
    M = unvec(m, n)
    Mdot, gdot = structured_field(M, gamma, a, b, ops)
    out = Mdot + gdot
    if g is not None:
        Omega = angular_velocity(M, gamma, a, b, ops)
        gO = _matmul(g, Omega)
        out += [gO[i][j] for i in range(n) for j in range(n)]
        out += [_neg(_mul(radius, v)) for v in _matvec(g, gdot)]
    return out


class HeyokaArithmetic:
    """``ops`` of the builders for heyoka expressions at one precision: exact rationals in the
    integrator's floating-point type (``"double"``, ``"real128"`` or ``"real"`` with ``bits``)."""

    def __init__(self, hy, kind: str, bits: int):
        self.hy, self.kind, self.bits = hy, kind, bits
        self.sqrt = hy.sqrt

    def rational(self, p: int, q: int):
        """$p/q$ as a heyoka constant of the target type (rounded once, in that type)."""
        hy = self.hy
        if self.kind == "double":
            return hy.expression(p / q)
        if self.kind == "real128":
            return hy.expression(hy.real128(p) / hy.real128(q))
        return hy.expression(hy.real(p, self.bits) / hy.real(q, self.bits))
