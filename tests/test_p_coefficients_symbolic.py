r"""The symbolic coefficients of eq:pol-first-integrals (:func:`symbolic.codegen.emit.axisym.p_coefficients`,
the source of the generated kernels) against their definition.

At a seeded rational point $(M, \gamma)$, $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda\,
\mathrm{Id}_n)$ is computed directly by SymPy (fraction-free elimination, not the Berkowitz expansion
the code uses) as a polynomial in $\lambda, \sigma$; the coefficient matrix evaluated at the point must
be exactly its $(n+1)\times 2$ table of coefficients of $\lambda^i\sigma^j$, nothing more.
"""

from __future__ import annotations

import random

import pytest
import sympy as sp
from chaplygin_nd.symbolic.codegen.emit import axisym


@pytest.mark.parametrize("n", [3, 4])
def test_p_coefficients_are_the_coefficients_of_the_determinant(n):
    rng = random.Random(100 + n)
    r = lambda: sp.Rational(rng.randint(-9, 9), rng.randint(1, 7))  # noqa: E731
    Msym, _ = axisym.M_symbols(n)
    gsym = axisym.gamma_symbols(n)
    subs = {g_: r() for g_ in gsym}
    for i in range(n):
        for j in range(i + 1, n):
            subs[Msym[i, j]] = r()
    Mv = Msym.subs(subs)
    assert Mv.T == -Mv
    gv = sp.Matrix([subs[g_] for g_ in gsym])
    lam, sig = sp.symbols("lambda sigma")
    p = sp.Poly((Mv + sig * gv * gv.T - lam * sp.eye(n)).det(method="bareiss"), lam, sig)
    assert p.degree(lam) == n and p.degree(sig) == 1

    got = axisym.p_coefficients(n)
    assert got.shape == (n + 1, 2)          # entry (i, j) multiplies lambda^i sigma^j, i <= n, j <= 1
    for i in range(n + 1):
        for j in range(2):
            assert sp.Rational(got[i, j].subs(subs)) == p.coeff_monomial(lam**i * sig**j), (i, j)
    assert sum(p.coeff_monomial(lam**i * sig**j) != 0 for i in range(n + 1) for j in range(2)) > n
