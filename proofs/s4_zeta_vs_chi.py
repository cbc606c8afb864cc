r"""S4:zeta-vs-chi — Chaplygin relative equilibria on $\mathcal{V}$ differ from the rigid body's for $n \ge 4$.

Claim (lines 747-756): for $n = 3$, $\zeta$ (eq:xiVnD) equals $\chi$ (eq:solManakov) on
$\mathcal{V}$ (P:n3special); for $n \ge 4$ there are $(\Omega_0, \gamma_0) \in \mathcal{V}$ with
$[\chi - \zeta, \Omega_0] \ne 0$, so $e^{\zeta t}\Omega_0e^{-\zeta t} \ne e^{\chi t}\Omega_0e^{-\chi t}$
for small $t \ne 0$ (their derivatives at $t = 0$ differ).

What is proved. $n = 3$: the derived $\zeta$ and the derived $\chi(\Omega_0)$ agree identically on a
generic symbolic point of $\mathcal{V}$ (modulo $\lVert\gamma\rVert^2 = 1$). $n = 4, 5$ (and $6$):
an explicit exact rational point of $\mathcal{V}$ — found by a deterministic search over small
rationals and printed in the ledger — with $a, b$ in the physical range and an exact non-zero entry
of $[\chi - \zeta, \Omega_0]$; $\Omega_0 = L_{\gamma_0}^{-1}M_0$ is an exact linear solve, and
$\zeta, \chi$ are both the derived and the printed ones (they agree, Th:Re and eq:solManakov).

Uses: Th:Re, eq:xiVnD, eq:solManakov, P:n3special, eq:V-velocity.
"""

from __future__ import annotations

import itertools

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs.s4_common import fact, generic_vertical, sym_checks
from chaplygin_nd.symbolic.algebra import commutator, unvec, vec, wedge
from chaplygin_nd.symbolic.axisym_inverse import inverse_closed_form
from chaplygin_nd.symbolic.axisymmetric import E_n, L_matrix_axisym
from chaplygin_nd.symbolic.printed import section4 as printed
from chaplygin_nd.symbolic.vertical import chi, zeta
from sympy.polys.matrices import DomainMatrix


def _explicit_point(n: int):
    """First point (deterministic order) of V with [chi - zeta, Omega_0] != 0."""
    a, b = sp.Integer(1), sp.Integer(1)
    gamma0 = sp.Matrix([0] * (n - 2) + [sp.Rational(3, 5), sp.Rational(4, 5)])
    f = [sp.eye(n)[:, i] for i in range(n - 2)] + [sp.Matrix([0] * (n - 2) + [4, -3]) / 5]
    pairs = [(i, j) for i in range(n - 1) for j in range(i + 1, n - 1)]
    for coeffs in itertools.product((0, 1, 2), repeat=len(pairs)):
        M0 = sp.zeros(n, n)
        for c, (i, j) in zip(coeffs, pairs, strict=True):
            M0 += c * wedge(f[i], f[j])
        if M0 == sp.zeros(n, n):
            continue
        L = DomainMatrix.from_Matrix(L_matrix_axisym(gamma0, a, b)).convert_to(sp.QQ)
        Omega0 = unvec(L.lu_solve(DomainMatrix.from_Matrix(vec(M0)).convert_to(sp.QQ)).to_Matrix(), n)
        z, c = zeta(M0, gamma0, a, b), chi(Omega0, a, b)
        C = commutator(c - z, Omega0)
        if C != sp.zeros(n, n):
            return a, b, gamma0, M0, Omega0, z, c, C
    raise ArithmeticError(f"no point found for n = {n}")


def _report(n: int):
    a, b, gamma0, M0, Omega0, z, c, C = _explicit_point(n)
    in_V = M0 * gamma0 == sp.zeros(n, 1)
    printed_agree = (printed.zeta_xiVnD(Omega0, gamma0, a, b) == z
                     and printed.chi(Omega0, a, b) == c
                     and Omega0 == inverse_closed_form(M0, gamma0, a, b))
    i, j = next((i, j) for i in range(n) for j in range(n) if C[i, j] != 0)
    where = (f"n = {n}: a = b = 1, gamma_0 = {list(gamma0)}, M_0 = {sp.sstr(M0.tolist())} (M_0 gamma_0 = 0), "
             f"[chi - zeta, Omega_0]_({i + 1},{j + 1}) = {C[i, j]}")
    ok = in_V and printed_agree and E_n(n).T * z == sp.zeros(1, n)
    return fact(ok and C[i, j] != 0, "explicit exact point: " + where)


@claim("S4:zeta-vs-chi", uses=("Th:Re", "eq:xiVnD", "eq:solManakov", "P:n3special", "eq:V-velocity"))
def s4_zeta_vs_chi() -> Verdict:
    def n3(n):
        M0, g = generic_vertical(3)
        return zeta(M0, g) - chi(inverse_closed_form(M0, g))

    same3 = sym_checks(n3, (3,), label="zeta-chi-3")
    points = [_report(n) for n in (4, 5, 6)]
    return Verdict.of_parts([
        Verdict.decide(same3).as_part("n = 3: zeta = chi on V"),
        *[Verdict.decide(p).as_part(f"n = {n}: [chi - zeta, Omega_0] != 0 at an explicit point of V")
          for n, p in zip((4, 5, 6), points, strict=True)],
    ], n_values=(3, 4, 5, 6))


