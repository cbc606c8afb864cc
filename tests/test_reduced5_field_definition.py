r"""The $n = 5$ reduction's raw field (row S6:reduced-n5) against its definition, exactly.

At a seeded rational phase point $(a, b, M, \gamma)$ with $\gamma \in S^4$, $\Omega$ is found by an
exact linear solve of $L_\gamma(\Omega) = M$ (eq:M-O, :func:`symbolic.axisymmetric.L_gamma_axisym`, the
definition; not the derived inverse), the field on $P$ is $D\dot M = D[M, \Omega]$,
$D\dot\gamma = -D\Omega\gamma$ with $D = 2(2+a+b)\Delta(x)$ (eq:Delta), and $D\dot f$ is the chain rule
along it applied by SymPy to each generator $f$ of :func:`symbolic.reduction.invariants_n5.generator_polys`.
:func:`symbolic.reduction.reduced_n5.phase_field_numerators` and
:func:`symbolic.reduction.reduced_n5.raw_derivatives` are evaluated at the same point and must agree
exactly, the $M$-part and the $\gamma$-part of each rate separately (an integral's rate may vanish with
either part negated, a generator's may not, but the parts are compared one by one all the same).
"""

from __future__ import annotations

import random

import pytest
import sympy as sp
from chaplygin_nd.symbolic.axisymmetric import L_gamma_axisym, a, b, x
from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5
from chaplygin_nd.symbolic.reduction import reduced_n5

PAIRS = [(i, j) for i in range(5) for j in range(i + 1, 5)]


def _point(seed: int) -> dict:
    """A seeded rational point: a, b, M (skew), gamma on S^4 (inverse stereographic image of t)."""
    rng = random.Random(seed)
    r = lambda: sp.Rational(rng.randint(-9, 9), rng.randint(1, 7))  # noqa: E731
    t = [r() for _ in range(4)]
    n2 = sum(v**2 for v in t)
    gam = sp.Matrix([2 * v / (1 + n2) for v in t] + [(1 - n2) / (1 + n2)])
    assert sum(v**2 for v in gam) == 1
    Mv = sp.zeros(5, 5)
    for i, j in PAIRS:
        Mv[i, j] = r()
        Mv[j, i] = -Mv[i, j]
    return {"a": sp.Rational(rng.randint(-6, 6), 7), "b": sp.Rational(rng.randint(1, 9), 5),
            "M": Mv, "gamma": gam}


def _field_by_definition(pt: dict):
    """(D M-dot, D gamma-dot) at ``pt`` from L_gamma (eq:M-O) solved exactly for Omega."""
    A, B, Mv, gam = pt["a"], pt["b"], pt["M"], pt["gamma"]
    w = sp.symbols("w0:10")
    Om = sp.zeros(5, 5)
    for (i, j), s in zip(PAIRS, w, strict=True):
        Om[i, j], Om[j, i] = s, -s
    L = L_gamma_axisym(Om, gam, A, B)
    sol = sp.solve([L[i, j] - Mv[i, j] for i, j in PAIRS], w, dict=True)
    assert len(sol) == 1 and len(sol[0]) == 10
    Om = Om.subs(sol[0])
    assert L_gamma_axisym(Om, gam, A, B) == Mv
    xv = gam[4]
    D = 2 * (2 + A + B) * ((2 + A) * (2 + B) - A * B * xv**2)
    return D * (Mv * Om - Om * Mv), -D * Om * gam


def _values(pt: dict) -> list:
    """The point as values of RING's generators (a, b, x, M_ij, q)."""
    return [pt["a"], pt["b"], pt["gamma"][4], *(pt["M"][i, j] for i, j in PAIRS),
            *pt["gamma"][:4]]


def _at(poly, vals):
    """The ring element ``poly`` at ``vals`` (one value per generator of RING), exactly: the
    ring's own evaluation (SymPy's ``subs`` on the expanded expression took minutes)."""
    assert poly.ring == ri5.RING
    return ri5.RING.domain.to_sympy(poly(*vals))


@pytest.mark.parametrize("seed", [1, 2])
def test_phase_field_numerators_are_the_field_of_eq_M_O(seed):
    pt = _point(seed)
    Mdot, gdot = reduced_n5.phase_field_numerators()
    assert set(Mdot) == set(PAIRS)          # (D M-dot_ij)_{i<j}, nothing else
    assert len(gdot) == 5
    want_M, want_g = _field_by_definition(pt)
    vals = _values(pt)
    for i, j in PAIRS:
        assert _at(Mdot[(i, j)], vals) == want_M[i, j], (i, j)
    for k in range(5):
        assert _at(gdot[k], vals) == want_g[k], k


@pytest.mark.parametrize("seed", [3])
def test_raw_derivatives_are_the_chain_rule_along_the_field(seed):
    pt = _point(seed)
    want_M, want_g = _field_by_definition(pt)
    vals = _values(pt)
    subs = dict(zip(ri5.PHASE_GENS, vals))
    Msyms = [ri5.M[i, j] for i, j in PAIRS]
    gsyms = list(ri5.gamma)
    raw = reduced_n5.raw_derivatives()
    assert set(raw) == set(reduced_n5.COORDS)
    assert _at(raw["x"], vals) == want_g[4]
    g = ri5.generator_polys()
    for name in reduced_n5.COORDS[1:]:
        f = g[name].as_expr()
        assert x not in f.free_symbols and a not in f.free_symbols and b not in f.free_symbols
        # xreplace: every generator replaced by its rational value at once (exact, as subs)
        m_part = sum(sp.diff(f, s).xreplace(subs) * want_M[i, j] for s, (i, j) in zip(Msyms, PAIRS))
        g_part = sum(sp.diff(f, s).xreplace(subs) * want_g[k] for k, s in enumerate(gsyms[:4]))
        # both parts are seen at this point (the gamma-part wherever f depends on q)
        assert m_part != 0 and (g_part != 0) == bool(f.free_symbols & set(gsyms)), name
        assert _at(raw[name], vals) == m_part + g_part, name
