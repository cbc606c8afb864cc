"""symbolic/family/exceptional_b.py (row S6:wedge-independence): d(phi) over Q(b) against the
gradient of H_k along the SO(n) orbit (an independent route), the Sturm count against known roots,
and controls that the exceptional b it finds are real drops of the rank."""

from __future__ import annotations

import flint
import pytest
import sympy as sp
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.family import exceptional_b as eb
from chaplygin_nd.symbolic.family import independence as ind
from chaplygin_nd.symbolic.family import wedge_integrals as wi


def _orbit_rows(M, g, a, b, n):
    """dH_k along the SO(n) orbit, xi = E_i E_n^T - E_n E_i^T (velocity ([xi, M], xi gamma)), by the
    gradient of wedge_integrals (b a number): equals -dphi(xi E_n) = 2a Phi."""
    K = (n + 1) // 2 - 1
    rows = []
    for k in range(1, K + 1):
        grad = wi.gradient(M, g, a, b, k, "sympy")
        row = []
        for i in range(n - 1):
            xi = sp.zeros(n)
            xi[i, n - 1], xi[n - 1, i] = 1, -1
            XM = xi * M - M * xi
            vec = [XM[p, q] for p, q in wi.subsets(n, 2)] + list(xi * g)
            row.append(sum(sp.Rational(x) * y for x, y in zip(grad, vec, strict=True)))
        rows.append(row)
    return sp.Matrix(rows)


def _at(x, b, engine):
    if engine == "flint":
        num = x.p(flint.fmpq(int(b.p), int(b.q)))
        den = x.q(flint.fmpq(int(b.p), int(b.q)))
        return sp.Rational(int((num / den).p), int((num / den).q))
    return sp.Rational(x.numer.as_expr().subs(eb._b, b) / x.denom.as_expr().subs(eb._b, b))


@pytest.mark.parametrize("n", [5, 6, 7])
def test_phi_matrix_is_the_orbit_derivative_of_the_conserved_functions(n):
    M, g, _, _ = eb.adapted_frame_point(points.generator(3, "exceptional test", n), n)
    a = sp.Rational(2, 3)
    for engine in ("sympy", "flint"):
        Phi = eb.phi_matrix(M, g, a, engine)
        for b in (sp.Rational(1, 3), sp.Rational(5, 2)):
            P = sp.Matrix([[_at(x, b, engine) for x in row] for row in Phi])
            assert _orbit_rows(M, g, a, b, n) == 2 * a * P


def test_sturm_count_against_known_roots():
    x = sp.Symbol("x")
    for expr, positive in [((x - 1) * (x - 2) * (x + 3), 2), (x**2 + 1, 0), (x * (x - sp.Rational(1, 2))**2, 1),
                           ((x + 1) * (x + 5), 0), (x**3 - 2, 1)]:
        coeffs = [sp.Rational(c) for c in reversed(sp.Poly(expr, x).all_coeffs())]
        p = flint.fmpq_poly([flint.fmpq(int(c.p), int(c.q)) for c in coeffs])
        assert eb.positive_roots_sturm(p) == positive
    with pytest.raises(ValueError, match="zero polynomial"):
        eb.positive_roots_sturm(flint.fmpq_poly([0]))


def test_a_root_of_G_is_a_real_drop_and_both_engines_agree():
    """n = 7 at a point whose G has a positive rational root b0: at b0 the rank of d(phi) falls and so
    does the whole Jacobian's at that point (the bound is sharp there); off b0 it is full."""
    n = 7
    for i in range(1, 20):
        M, g, _, _ = eb.adapted_frame_point(points.generator(3, "exceptional drop", i), n)
        a = sp.Rational(1, 2)
        s, f = (eb.exceptional_record(M, g, a, eng) for eng in ("sympy", "flint"))
        assert {k: s[k] for k in s if k != "poly"} == {k: f[k] for k in f if k != "poly"}
        assert s["pole_positive_roots"] == 0 and s["rank_at_0"] == 3
        if s["rational_positive_roots"]:
            break
    else:
        pytest.fail("no point with a positive rational exceptional b among 19")
    b0 = s["rational_positive_roots"][0]
    assert _orbit_rows(M, g, a, b0, n).rank() < 3
    assert ind.rank_record(M, g, a, b0, "flint")["rank"] < 2 * n - 2 - n // 2
    assert ind.rank_record(M, g, a, b0 + 1, "flint")["rank"] == 2 * n - 2 - n // 2


def test_the_rows_exceptional_b_record_is_plain_json():
    """The row's data goes into verification.json: plain ints and strings, not SymPy numbers."""
    import json

    from chaplygin_nd.proofs import s6_wedge_independence as row

    part, rec = row.exceptional(5)
    assert part.verdict == "holds"
    assert json.loads(json.dumps(rec)) == rec and type(rec["common_positive_roots"]) is int
