r"""Beyond the paper: the reduced equations on $P/SO(4)$ for $n = 5$ (row S6:reduced-n5).

The paper's conclusion leaves open: "Obtain the reduced equations on $P/SO(n-1)$ for $n \ge 5$ and
determine if they are integrable." This row derives them for $n = 5$ (the first half), as eq:red-system
is derived for $n = 4$ (:mod:`symbolic.reduction.invariants_n5`, :mod:`symbolic.reduction.reduced_n5`).

**Claim.** With $M = \begin{pmatrix} K & u\\ -u^T & 0\end{pmatrix}$, $\gamma = (q, x)$, $K_\pm = K \pm \star K$,
$S = K_+K_-$, the ten functions
$x,\ A_\pm = -\tfrac14\operatorname{tr}K_\pm^2,\ B = \lVert u\rVert^2,\ G = \langle u,q\rangle,\ E_\pm = u^TK_\pm q,\
S_{uu} = u^TSu,\ S_{uq} = u^TSq,\ S_{qq} = q^TSq$ are $SO(4)$-invariant and

1. together with $s = \lVert q\rVert^2$ they *generate* the invariant polynomials of $(K, u, q)$ in every
   tridegree $(i, j, l)$ with $i \le 5$, $j \le 6$, $l \le 7$, $i + j + l \le 12$ — which contains every
   tridegree of the reduced field's numerators (character count = rank of the products modulo a
   prime at random points; FLINT and SymPy);
2. they satisfy exactly two relations up to tridegree $(4,2,2)$:
   $R_1 = BS_{qq} - 2GS_{uq} + sS_{uu} + 2E_+E_- = 0$ and
   $R_2 = S_{uq}^2 - S_{uu}S_{qq} + A_-E_+^2 + A_+E_-^2 - A_+A_-(Bs - G^2) = 0$ ($s = 1-x^2$ on $P$),
   proved as polynomial identities in $(K, u, q)$;
3. they separate generic orbits: at a seeded rational point of $P$ their differentials restricted to
   $TP$ have rank $8 = \dim P/SO(4)$ and vanish on the six generator directions of $SO(4)$ (exact, SymPy
   and FLINT ranks);
4. the reduced field: $D\,\tfrac{d}{dt}f = N_f(x, A_\pm, B, G, E_\pm, S_{uu}, S_{uq}, S_{qq})$ with
   $D = 2(2+a+b)\Delta(x)$ and $N_f$ polynomial (derived by ansatz and exact rref over $\mathbb{Q}$); each
   identity $N_f\circ\pi = D\dot f$ is proved on $P$ (sparse polynomials modulo $\lVert\gamma\rVert^2 = 1$,
   SymPy and FLINT). In particular $\dot x = G/(2+a+b)$, as for $n = 4$.

**Uses** eq:motion-general, P:inversion, eq:Delta, eq:action. $n = 5$. Not a claim of the paper.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.symbolic import algebra
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.identity import Check, rational_identity
from chaplygin_nd.symbolic.exact.points import ledger_seed
from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5
from chaplygin_nd.symbolic.reduction import reduced_n5 as r5

SECTION = "Conclusions — open problems (beyond the paper)"
SPHERE = (*ri5.q, ri5.gamma[4])
#: The tridegrees of the generation check (part 1).
DEGREES = tuple((i, j, l) for i in range(6) for j in range(7) for l in range(8)
                if (j + l) % 2 == 0 and i + j + l <= 12)


def _field_tridegrees() -> set:
    out = set()
    for N in r5.raw_derivatives().values():
        for mon in N.keys():
            out.add(ri5._tridegree(mon))
    return out


def generation_part() -> tuple[Check, list]:
    """Part 1: the products span the invariants of every tridegree of :data:`DEGREES`."""
    rows = ri5.generation_check(DEGREES, ledger_seed())
    missing = sorted(_field_tridegrees() - set(DEGREES))
    bad = [r for r in rows if not r["spans"]]
    ok = not bad and not missing
    return Check(ok, (f"{len(rows)} tridegrees: dimension (SU(2)xSU(2) characters) = rank of the "
                      "generator products mod 2^61-1 at random points (FLINT nmod_mat, SymPy "
                      "DomainMatrix over GF(p), equal)" + (f"; short: {bad[:3]}" if bad else "")
                      + (f"; field tridegrees outside the checked range: {missing}" if missing else ""))
                 ), rows


def relation_part() -> Check:
    """Part 2: the relations vanish identically in $(K, u, q)$, and $R_1, R_2$ with $s = 1 - x^2$ on $P$
    (both engines)."""
    rel = ri5.relations()
    polys = [ri5.to_phase_space(r) for rs in rel.values() for r in rs]
    if [len(rel[(2, 2, 2)]), len(rel[(4, 2, 2)])] != [1, 3]:
        return Check(False, f"unexpected relation counts {[len(v) for v in rel.values()]}")
    # and R1, R2 as the kernels use them (s = 1 - x^2) vanish on P
    on_p = [ri5.to_phase_space(ri5.INV_RING(e)) for e in r5.relations_on_P()]
    free = rational_identity(polys, label="S6:reduced-n5 relations")
    if not free.ok:
        return free
    return rational_identity(on_p, sphere=SPHERE, label="S6:reduced-n5 relations on P")


def _point():
    rng = points.generator(ledger_seed(), "S6:reduced-n5")
    return points.skew_matrix(rng, 5), points.sphere_point(rng, 5)


def separation_part() -> tuple[Check, Check]:
    r"""Part 3: rank of the differentials of the ten coordinates on $TP$ and invariance, exactly."""
    from chaplygin_nd.symbolic.exact import flint_engine

    Mv, g = _point()
    gens = ri5.generator_polys()
    R = ri5.RING
    values = [0, 0, g[4]] + [Mv[i, j] for i in range(5) for j in range(i + 1, 5)] + list(g[:4])
    at = [sp.Rational(v) for v in values]
    rows = []
    for name in r5.COORDS:
        f = R.gens[2] if name == "x" else gens[name]
        grad = [f.diff(R.gens[3 + k]) for k in range(10)]
        grad += [f.diff(R.gens[13 + k]) for k in range(4)] + [f.diff(R.gens[2])]
        rows.append([sp.Rational(str(p(*at))) if p else sp.Integer(0) for p in grad])
    Jm = sp.Matrix(rows)
    proj = sp.diag(sp.eye(10), sp.eye(5) - g * g.T)   # onto T_gamma S^4 (gamma is a unit vector)
    JT = Jm * proj
    X = []
    for i in range(4):
        for j in range(i + 1, 4):
            Y = algebra.wedge(algebra.basis_vector(5, i), algebra.basis_vector(5, j))
            X.append(list(algebra.vec(algebra.commutator(Y, Mv))) + list(Y * g))
    Xm = sp.Matrix(X)
    r_sympy = JT.rank()
    with flint_engine.use_engine("flint"):
        r_flint = flint_engine.rank(JT)
    inv = Jm * Xm.T
    rank_ok = r_sympy == r_flint == 8
    return (Check(rank_ok, f"rank on TP at a seeded rational point: SymPy {r_sympy}, FLINT "
                           f"{r_flint} (dim P/SO(4) = 14 - 6 = 8)"),
            Check(all(v == 0 for v in inv), "differentials vanish on the 6 generators of so(4) "
                                            "(exact zeros)"))


def field_parts() -> list:
    """Part 4: $N_f\\circ\\pi - D\\dot f = 0$ on $P$, per coordinate (both engines)."""
    raw, num = r5.raw_derivatives(), r5.field_numerators()
    parts = []
    for name in r5.COORDS:
        res = ri5.to_phase_space(num[name]) - raw[name]
        chk = rational_identity([res], sphere=SPHERE, label=f"S6:reduced-n5 d{name}/dt")
        parts.append(Verdict.all_of([("derived = D d/dt on P", chk)], n_values=(5,))
                     .as_part(f"d{name}/dt"))
    return parts


def field_text() -> str:
    """The derived field as text (the row's notes): each $D\\dot f$, collected in the coordinates."""
    out = []
    syms = [r5.SYMBOLS[c] for c in r5.COORDS]
    for name, p in r5.field_numerators().items():
        e = sp.collect(sp.expand(p.as_expr()), syms[1:], sp.factor)
        out.append(f"D d{name}/dt = {e}")
    return "; ".join(out)


@claim("S6:reduced-n5", uses=("eq:motion-general", "P:inversion", "eq:Delta", "eq:action"),
       adds=(SECTION, "the paper's open problem, first half, for n = 5: generators of the "
                      "SO(4)-invariant polynomials, their relations, and the reduced vector field on "
                      "P/SO(4) written in them, derived and proved exactly on P"))
def s6_reduced_n5() -> Verdict:
    gen, _rows = generation_part()
    rel = relation_part()
    rank, inv = separation_part()
    parts = [Verdict.all_of([("generation", gen)], n_values=(5,)).as_part("generators"),
             Verdict.all_of([("relations", rel)], n_values=(5,)).as_part("relations R1, R2"),
             Verdict.all_of([("rank 8", rank), ("invariant", inv)], n_values=(5,))
             .as_part("orbit separation")]
    parts += field_parts()
    notes = ("coordinates r = (x, Ap, Am, B, G, Ep, Em, Suu, Suq, Sqq), D = 2(2+a+b)Delta(x); "
             "relations R1 = B Sqq - 2 G Suq + (1-x^2) Suu + 2 Ep Em, R2 = Suq^2 - Suu Sqq + "
             "Am Ep^2 + Ap Em^2 - Ap Am (B(1-x^2) - G^2); field: " + field_text())
    return Verdict.of_parts(parts, n_values=(5,), notes=notes, method=(
        "invariant theory (SU(2)xSU(2) characters + rank mod p of generator products, FLINT and "
        "SymPy), ansatz + exact QQ rref for the field, each component re-proved on P modulo "
        "|gamma|^2 = 1 (SymPy and FLINT), exact ranks at a seeded rational point"))
