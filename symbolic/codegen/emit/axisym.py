r"""Kernels of the axisymmetric $n$-dimensional sphere (Section 4), from the derived expressions.

Sources (all *derived*, none printed): $\Delta$ from :mod:`symbolic.axisymmetric` (the
determinant of the block $C$), the coefficients $c_0..c_5$ of $L_\gamma^{-1}$ from
:mod:`symbolic.axisym_inverse` (equivariant ansatz, proved in the ledger row P:inversion), the
coefficients $\kappa$ of $\zeta$ and $\tilde\kappa$ of $\chi$ from :mod:`symbolic.vertical`, and
the definitions of :mod:`symbolic.model` for $L_\gamma$, the equations of motion, the energy and
$p(\lambda, \sigma)$.

Two kinds of kernel:

* *coefficient kernels* for every $n$: ``inverse_coefficients(x, a, b)`` (six scalars,
  $L_\gamma^{-1}M = \sum_k c_k T_k(M)$) and ``vertical_coefficients(x, a, b)`` ($\kappa$,
  $\tilde\kappa$). The hand-written runtime :mod:`runtime.axisym` applies them to batches of
  $n\times n$ matrices (einsum); ``generated/`` stays free of the $n$-dependent assembly;
* *component kernels* for $n = 3$ and $n = 4$ (faster than the matrix form for small $n$): $M$ in
  the coordinates ``vec`` of :mod:`symbolic.algebra` (entries $M_{ij}$, $i<j$, lexicographic:
  $(M_{12}, M_{13}, M_{23})$ for $n = 3$, $(M_{12}, M_{13}, M_{14}, M_{23}, M_{24}, M_{34})$ for
  $n = 4$), $\gamma \in \mathbb{R}^n$ with $x = \gamma_n$.

$\Delta$ is emitted as $2(2+a+b) + ab\,(1-x)(1+x)$ (proved equal to the derived $\Delta$ in
proofs/s4_kernel_forms.py, row K:Delta). Measured over the hard cases ($|x| \to 1$, $a \in [-1, 1]$,
$b$ up to $10^{12}$) this form and the naive $(2+a)(2+b) - abx^2$ are both within 1.1 ulp of the
50-digit value: $\Delta \ge 2+b$ is never the small difference of large terms, so no stable rewrite
is *needed*; the row only certifies the form the kernels evaluate.
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from chaplygin_nd.symbolic.algebra import killing, skew_symbols, vec
from chaplygin_nd.symbolic.axisym_inverse import ansatz_terms, inverse_coefficients
from chaplygin_nd.symbolic.axisymmetric import Delta, L_matrix_axisym, a, b, x
from chaplygin_nd.symbolic.codegen.kernels import Argument, Kernel
from chaplygin_nd.symbolic.model import motion
from chaplygin_nd.symbolic.structured_field import PAIRS, VECTORS, g, s, structured_weights
from chaplygin_nd.symbolic.vertical import chi, chi_coefficient, inertia_tilde, zeta_coefficient

__all__ = ["kernels", "stable_Delta", "DELTA_SYMBOL", "coefficient_kernels", "component_kernels",
           "M_symbols", "gamma_symbols", "p_coefficients"]

#: A placeholder for $\Delta(x)$ in the coefficient kernels (substituted by :func:`stable_Delta`).
DELTA_SYMBOL = sp.Symbol("Delta_x", positive=True)


def stable_Delta(x_=x, a_=a, b_=b) -> sp.Expr:
    r"""$\Delta(x) = 2(2+a+b) + ab(1-x)(1+x)$ — eq:Delta in the form the kernels evaluate (equal to
    the derived :func:`symbolic.axisymmetric.Delta`, row K:Delta; no accuracy gain over the naive
    form was measured, see the module docstring); any real $x, a, b$."""
    return 2 * (2 + a_ + b_) + a_ * b_ * ((1 - x_) * (1 + x_))


def _with_stable_Delta(expr: sp.Expr) -> sp.Expr:
    """Rewrite a rational function of (a, b, x) whose denominator contains the derived Delta
    (up to sign) with Delta replaced by :func:`stable_Delta`; checked exactly."""
    num, den = sp.fraction(sp.factor(expr))
    q, r = sp.div(sp.expand(den), Delta(), a, b, x)
    if r != 0 or x in q.free_symbols:
        return expr
    out = num / (q * stable_Delta())
    if sp.expand(sp.numer(sp.together(out - expr))) != 0:  # pragma: no cover
        raise ArithmeticError("stable rewrite changed the value")
    return out


def M_symbols(n: int) -> tuple[sp.Matrix, tuple[sp.Symbol, ...]]:
    """The generic skew matrix $M$ of size ``n`` and its coordinates (``vec`` order)."""
    M = skew_symbols("M", n)
    return M, tuple(vec(M))


def gamma_symbols(n: int) -> tuple[sp.Symbol, ...]:
    r"""Symbols $\gamma_1..\gamma_n$ (real)."""
    return sp.symbols(f"gamma1:{n + 1}", real=True)


@cache
def p_coefficients(n: int) -> sp.Matrix:
    r"""Coefficients of $p(\lambda, \sigma) = \det(M + \sigma\gamma\gamma^T - \lambda\,\mathrm{Id}_n)$
    (eq:pol-first-integrals) as an $(n+1)\times 2$ matrix: entry $(i, j)$ multiplies
    $\lambda^i\sigma^j$ ($p$ is affine in $\sigma$: $\gamma\gamma^T$ has rank one)."""
    lam, sig = sp.symbols("lambda sigma")
    M, _ = M_symbols(n)
    g = sp.Matrix(gamma_symbols(n))
    A = M + sig * g * g.T - lam * sp.eye(n)
    p = sp.Poly(A.det(method="berkowitz"), lam, sig)
    if p.degree(sig) > 1:  # pragma: no cover
        raise ArithmeticError("p is not affine in sigma")
    return sp.Matrix(n + 1, 2, lambda i, j: sp.expand(p.coeff_monomial(lam**i * sig**j)))


def coefficient_kernels() -> list[Kernel]:
    """Kernels valid for every n: Delta, the inverse coefficients, kappa and kappa-tilde."""
    X, A_, B_ = (Argument("x", (x,), True), Argument("a", (a,), True), Argument("b", (b,), True))
    cs = [_with_stable_Delta(c) for c in inverse_coefficients()]
    kappa = _with_stable_Delta(zeta_coefficient())
    kappa_t = sp.factor(chi_coefficient())
    S_, G_ = Argument("s", (s,), True), Argument("gg", (g,), True)
    w, u = structured_weights()
    weights = [_with_stable_Delta(e) for e in w + u]
    layout = ", ".join(f"{VECTORS[i]}^{VECTORS[j]}" for i, j in PAIRS)
    return [
        Kernel("Delta", ("eq:Delta", "K:Delta"),
               "Delta(x) = (2+a)(2+b) - a b x^2 (eq:Delta), evaluated as 2(2+a+b) + ab(1-x)(1+x)\n"
               "    (row K:Delta: equal forms). Domain: any real x, a, b; positive for |x| <= 1, |a| <= 1, b > 0.",
               (X, A_, B_), sp.Matrix([stable_Delta()]), (1,)),
        Kernel("inverse_coefficients", ("P:inversion", "K:Delta"),
               "c_0..c_5 of Omega = L_gamma^{-1} M = sum_k c_k T_k(M) (P:inversion, derived by the\n"
               "    ansatz of symbolic.axisym_inverse), T = (M, (M g)^g, (M E)^E, (M g)^E, (M E)^g,\n"
               "    <M g, E> g^E), u^v = u v^T - v u^T. Any n >= 3; x = gamma_n, |gamma| = 1; Delta, 2+a+b != 0.",
               (X, A_, B_), sp.Matrix(cs), (6,)),
        Kernel("vertical_coefficients", ("Th:Re", "eq:solManakov", "K:Delta"),
               "(kappa, kappa_t): zeta = kappa M0 - L^{-1} M0 (Th:Re, derived in symbolic.vertical) and\n"
               "    chi = kappa_t Itilde(Omega0) - Omega0 (eq:solManakov). Any n >= 3, x = gamma0_n; on V.",
               (X, A_, B_), sp.Matrix([kappa, kappa_t]), (2,)),
        Kernel("structured_field_weights", ("S4:structured-field", "eq:motion-general", "P:inversion", "K:Delta"),
               "Weights of the O(n^2) full field (S4:structured-field, derived in symbolic.structured_field):\n"
               "    dM/dt = sum w_ij V_i^V_j, dgamma/dt = sum u_i V_i, V = (M^2 gamma, M^2 E, M gamma, M E, gamma, E);\n"
               f"    out[:{len(PAIRS)}] = w over the pairs ({layout}),\n"
               f"    out[{len(PAIRS)}:] = u. x = gamma_n, s = (M gamma)_n, gg = <gamma, gamma>; any n >= 3; Delta, 2+a+b != 0.",
               (X, S_, G_, A_, B_), sp.Matrix(weights), (len(weights),)),
    ]


def component_kernels(n: int) -> list[Kernel]:
    """Component kernels for one n (3 or 4): L_gamma, Omega, the field, energy, p, zeta, chi."""
    M, m = M_symbols(n)
    g_syms = gamma_symbols(n)
    gamma = sp.Matrix(g_syms)
    W = skew_symbols("Omega", n)
    w = tuple(vec(W))
    Ma, Ga, Wa = Argument("M", m), Argument("gamma", g_syms), Argument("Omega", w)
    Aa, Ba = Argument("a", (a,), True), Argument("b", (b,), True)
    xn = g_syms[-1]
    cs = [_with_stable_Delta(c).subs(x, xn) for c in inverse_coefficients()]
    Omega = sum((c * T for c, T in zip(cs, ansatz_terms(M, gamma))), sp.zeros(n, n))
    Mdot, gdot = motion(M, gamma, Omega)
    energy = killing(M, Omega) / 2
    kappa = _with_stable_Delta(zeta_coefficient()).subs(x, xn)
    zeta0 = kappa * M - Omega  # the assembly of symbolic.vertical.zeta, with stable coefficients
    d = len(m)
    return [
        Kernel(f"L_matrix_axisym_{n}d", ("eq:M-O", "eq:axisymm"),
               f"Matrix of L_gamma (eq:M-O with J = Id + a E_n E_n^T, eq:axisymm) in the basis E_i^E_j\n"
               f"    (i<j) of so({n}): vec(M) = L @ vec(Omega). Any gamma in R^{n}.",
               (Ga, Aa, Ba), L_matrix_axisym(gamma), (d, d)),
        Kernel(f"angular_velocity_axisym_{n}d", ("P:inversion", "K:Delta"),
               f"vec(Omega) = vec(L_gamma^{{-1}} M) (P:inversion, derived coefficients), n = {n};\n"
               f"    M as vec (entries i<j), gamma on S^{n - 1}, x = gamma_{n}.",
               (Ma, Ga, Aa, Ba), vec(Omega), (d,)),
        Kernel(f"vector_field_axisym_{n}d", ("eq:motion-general", "P:inversion", "K:Delta"),
               f"(vec dM/dt, dgamma/dt) = ([M, Omega], -Omega gamma) (eq:motion-general), Omega from\n"
               f"    P:inversion; shape (..., {d + n}). Domain as angular_velocity_axisym_{n}d.",
               (Ma, Ga, Aa, Ba), sp.Matrix.vstack(vec(Mdot), gdot), (d + n,)),
        Kernel(f"energy_axisym_{n}d", ("S2.2:energy", "P:inversion", "K:Delta"),
               "H = 1/2 <M, Omega>_kappa, Killing metric -1/2 tr (S2.2:energy), Omega = L_gamma^{-1} M.\n"
               "    Domain as angular_velocity_axisym.",
               (Ma, Ga, Aa, Ba), sp.Matrix([energy]), (1,)),
        Kernel(f"p_coefficients_{n}d", ("eq:pol-first-integrals",),
               f"Coefficients of p(lambda, sigma) = det(M + sigma g g^T - lambda Id) (eq:pol-first-integrals):\n"
               f"    out[..., i, j] multiplies lambda^i sigma^j; shape (..., {n + 1}, 2). Any M, gamma.",
               (Ma, Ga), p_coefficients(n), (n + 1, 2)),
        Kernel(f"zeta_{n}d", ("Th:Re", "K:Delta"),
               f"vec(zeta) for (M0, gamma0) in V (Th:Re, derived): zeta = kappa(x0) M0 - L^{{-1}} M0, zeta E_n = 0.\n"
               f"    Domain: M0 gamma0 = 0, gamma0 on S^{n - 1}.",
               (Ma, Ga, Aa, Ba), vec(zeta0), (d,)),
        Kernel(f"chi_{n}d", ("eq:solManakov",),
               "vec(chi) = vec(kappa_t Itilde(Omega0) - Omega0), Itilde = I + b Id (eq:solManakov, derived).\n"
               "    Domain: any Omega0 (the Manakov solution needs (Omega0, gamma0) in V).",
               (Wa, Aa, Ba), vec(chi(W)), (d,)),
        Kernel(f"Itilde_{n}d", ("eq:Manakov", "eq:itildendim"),
               "vec(Itilde(Omega)) = vec(J Omega + Omega J + b Omega), J of eq:axisymm (eq:Manakov).",
               (Wa, Aa, Ba), vec(inertia_tilde(W)), (d,)),
    ]


def kernels() -> list[Kernel]:
    """The kernel list of ``generated/axisym.py``."""
    return coefficient_kernels() + component_kernels(3) + component_kernels(4)
