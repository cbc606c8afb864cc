r"""Beyond the paper: a sixth integral for $n = 5$, and with it the paper's open problem for $n = 5$
(row S6:sixth-integral-n5).

**Claim.** For the axisymmetric sphere in dimension $n = 5$ (any $a$, $b$ with $\Delta \ne 0$), with
$w = \star(M\wedge M)/2$ (the Pfaffians of the $4\times4$ principal minors of $M$, signed so that $Mw = 0$)
and $B = aE_5E_5^T + b\gamma\gamma^T$ (so $L_\gamma(\Omega) = 2\Omega + B\Omega + \Omega B$),

.. math::
    F = \frac{\langle w, B(2+B)w\rangle}{\Delta(x)} = \frac{a(a+2)\langle w,E_5\rangle^2
        + 2abx\langle w,E_5\rangle\langle w,\gamma\rangle + b(b+2)\langle w,\gamma\rangle^2}{(2+a)(2+b)-abx^2}

is a first integral of eq:motion-general on $P = \mathfrak{so}(5)\times S^4$, invariant under $SO(4)$ and,
for $a \ne 0$, independent of the five known integrals (the non-constant coefficients of
$p(\lambda, \sigma)$ and $H$). At $a = 0$ (spherical tensor) $F = \tfrac b2\langle w,\gamma\rangle^2 = \tfrac b2 c_{\sigma\lambda^0}$.

**Proved here.** (1) $\Delta\,D\dot N_F - N_F\,D\dot\Delta = 0$ on $P$ for symbolic $a, b$ ($N_F = \Delta F$,
$D\dot{}$ along the derived field with $D = 2(2+a+b)\Delta$): a sparse-polynomial identity modulo
$\lVert\gamma\rVert^2 = 1$, SymPy and FLINT. (2) $N_F$ is a polynomial in the $SO(4)$-invariants of
S6:reduced-n5 (exact ansatz) and composing back gives $N_F$ on $P$ (both engines): $F$ descends to
$P/SO(4)$. (3) At a seeded rational point the differentials of the five known integrals and $F$,
restricted to $TP$, have rank 6 (SymPy and FLINT). (4) The text form of ``verification.json`` equals
$F$ (both engines).

(5) The integral found by the exact search on $P$ (S6:first-integrals),
$F_s = \langle w, (2+a)E_5 + bx\gamma\rangle^2/\Delta$, satisfies $aF_s - (2+a)F = -b\langle w,\gamma\rangle^2$
(a known integral): the two routes found one and the same new integral.

**What follows** (row S6:euler-jacobi-n5): with the five known integrals, $F$ gives the $8 - 2 = 6$
integrals that Euler–Jacobi needs on the 8-dimensional $P/SO(4)$; that row computes the invariant
measure on the quotient, compactness and the independence there, and cites the theorem.

**How it was found.** simulate/analysis/integral_guide.py: on 10 drawn orbits at $(a, b) = (1/2, 2)$,
the $M$-degree-4 basis over $\Delta$ (numerator degree $\le 2$ in $x$) had a 5-dimensional orbit-constant
space against 4 expected (the relation $R_1$ and three known products), singular-value gap
$3.5\times10^{-6}$ to $10^{-15}$; exact null space over $\mathbb{Q}(a, b)$ of the ansatz
$\sum c_{ij}(A_+-A_-)^i(E_+-E_-)^{2-i}x^j$ was one-dimensional and gave $F$.

**Uses** eq:motion-general, P:inversion, eq:Delta, eq:pol-first-integrals, P:Measure, eq:action.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s6_open_reduced_n5 import _integral_gradients
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import Check, rational_identity
from chaplygin_nd.symbolic.exact.points import ledger_seed
from chaplygin_nd.symbolic.family import sixth_integral as si
from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5
from chaplygin_nd.symbolic.reduction import reduced_n5 as r5

SECTION = "Conclusions — open problems (beyond the paper)"
SPHERE = (*ri5.q, ri5.gamma[4])
_PAIRS = [(i, j) for i in range(5) for j in range(i + 1, 5)]


def _DX(f):
    r"""$D\dot f$ along the derived field on $P$ for ``f`` in :data:`symbolic.reduction.invariants_n5.RING`."""
    R = ri5.RING
    g = R.gens
    Mdot, gdot = r5.phase_field_numerators()
    tot = R(0)
    for k, pr in enumerate(_PAIRS):
        d = f.diff(g[3 + k])
        if d:
            tot += d * Mdot[pr]
    for k in range(4):
        d = f.diff(g[13 + k])
        if d:
            tot += d * gdot[k]
    d = f.diff(g[2])
    if d:
        tot += d * gdot[4]
    return tot


def conservation() -> Check:
    """Part (1): $\\Delta\\,D\\dot N_F - N_F\\,D\\dot\\Delta = 0$ on $P$ (both engines)."""
    N, Dl = si.numerator_ring(), si.Delta_ring()
    return rational_identity([Dl * _DX(N) - N * _DX(Dl)], sphere=SPHERE,
                             label="S6:sixth-integral-n5 dF/dt")


def descends() -> Check:
    """Part (2): $N_F$ in the invariants, composed back, equals $N_F$ on $P$ (both engines)."""
    back = ri5.to_phase_space(si.numerator_in_invariants()) - si.numerator_ring()
    return rational_identity([back], sphere=SPHERE, label="S6:sixth-integral-n5 invariants")


def independence() -> tuple[Check, dict]:
    """Part (3): rank 6 of the differentials of the five known integrals and $F$ on $TP$."""
    from chaplygin_nd.symbolic.exact import flint_engine

    rng = points.generator(ledger_seed(), "S6:sixth-integral-n5")
    gamma = points.sphere_point(rng, 5)
    M = points.skew_matrix(rng, 5)
    a, b = points.rational(rng, -1, 1), points.rational(rng, 1, 3)
    _coeffs, G = _integral_gradients(M, gamma, a, b)
    R = ri5.RING
    g = R.gens
    F = si.numerator_ring()
    Dl = si.Delta_ring()
    at = [a, b, gamma[4]] + [M[i, j] for i, j in _PAIRS] + list(gamma[:4])
    at = [sp.Rational(v) for v in at]

    def value(p):
        return sp.Rational(str(p(*at))) if p else sp.Integer(0)

    N0, D0 = value(F), value(Dl)
    order = [g[3 + k] for k in range(10)] + [g[13 + k] for k in range(4)] + [g[2]]
    grad = [(value(F.diff(v)) * D0 - N0 * value(Dl.diff(v))) / D0**2 for v in order]
    J = G.col_join(sp.Matrix([grad]))
    proj = sp.diag(sp.eye(10), sp.eye(5) - gamma * gamma.T)
    JT = J * proj
    r_sympy = JT.rank()
    with flint_engine.use_engine("flint"):
        r_flint = flint_engine.rank(JT)
    known = (G * proj).rank()
    ok = r_sympy == r_flint == 6 and known == 5
    return (Check(ok, f"rank on TP at a seeded rational point (a = {a}, b = {b}): known five "
                      f"{known}, with F: SymPy {r_sympy}, FLINT {r_flint}"),
            {"a": str(a), "b": str(b), "rank_known": known, "rank_with_F": r_sympy})


def same_as_search() -> Check:
    r"""Part (5): the integral the exact search finds (S6:first-integrals,
    :func:`symbolic.search.found_integral.new_integral`: $F_s = \langle w, (2+a)E_5 + bx\gamma\rangle^2/\Delta$) and $F$
    are one integral modulo the known ones: $aF_s - (2+a)F = -b\langle w,\gamma\rangle^2$ (the last is the
    known $c_{\sigma\lambda^0}$), a polynomial identity after multiplying by $\Delta$ (both engines).
    Two independent routes (the numerical guide with an ansatz in the invariants here, the
    mod-$p$ search on $P$ there) found it."""
    from chaplygin_nd.symbolic.search import found_integral

    N_search, Dl = found_integral.new_integral(ri5.M, ri5.gamma, r5.a, r5.b)
    N_here = si.numerator_expr(ri5.M, ri5.gamma, r5.a, r5.b)
    w = sp.Matrix(si.pfaffian_vector([[ri5.M[i, j] for j in range(5)] for i in range(5)]))
    L = (w.T * ri5.gamma)[0, 0]
    residual = r5.a * N_search - (2 + r5.a) * N_here + r5.b * L**2 * Dl
    return rational_identity([sp.expand(residual)], label="S6:sixth-integral-n5 = search's F")


def text_form() -> Check:
    """Part (4): the SymPy-parsable text of ``verification.json`` is $F$ (both engines)."""
    parsed = sp.sympify(si.integral_text(), locals={f"M_{i + 1}{j + 1}": ri5.M[i, j] for i, j in _PAIRS}
                        | {f"gamma_{i + 1}": ri5.gamma[i] for i in range(5)}
                        | {"a": r5.a, "b": r5.b})
    Dl = si.Delta_ring().as_expr()
    return rational_identity(parsed - si.numerator_ring().as_expr() / Dl, sphere=SPHERE,
                             label="S6:sixth-integral-n5 text")


@claim("S6:sixth-integral-n5", uses=("eq:motion-general", "P:inversion", "eq:Delta",
                                      "eq:pol-first-integrals", "P:Measure", "eq:action"),
       adds=(SECTION, "a sixth first integral of the axisymmetric n = 5 sphere, F = <w, B(2+B)w>/Delta "
                      "with w = *(M^M)/2 and B = a E_n E_n^T + b gamma gamma^T, proved exactly and "
                      "independent of the five known; the same integral as the exact search's "
                      "(S6:first-integrals), up to the known c_sigma_lambda0; what follows for the "
                      "reduced system: S6:euler-jacobi-n5"))
def s6_sixth_integral_n5() -> Verdict:
    indep, where = independence()
    parts = [Verdict.all_of([("dF/dt = 0 on P", conservation())], n_values=(5,)).as_part("first integral"),
             Verdict.all_of([("F descends", descends())], n_values=(5,)).as_part("SO(4)-invariant"),
             Verdict.all_of([("rank 6", indep)], n_values=(5,)).as_part("independent of the known five"),
             Verdict.all_of([("text", text_form())], n_values=(5,)).as_part("text form"),
             Verdict.all_of([("a F_search - (2+a) F = -b <w, gamma>^2", same_as_search())],
                            n_values=(5,)).as_part("the exact search's integral is this one")]
    notes = ("F = " + si.integral_text() + " ; in the reduced coordinates of S6:reduced-n5: "
             "Delta F = " + sp.sstr(sp.factor(si.numerator_in_invariants().as_expr()))
             + f"; independence point: {where}")
    return Verdict.of_parts(parts, n_values=(5,), notes=notes, method=(
        "exact: dF/dt = 0 as a sparse-polynomial identity modulo |gamma|^2 = 1 for symbolic a, b "
        "(SymPy and FLINT), invariant-theory normal form, exact Jacobian rank at a seeded rational "
        "point (SymPy and FLINT); the search's form of the integral by a polynomial identity"))
