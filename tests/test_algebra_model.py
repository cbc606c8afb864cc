"""so(n) algebra and the general model against their definitions."""

import pytest
import sympy as sp
from chaplygin_nd.symbolic.algebra import (
    commutator,
    hat,
    killing,
    skew_symbols,
    so_basis,
    unhat,
    unvec,
    vec,
    vector_symbols,
    wedge,
)
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.mass_operator import L_matrix_qq
from chaplygin_nd.symbolic.measure import chaplygin_divergence_at
from chaplygin_nd.symbolic.model import (
    L_gamma,
    L_matrix,
    L_matrix_derivative,
    angular_velocity,
    mass_tensor_symbols,
)


def test_hat_is_a_lie_algebra_isomorphism():
    u, v = vector_symbols("u", 3), vector_symbols("v", 3)
    assert (hat(u) * v - u.cross(v)).expand() == sp.zeros(3, 1)
    assert (commutator(hat(u), hat(v)) - hat(u.cross(v))).expand() == sp.zeros(3, 3)
    assert unhat(hat(u)) == u
    assert (wedge(u, v) - hat(v.cross(u))).expand() == sp.zeros(3, 3)


@pytest.mark.parametrize("n", [3, 4, 5])
def test_killing_metric_and_coordinates(n):
    A, B = skew_symbols("A", n), skew_symbols("B", n)
    assert sp.expand(killing(A, B) - (vec(A).T * vec(B))[0]) == 0
    assert unvec(vec(A), n) == A
    basis = so_basis(n)
    assert all(killing(X, Y) == (1 if i == j else 0)
               for i, X in enumerate(basis) for j, Y in enumerate(basis))


@pytest.mark.parametrize("n", [3, 4])
def test_L_matrix_is_the_matrix_of_L_gamma(n):
    gamma, J, b = vector_symbols("g", n), mass_tensor_symbols(n), sp.Symbol("b")
    direct = sp.Matrix.hstack(*[vec(L_gamma(B, gamma, J, b)) for B in so_basis(n)])
    assert (direct - L_matrix(gamma, J, b)).expand() == sp.zeros(*direct.shape)
    for k in range(n):
        assert (L_matrix(gamma, J, b).diff(gamma[k]) - L_matrix_derivative(gamma, b, k)).expand() \
            == sp.zeros(*direct.shape)


def test_exact_solve_and_qq_assembly_agree():
    rng = points.generator(5, "solve")
    n = 6
    gamma, M = points.sphere_point(rng, n), points.skew_matrix(rng, n)
    J, b = sp.diag(*range(1, n + 1)), sp.Rational(3, 4)
    Omega = angular_velocity(M, gamma, J, b)
    assert L_gamma(Omega, gamma, J, b) == M
    assert L_matrix_qq(gamma, J, b).to_Matrix() == L_matrix(gamma, J, b)
    assert L_matrix_qq(gamma, J, b, derivative=2).to_Matrix() == L_matrix_derivative(gamma, b, 2)


def test_divergence_at_point_detects_a_wrong_density():
    rng = points.generator(9, "div")
    n = 4
    gamma, M = points.sphere_point(rng, n), points.skew_matrix(rng, n)
    d = chaplygin_divergence_at(M, gamma, sp.diag(1, 2, 3, 5), sp.Rational(2))
    transport = sum(g * l for g, l in zip(d["gamma_dot"], d["dlogdet"]))
    assert d["div"] - transport / 2 == 0          # (det L)^(-1/2): invariant
    assert d["div"] - transport != 0              # (det L)^(-1): not invariant here


def test_measure_residual_is_div_of_rho_x_over_rho():
    """symbolic.measure.measure_residual: div(rho X)/rho for rho = prod D_i^p_i, computed here by
    differentiating rho X directly. Its rows test only whether it is zero, so a negated residual
    survived them (a mutation run)."""
    from chaplygin_nd.symbolic.measure import measure_residual

    x, y = sp.symbols("x y", positive=True)
    field, rho = [x * y, x - y**2], x**3 * (1 + y) ** sp.Rational(-1, 2)
    want = sum(sp.diff(rho * f, c) for f, c in zip(field, (x, y))) / rho
    got = measure_residual(field, [x, y], [(x, 3), (1 + y, sp.Rational(-1, 2))])
    assert sp.simplify(got - want) == 0 and sp.simplify(want) != 0


def test_angular_velocity_with_symbolic_entries_is_the_rational_solve_put_together():
    """model.angular_velocity's SymPy branch (symbolic entries: no row takes it, all rows solve
    at rational points; a mutation run: a negated result survived) against its rational branch
    at a value of the symbol, and eq:M-O itself."""
    s = sp.Symbol("s", positive=True)
    M = sp.Matrix([[0, 1, -2], [-1, 0, 3], [2, -3, 0]])
    gamma = sp.Matrix([sp.Rational(2, 3), sp.Rational(1, 3), sp.Rational(2, 3)])
    J = sp.diag(1, 1, 1 + s)
    b = sp.Rational(3, 2)
    Om = angular_velocity(M, gamma, J, b)
    at = Om.subs(s, sp.Rational(1, 2)).applyfunc(sp.simplify)
    assert at == angular_velocity(M, gamma, sp.diag(1, 1, sp.Rational(3, 2)), b)
    assert (L_gamma(Om, gamma, J, b) - M).applyfunc(sp.simplify) == sp.zeros(3, 3)


def test_symbol_helpers_are_their_docstrings():
    """algebra.skew_symbols ({name}{i}{j} above the diagonal, 1-based, '_' between indices from
    n = 10), algebra.basis_vector (its error message names the range 0..n-1) and
    model.mass_tensor_symbols (diag(J_1, ..., J_n), positive). Their mutants changed no row
    (generic symbols under other names, a message, a sign of J no row fixes): a mutation run."""
    from chaplygin_nd.symbolic.algebra import basis_vector

    S = skew_symbols("m", 4)
    assert [S[0, 1].name, S[2, 3].name, S[1, 3].name] == ["m12", "m34", "m24"]
    assert S[1, 0] == -S[0, 1] and S[0, 0] == 0
    assert skew_symbols("m", 10)[8, 9].name == "m9_10"
    with pytest.raises(ValueError, match=r"index 3 outside 0\.\.2"):
        basis_vector(3, 3)
    J = mass_tensor_symbols(3)
    assert J == sp.diag(*sp.symbols("J1:4", positive=True)) and all(J[i, i].is_positive for i in range(3))
