"""Values of the first-integral search (row S6:first-integrals) against their definitions: the
survivors of ``chaplygin mutate-derivations`` that the row's rank and span checks cannot
see — a generator's sign or scale, the names and the torus branch of the coordinates, boxes and
code paths the row's cheap boxes never take (no known product, gamma-degree 0, D^2, a block
decided by its rank alone, several chunks, no margin of rows) — and the sign of
sixth_integral.pfaffian_vector (S6:sixth-integral-n5). Every expected value comes from the
definition, computed here over QQ, or from a count the definition fixes; none from the output."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp
from chaplygin_nd.symbolic.search import (
    box_search,
    candidate_basis,
    found_integral,
    known_integrals,
    sampled_field,
)
from chaplygin_nd.symbolic.search import integral_search as fi

A, B = sp.Rational(-1, 3), sp.Rational(3, 2)
GENERIC3 = sampled_field.general((1, sp.Rational(3, 2), sp.Rational(7, 3)), sp.Rational(1, 2))
P = sampled_field.PRIMES[0]


# ---- candidate_basis.coordinates: the linear forms of the module docstring -------------------------

def _definition(n: int, planes: int):
    """(labels, vectors, weights) of the basis zeta_j = E_{2j-1} + i E_{2j}, its conjugate, then
    E_k, written from fi_basis's docstring (1-based labels)."""
    labels, vecs, wts = [], [], []
    for j in range(planes):
        for s, lab in ((1, f"z{j + 1}"), (-1, f"zb{j + 1}")):
            v = [0] * n
            v[2 * j], v[2 * j + 1] = 1, sp.I * s
            w = [0] * planes
            w[j] = s
            labels.append(lab)
            vecs.append(sp.Matrix(v))
            wts.append(w)
    for k in range(2 * planes, n):
        labels.append(f"e{k + 1}")
        vecs.append(sp.Matrix([int(t == k) for t in range(n)]))
        wts.append([0] * planes)
    return labels, vecs, wts


@pytest.mark.parametrize("n, planes", [(3, 0), (4, 1), (5, 2), (5, 1)])
def test_coordinates_are_the_linear_forms_of_the_definition(n, planes):
    """Names, Gaussian-integer rows, weights and the reflections' action of candidate_basis.coordinates
    against u^T M v (u before v) and u^T gamma evaluated over QQ(i) at an integer point."""
    co = candidate_basis.coordinates(n, planes)
    labels, vecs, wts = _definition(n, planes)
    pairs = list(itertools.combinations(range(n), 2))
    assert co.names == tuple([f"M[{labels[a]},{labels[b]}]" for a, b in pairs]
                             + [f"g[{lab}]" for lab in labels])
    assert co.is_gamma.tolist() == [False] * len(pairs) + [True] * n
    assert co.xn == len(co.names) - 1 and co.names[co.xn] == f"g[e{n}]"
    assert co.weight.tolist() == [[x + y for x, y in zip(wts[a], wts[b])] for a, b in pairs] + wts
    rng = np.random.default_rng([n, planes])
    z = [int(t) for t in rng.integers(-9, 10, size=len(pairs) + n)]
    M = sp.zeros(n, n)
    for c, (i, j) in enumerate(pairs):
        M[i, j], M[j, i] = z[c], -z[c]
    g = sp.Matrix(z[len(pairs):])
    want = [(vecs[a].T * M * vecs[b])[0, 0] for a, b in pairs] + [(u.T * g)[0, 0] for u in vecs]
    got = [sum((int(r) + sp.I * int(i)) * x for r, i, x in zip(co.re[t], co.im[t], z))
           for t in range(len(co.names))]
    assert [sp.expand(w - v) for w, v in zip(want, got)] == [0] * len(want)
    for k, (perm, sign) in enumerate(co.action):   # coordinate_t(g_k . z) = sign_t coordinate_perm[t](z)
        flip = [-1 if t == k else 1 for t in range(n)]
        zk = [flip[i] * flip[j] * z[c] for c, (i, j) in enumerate(pairs)] + [
            flip[t] * z[len(pairs) + t] for t in range(n)]
        image = [sum((int(r) + sp.I * int(i)) * x for r, i, x in zip(co.re[t], co.im[t], zk))
                 for t in range(len(co.names))]
        assert [sp.expand(image[t] - int(sign[t]) * got[int(perm[t])])
                for t in range(len(co.names))] == [0] * len(co.names)
        assert sorted(perm.tolist()) == list(range(len(co.names)))


@pytest.mark.parametrize("n, planes, bound", [(5, 3, 2), (4, 2, 1), (3, -1, 1)])
def test_coordinates_refuse_more_planes_than_the_torus_has(n, planes, bound):
    """A maximal torus of SO(n-1) has floor((n-1)/2) planes: the error names that bound."""
    with pytest.raises(ValueError, match=rf"^planes must lie in 0\.\.{bound}$"):
        candidate_basis.coordinates(n, planes)


# ---- known_integrals.values: each generator's value against its definition over QQ ----------------

def _point(n: int, seed: int):
    """An exact point: integer skew M, gamma on the sphere (inverse stereographic projection of
    integers), as sympy matrices and as the search's row z mod p."""
    rng = np.random.default_rng([seed, n])
    pairs = list(itertools.combinations(range(n), 2))
    m = [int(t) for t in rng.integers(-9, 10, size=len(pairs))]
    t = [sp.Integer(int(x)) for x in rng.integers(-5, 6, size=n - 1)]
    s = sum(x * x for x in t)
    g = sp.Matrix([2 * x / (s + 1) for x in t] + [(s - 1) / (s + 1)])
    M = sp.zeros(n, n)
    for c, (i, j) in enumerate(pairs):
        M[i, j], M[j, i] = m[c], -m[c]
    z = np.array([[x % P for x in m] + [sampled_field.mod(x, P) for x in g]], dtype=np.int64)
    return M, g, z


def _omega(model: sampled_field.Model, M, g):
    """Omega from its definition L_gamma(Omega) = M (eq:M-O), L_gamma(X) = J X + X J +
    b ((X gamma) gamma^T - gamma (X gamma)^T), solved over QQ."""
    n = M.shape[0]
    pairs = list(itertools.combinations(range(n), 2))
    J = sp.diag(*model.J)
    cols = []
    for i, j in pairs:
        E = sp.zeros(n, n)
        E[i, j], E[j, i] = 1, -1
        img = J * E + E * J + model.b * (E * g * g.T - g * (E * g).T)
        cols.append([img[k, l] for k, l in pairs])
    w = sp.Matrix(cols).T.solve(sp.Matrix([M[i, j] for i, j in pairs]))
    Om = sp.zeros(n, n)
    for c, (i, j) in enumerate(pairs):
        Om[i, j], Om[j, i] = w[c], -w[c]
    return Om


def _pf4(A, idx):
    a, b, c, d = idx
    return A[a, b] * A[c, d] - A[a, c] * A[b, d] + A[a, d] * A[b, c]


def _expected(model: sampled_field.Model, M, g, include_new: bool) -> dict:
    """The generators by definition (fi_known's docstring), exact rationals, by name."""
    n = M.shape[0]
    lam, sig = sp.symbols("lambda sigma")
    p = sp.Poly((M + sig * g * g.T - lam * sp.eye(n)).det(), lam, sig)
    out = {}
    for gen in known_integrals.generators(model, include_new):   # (-1)^n p: fi_known's docstring
        if gen.name.startswith("p0[lambda^"):
            out[gen.name] = (-1) ** n * p.coeff_monomial(lam ** int(gen.name[10:-1]))
        elif gen.name.startswith("p1[sigma lambda^"):
            out[gen.name] = (-1) ** n * p.coeff_monomial(sig * lam ** int(gen.name[16:-1]))
    Om = _omega(model, M, g)
    out["H"] = sum(M[i, j] * Om[i, j] for i, j in itertools.combinations(range(n), 2)) / 2
    if n == 4:
        out["Pf(M)"] = _pf4(M, (0, 1, 2, 3))
    if n == 5:   # v_i = (-1)^(i+1) Pf of M without row and column i (1-based i)
        v = sp.Matrix([(-1) ** i * _pf4(M, [t for t in range(5) if t != i]) for i in range(5)])
        assert v * v.T == M.adjugate()          # adj(M) = v v^T: the Pfaffians and their signs
        out["<v, gamma>"] = (v.T * g)[0, 0]
        if include_new:
            num, den = found_integral.new_integral(M, g, model.a, model.b)
            out["F"] = num / den
            e = sp.Matrix([0, 0, 0, 0, 1])    # F2 = <v, B(2+B)v>/Delta, B = a E_n E_n^T + b gamma gamma^T
            Bm = model.a * e * e.T + model.b * g * g.T
            out["F2"] = (v.T * Bm * (2 * sp.eye(5) + Bm) * v)[0, 0] / den
    return out


@pytest.mark.parametrize("n, include_new", [(4, False), (5, True)])
def test_known_values_are_the_generators_of_the_definition(n, include_new):
    """known_integrals.values at an exact point, column by column, against the definitions over QQ
    reduced mod p: a sign or a scale of one generator (which no rank sees) is caught. The
    coefficients of (-1)^n det(M + sigma gamma gamma^T - lambda), Pf M (n = 4), <v, gamma> with
    adj(M) = v v^T, F and F2 (n = 5), H = <M, Omega>/2 with Omega solved from eq:M-O."""
    model = sampled_field.axisymmetric(n, A, B)
    M, g, z = _point(n, 11)
    got = known_integrals.values(model, z, P, include_new)[0]
    want = _expected(model, M, g, include_new)
    names = [gen.name for gen in known_integrals.generators(model, include_new)]
    assert len(got) == len(names) and set(names) == set(want)
    for name in names:
        assert int(got[names.index(name)]) == sampled_field.mod(want[name], P), name
    assert want["H"] > 0      # the energy is positive definite in M (a check of _omega itself)


def test_general_integral_for_n6_is_the_hodge_form_g():
    """found_integral.general_integral's docstring: for n = 6 it is G of new_integral_6 (built from
    W = *(M ^ M)/8, another formula), equal at an exact point — its sign and scale included."""
    M, g, _ = _point(6, 5)
    a, b = sp.Rational(2, 9), sp.Rational(5, 3)
    n1, d1 = found_integral.general_integral(M, g, a, b)
    n2, d2 = found_integral.new_integral_6(M, g, a, b)
    assert d1 != 0 and n1 != 0 and n1 / d1 == n2 / d2


# ---- the search on boxes and code paths the row's cheap boxes do not take --------------------

def test_a_box_without_known_products_has_known_rank_zero_in_every_block():
    """n = 3, M-degree 1, gamma-degree 0: no product of the generators lies there (<M, gamma>
    needs gamma-degree 1), so every block's known rank is 0 (and the blocks are the basis')."""
    assert known_integrals.products(GENERIC3, 1, 0, 0) == []
    ranks = fi.known_ranks(GENERIC3, 1, 0, 0, False)
    assert ranks == {blk.character: 0 for blk in candidate_basis.basis(3, 1, 0, 0).blocks}


@pytest.mark.parametrize("model, box, count", [
    (GENERIC3, (1, 0, 0), 0),                          # nothing M-linear without gamma
    (GENERIC3, (1, 1, 0), 1),                          # <M, gamma>: gamma-degree exactly 1
    (sampled_field.axisymmetric(4, A, B), (2, 0, 0), 2),    # the two Casimirs |M|^2, Pf M of so(4)
])
def test_boxes_at_the_lowest_gamma_degree_hold_their_integrals(model, box, count):
    """gamma-degree 0 and 1 boxes (d_gamma >= 0 is in the domain): the generators of gamma-degree
    0 (Pf M) and 1 (<v, gamma>) are counted there, and the bounds meet at the count the definition
    gives."""
    r = fi.search_degree(model, *box)
    assert (r.found, r.known, r.settled, r.recovered is not False) == (count, count, True, True)


def test_the_numerators_of_a_d_squared_box_are_in_the_kernel():
    """k = 2: the known products enter the box as numerators P = F D^2; the recovery check
    (every known numerator lies in the F_p kernel) holds only with the right power of D."""
    r = fi.search_degree(GENERIC3, 2, 4, 2)
    assert r.products > 0 and r.found == r.known > 0 and r.settled and r.recovered is True


def test_the_rank_branch_gives_the_nullity_of_the_kernel_branch(monkeypatch):
    """Blocks above RECOVERY_MAX take nullity = columns - rank; with RECOVERY_MAX = 0 every block
    does, and the nullities equal the F_p kernel dimensions of the default run."""
    model = sampled_field.axisymmetric(4, A, B)
    kernel = fi.search_degree(model, 2, 4, 1)
    monkeypatch.setattr(box_search, "RECOVERY_MAX", 0)  # the base owns it
    ranked = fi.search_degree(model, 2, 4, 1)
    assert ranked.recovered is None
    assert [b.nullity for b in ranked.blocks] == [b.nullity for b in kernel.blocks]
    assert ranked.found == kernel.found == 4


def test_several_chunks_give_the_matrix_of_one(monkeypatch):
    """The condition rows are built in chunks of about CHUNK_ENTRIES entries (memory only): with
    chunks of a few rows the search decides every block as with one chunk."""
    model = sampled_field.axisymmetric(4, A, B)
    one = fi.search_degree(model, 2, 4, 1)
    B_ = candidate_basis.basis(4, 2, 4, model.planes)
    monkeypatch.setattr(fi, "CHUNK_ENTRIES", 7 * B_.size)
    chunked = fi.search_degree(model, 2, 4, 1)
    assert chunked.blocks == one.blocks and chunked.found == one.found == 4


def test_as_many_conditions_as_unknowns_settle_a_control_box(monkeypatch):
    """MARGIN = 0: each block gets exactly as many conditions as unknowns (every row counts:
    one dropped leaves a kernel that is not an integral); the control box still settles."""
    monkeypatch.setattr(fi, "MARGIN", 0)
    r = fi.search_degree(sampled_field.axisymmetric(4, A, B), 2, 4, 1)
    assert (r.found, r.known, r.settled) == (4, 4, True)


# ---- sixth_integral.pfaffian_vector (S6:sixth-integral-n5): its sign convention ---------------

def test_sixth_integral_pfaffian_vector_is_the_documented_one():
    """w_i = (-1)^i Pf(M without row and column i) (0-based), pinned where the Pfaffian is known in
    closed form: for M = E_12 + E_34 (the standard symplectic form on the first four coordinates)
    Pf = 1, so w = (0, 0, 0, 0, 1); and at an integer point it is found_integral.pfaffian_vector (the
    vector of F, another implementation of the same definition) with M w = 0. The row's N_F is
    quadratic in w and cannot see its sign."""
    from chaplygin_nd.symbolic.family import sixth_integral

    M = sp.zeros(5, 5)
    M[0, 1], M[1, 0], M[2, 3], M[3, 2] = 1, -1, 1, -1
    assert sixth_integral.pfaffian_vector(M.tolist()) == [0, 0, 0, 0, 1]
    M, _g, _z = _point(5, 3)
    w = sixth_integral.pfaffian_vector(M.tolist())
    assert sp.Matrix(w) == found_integral.pfaffian_vector(M) and M * sp.Matrix(w) == sp.zeros(5, 1)
    assert any(w)


def test_prove_symbolic_proves_the_integral_at_the_parameters_given():
    """prove_symbolic(n, a, b): numeric a, b given are the ones the integral is built and proved
    with (symbolic a, b only by default); F (n = 3) is an integral there."""
    seen = []

    def spy(M, gamma, a, b):
        seen.append((a, b))
        return found_integral.new_integral(M, gamma, a, b)

    assert found_integral.prove_symbolic(3, A, B, builder=spy).ok
    assert seen == [(A, B)]


# ---- known_integrals.generators: the degrees of the new integrals --------------------------------------

@pytest.mark.parametrize("n, name, integral", [(5, "F", found_integral.new_integral),
                                               (6, "G", found_integral.new_integral_6)])
def test_the_new_integrals_generators_have_their_numerators_degrees(n, name, integral):
    """A generator's M-degree and gamma-degree are those of its numerator (the latter modulo the
    sphere), computed here from the symbolic numerator. The n = 6 branch (G) is one S6:first-
    integrals never takes: a mutant giving G gamma-degree 3 survived it."""
    from chaplygin_nd.symbolic.algebra import skew_symbols, vector_symbols

    model = sampled_field.axisymmetric(n, A, B)
    gen = next(g for g in known_integrals.generators(model, include_new=True) if g.name == name)
    M, gam = skew_symbols("m", n), vector_symbols("g", n)
    num, _ = integral(M, gam, model.a, model.b)
    assert gen.m_degree == sp.Poly(num, *sorted(M.free_symbols, key=str)).total_degree()
    assert gen.g_degree == known_integrals._sphere_degree(num, list(gam))
    assert gen.d_power == 1


# ---- found_integral.pfaffian and reduced5_invariants.K_matrix -------------------------------------------

@pytest.mark.parametrize("size", [0, 2, 3, 4, 6])
def test_fi_new_pfaffian_is_the_definition(size):
    """Against the permutation sum, its sign included (the rows use Pf through v v^T = adj M and
    quadratic forms, blind to a sign), and 0 for an odd size (a branch no row
    takes)."""
    import definitions
    from chaplygin_nd.symbolic.exact import points

    A = points.skew_matrix(points.generator(size, "tests/test_fi_survivors pfaffian"), size) \
        if size else sp.zeros(0, 0)
    assert found_integral.pfaffian(A) == (definitions.pfaffian(A) if size else 1)


def test_k_matrix_is_the_upper_left_block_and_u_the_last_column():
    """reduction.invariants_n5.K_matrix's docstring: K = (M_ij), i, j < 4, and u = (M_i5), i < 4. A
    K with a fifth column or row survived the rows (they index it below 4)."""
    from chaplygin_nd.symbolic.reduction import invariants_n5 as ri

    Mm = [[10 * i + j for j in range(5)] for i in range(5)]
    K, u = ri.K_matrix(Mm)
    assert K == [[10 * i + j for j in range(4)] for i in range(4)]
    assert u == [10 * i + 4 for i in range(4)]


def test_the_axisymmetric_model_carries_its_a_and_b():
    """sampled_field.axisymmetric: J = Id + a E_n E_n^T (eq:axisymm), the given b, kind and a. The
    search's counts are the same for every generic (a, b), so S6:first-integrals did not see a and
    b exchanged."""
    model = sampled_field.axisymmetric(5, A, B)
    assert model.J == (1, 1, 1, 1, 1 + A) and model.b == B and model.a == A
    assert model.kind == "axisymmetric" and model.n == 5 and model.planes == 2
    assert all(isinstance(v, sp.Rational) for v in (*model.J, model.a, model.b))
