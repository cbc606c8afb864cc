r"""Section 4 of the paper *as printed* — a literal transcription, written once.

Each function is one displayed formula of chaplygin-sphere-nd.tex, tagged with its ledger id and
the LaTeX source line, transcribed symbol by symbol (signs, factors, the order in $u\wedge v$).
Nothing here is derived, corrected or simplified; no derivation imports this module (DESIGN.md
rule 1) — only proofs/ compare it with :mod:`symbolic.axisymmetric`, :mod:`symbolic.axisym_inverse`
and :mod:`symbolic.vertical`.

Conventions of the paper: $u\wedge v = uv^T - vu^T$; $x = \gamma_n = \langle\gamma, E_n\rangle$;
$\hat{}$ the hat map. Arguments are SymPy matrices (column vectors for $\gamma$, $E_n$).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.algebra import basis_vector, commutator, hat, wedge

__all__ = [
    "SOURCE", "J_axisymm", "inertia_3d", "inertia_axisymm", "L_axisymm", "velocity_form_rhs",
    "velocity_form_lhs", "Delta", "images_of_basis", "C_block", "block_diagonal", "det_L", "measure_density_M",
    "measure_density_Omega", "Omega_inverse", "K", "aux_inversion", "system_U_Z", "U_solution",
    "Y_solution", "action", "tori_generic_dimension", "curve_Th_Re", "Omega_corollary", "V_velocity", "Itilde_3d", "euler_3d_rhs", "zeta_3d_matrix",
    "zeta_3d_wedge", "zeta_Th_Re", "Omega0_Th_Re", "zeta_xiVnD", "mu_n3", "mu_n3_equation",
    "Itilde", "Itilde_gamma", "Itilde_gamma_En", "chi", "Omega0_Manakov",
    "vertical_torus_dimension",
]

#: claim id -> LaTeX source lines transcribed in this module.
SOURCE = {
    "eq:axisymm": (366, 368), "eq:M-O-axi-symm": (372, 376, 380), "eq:Delta": (389,),
    "P:Measure": (398, 410, 411, 412, 421, 422, 423, 424, 428, 430), "P:inversion": (441, 446, 447, 448),
    "eq:aux-inversion": (460, 466, 467, 472, 479), "eq:action": (495,),
    "eq:V-velocity": (514, 515), "eq:xiV3D": (522, 525, 526, 527, 539, 540, 541, 542, 543, 558),
    "Th:Re": (587, 591, 592, 610, 614), "Th:Re-corollary": (628,), "Th:Re-tori": (579, 580, 904, 905, 906), "eq:xiVnD": (642, 643, 644), "P:n3special": (666, 671, 674),
    "eq:itildendim": (708, 712), "eq:solManakov": (728, 736),
    "Th:Re-tori:frequencies": (579, 580),
}


def _E(n: int) -> sp.Matrix:
    return basis_vector(n, n - 1)


def _dot(u: sp.Matrix, v: sp.Matrix) -> sp.Expr:
    return (u.T * v)[0, 0]


# -- eq:axisymm, line 366:  \J =\mbox{Id}_n+a E_nE_n^t
def J_axisymm(n, a):
    """eq:axisymm (line 366): $\\mathbb{J} = \\mathrm{Id}_n + a E_n E_n^t$."""
    return sp.eye(n) + a * _E(n) * _E(n).T


# -- eq:axisymm, line 368: "the 3x3 inertia matrix is the diagonal matrix with entries (2+a,2+a,2)"
def inertia_3d(a):
    """eq:axisymm (line 368): $\\mathbb{I} = \\mathrm{diag}(2+a, 2+a, 2)$ for $n = 3$."""
    return sp.diag(2 + a, 2 + a, 2)


# -- eq:M-O-axi-symm, line 372:  \I (\Omega) =2\Omega +a (\Omega E_n) \wedge E_n
def inertia_axisymm(Omega, a):
    """eq:M-O-axi-symm (line 372): $\\mathbb{I}(\\Omega) = 2\\Omega + a(\\Omega E_n)\\wedge E_n$."""
    E = _E(Omega.rows)
    return 2 * Omega + a * wedge(Omega * E, E)


# -- eq:M-O-axi-symm, line 376: M=L_\gamma(\Omega)= 2\Omega + a (\Omega E_n) \wedge E_n + b(\Omega \gamma) \wedge \gamma
def L_axisymm(Omega, gamma, a, b):
    """eq:M-O-axi-symm (line 376): $L_\\gamma(\\Omega) = 2\\Omega + a(\\Omega E_n)\\wedge E_n + b(\\Omega\\gamma)\\wedge\\gamma$."""
    E = _E(Omega.rows)
    return 2 * Omega + a * wedge(Omega * E, E) + b * wedge(Omega * gamma, gamma)


# -- eq:M-O-axi-symm, line 380:
#    2\dot \Omega + a(\dot \Omega E_n)\wedge E_n + b (\dot \Omega \gamma )\wedge \gamma = a [ (\Omega E_n)\wedge E_n , \Omega]
def velocity_form_lhs(Omega_dot, gamma, a, b):
    """eq:M-O-axi-symm (line 380), left side: $2\\dot\\Omega + a(\\dot\\Omega E_n)\\wedge E_n + b(\\dot\\Omega\\gamma)\\wedge\\gamma$."""
    E = _E(Omega_dot.rows)
    return 2 * Omega_dot + a * wedge(Omega_dot * E, E) + b * wedge(Omega_dot * gamma, gamma)


def velocity_form_rhs(Omega, a):
    """eq:M-O-axi-symm (line 380), right side: $a[(\\Omega E_n)\\wedge E_n, \\Omega]$."""
    E = _E(Omega.rows)
    return a * commutator(wedge(Omega * E, E), Omega)


# -- eq:Delta, line 389:  \Delta(x) = (2+a)(2+b)-abx^2
def Delta(x, a, b):
    """eq:Delta (line 389): $\\Delta(x) = (2+a)(2+b) - abx^2$."""
    return (2 + a) * (2 + b) - a * b * x**2


# -- P:Measure, lines 410-412 (the four images of the basis), x = <gamma, E_n>
def images_of_basis(gamma, w_i, w_j, a, b):
    """P:Measure (lines 410-412): dict name -> (argument, printed image) for
    $E_n\\wedge w_j$, $\\gamma\\wedge w_j$, $E_n\\wedge\\gamma$, $w_i\\wedge w_j$."""
    E = _E(gamma.rows)
    x = _dot(gamma, E)
    return {
        "E_n^w_j": (wedge(E, w_j), (2 + a) * wedge(E, w_j) + b * x * wedge(gamma, w_j)),
        "gamma^w_j": (wedge(gamma, w_j), a * x * wedge(E, w_j) + (2 + b) * wedge(gamma, w_j)),
        "E_n^gamma": (wedge(E, gamma), (2 + a + b) * wedge(E, gamma)),
        "w_i^w_j": (wedge(w_i, w_j), 2 * wedge(w_i, w_j)),
    }


# -- P:Measure, line 428:  C=\begin{pmatrix} 2+a  & ax \\ bx & 2+b \end{pmatrix}
def C_block(x, a, b):
    """P:Measure (line 428): $C = \\begin{pmatrix} 2+a & ax \\\\ bx & 2+b\\end{pmatrix}$."""
    return sp.Matrix([[2 + a, a * x], [b * x, 2 + b]])


# -- P:Measure, lines 421-424: the block-diagonal form of L_gamma
def block_diagonal(n, x, a, b):
    """P:Measure (lines 421-424): ``\\begin{pmatrix} C_1 & 0 & 0 & \\cdots & 0 \\\\ [...] & C_{n-2} &0 & 0
    \\\\ 0 & \\cdots & 0 & 2+a+b & 0 \\\\ 0 & \\cdots & 0 & 0 & 2 \\mbox{Id}_{(n-2)(n-3)/2}\\end{pmatrix}``
    with all $C_j = C$ (line 428)."""
    blocks = [C_block(x, a, b)] * (n - 2) + [sp.Matrix([[2 + a + b]])]
    blocks += [sp.Matrix([[2]])] * ((n - 2) * (n - 3) // 2)
    return sp.diag(*blocks)


# -- P:Measure, line 430: det L_gamma = (2+a+b) 2^{(n-2)(n-3)/2} Delta(x)^{n-2}
def det_L(n, x, a, b):
    """P:Measure (line 430): $\\det L_\\gamma = (2+a+b)\\,2^{(n-2)(n-3)/2}\\,\\Delta(x)^{n-2}$."""
    return (2 + a + b) * sp.Integer(2) ** ((n - 2) * (n - 3) // 2) * Delta(x, a, b) ** (n - 2)


# -- P:Measure, line 398:  \mu = \frac{1}{\Delta(x)^{\frac{n-2}{2}}}\,dM\, d\gamma = \Delta(x)^{\frac{n-2}{2}}\,d\Omega\, d\gamma
def measure_density_M(n, x, a, b):
    """P:Measure (line 398): density of $\\mu$ with respect to $dM\\,d\\gamma$: $\\Delta(x)^{-(n-2)/2}$."""
    return Delta(x, a, b) ** (-sp.Rational(n - 2, 2))


def measure_density_Omega(n, x, a, b):
    """P:Measure (line 398): density of $\\mu$ with respect to $d\\Omega\\,d\\gamma$: $\\Delta(x)^{(n-2)/2}$."""
    return Delta(x, a, b) ** sp.Rational(n - 2, 2)


# -- P:inversion, lines 441-448
def K(M, gamma, a, b):
    """P:inversion (lines 446-448): $K = abx(M\\gamma)\\wedge E_n - a(2+b)(ME_n)\\wedge E_n + abx(ME_n)\\wedge\\gamma
    - b(2+a)(M\\gamma)\\wedge\\gamma - \\frac{ab(4+a+b)\\langle M\\gamma, E_n\\rangle}{2+a+b}\\gamma\\wedge E_n$."""
    E = _E(M.rows)
    x = _dot(gamma, E)
    return (a * b * x * wedge(M * gamma, E) - a * (2 + b) * wedge(M * E, E)
            + a * b * x * wedge(M * E, gamma) - b * (2 + a) * wedge(M * gamma, gamma)
            - a * b * (4 + a + b) * _dot(M * gamma, E) / (2 + a + b) * wedge(gamma, E))


def Omega_inverse(M, gamma, a, b):
    """P:inversion (line 441): $\\Omega = \\tfrac12 M + \\frac{1}{2\\Delta(x)}K$."""
    x = _dot(gamma, _E(M.rows))
    return sp.Rational(1, 2) * M + K(M, gamma, a, b) / (2 * Delta(x, a, b))


# -- eq:aux-inversion, line 460:  <Omega gamma, E_n> = <M gamma, E_n>/(2+a+b)
def aux_inversion(M, gamma, a, b):
    """eq:aux-inversion (line 460): the printed value of $\\langle\\Omega\\gamma, E_n\\rangle$."""
    return _dot(M * gamma, _E(M.rows)) / (2 + a + b)


# -- lines 466-467: the linear system for U = (Omega E_n)^E_n, Z = (Omega gamma)^E_n
def system_U_Z(U, Z, M, gamma, a, b):
    """eq:aux-inversion (lines 466-467): the two residuals (lhs - rhs) of
    $(2+a)U + bxZ = (ME_n)\\wedge E_n + b\\frac{\\langle M\\gamma,E_n\\rangle}{2+a+b}\\gamma\\wedge E_n$,
    $axU + (2+b)Z = (M\\gamma)\\wedge E_n$."""
    E = _E(M.rows)
    x = _dot(gamma, E)
    r1 = (2 + a) * U + b * x * Z - (wedge(M * E, E)
                                    + b * _dot(M * gamma, E) / (2 + a + b) * wedge(gamma, E))
    r2 = a * x * U + (2 + b) * Z - wedge(M * gamma, E)
    return r1, r2


# -- line 472
def U_solution(M, gamma, a, b):
    """eq:aux-inversion (line 472): $(\\Omega E_n)\\wedge E_n = \\frac{1}{\\Delta}\\big((2+b)(ME_n)\\wedge E_n
    - bx(M\\gamma)\\wedge E_n + \\frac{b(2+b)\\langle M\\gamma,E_n\\rangle}{2+a+b}\\gamma\\wedge E_n\\big)$."""
    E = _E(M.rows)
    x = _dot(gamma, E)
    return ((2 + b) * wedge(M * E, E) - b * x * wedge(M * gamma, E)
            + b * (2 + b) * _dot(M * gamma, E) / (2 + a + b) * wedge(gamma, E)) / Delta(x, a, b)


# -- line 479
def Y_solution(M, gamma, a, b):
    """eq:aux-inversion (line 479): $(\\Omega\\gamma)\\wedge\\gamma = \\frac{1}{\\Delta}\\big(-ax(ME_n)\\wedge\\gamma
    + (2+a)(M\\gamma)\\wedge\\gamma + \\frac{a(2+a)\\langle M\\gamma,E_n\\rangle}{2+a+b}\\gamma\\wedge E_n\\big)$."""
    E = _E(M.rows)
    x = _dot(gamma, E)
    return (-a * x * wedge(M * E, gamma) + (2 + a) * wedge(M * gamma, gamma)
            + a * (2 + a) * _dot(M * gamma, E) / (2 + a + b) * wedge(gamma, E)) / Delta(x, a, b)


# -- eq:action, line 495:  h\cdot (M, \gamma) = (hMh^{-1}, h\gamma)
def action(h, M, gamma):
    """eq:action (line 495): $h\\cdot(M, \\gamma) = (hMh^{-1}, h\\gamma)$, $h \\in SO(n-1)$."""
    return h * M * h.inv(), h * gamma


# -- eq:V-velocity, lines 514-515
def V_velocity(Omega, gamma, a, b):
    """eq:V-velocity (lines 514-515): the two printed conditions, as expressions that must vanish:
    $(2+b)\\Omega\\gamma + ax\\Omega E_n$ and $\\langle\\Omega\\gamma, E_n\\rangle$."""
    E = _E(Omega.rows)
    x = _dot(gamma, E)
    return (2 + b) * Omega * gamma + a * x * Omega * E, _dot(Omega * gamma, E)


# -- eq:xiV3D, line 522: \tilde \I=\mbox{diag}(2+a+b,2+a+b, 2+b)
def Itilde_3d(a, b):
    """eq:xiV3D (line 522): $\\tilde{\\mathbb{I}} = \\mathrm{diag}(2+a+b, 2+a+b, 2+b)$."""
    return sp.diag(2 + a + b, 2 + a + b, 2 + b)


# -- lines 525-527
def euler_3d_rhs(Omega, a, b):
    """eq:xiV3D (lines 525-527): $\\dot\\Omega_1 = \\frac{a\\Omega_2\\Omega_3}{2+a+b}$,
    $\\dot\\Omega_2 = -\\frac{a\\Omega_1\\Omega_3}{2+a+b}$, $\\dot\\Omega_3 = 0$."""
    O1, O2, O3 = Omega
    return sp.Matrix([a * O2 * O3 / (2 + a + b), -a * O1 * O3 / (2 + a + b), 0])


# -- eq:xiV3D, lines 539-543, first form (matrix with \bar\Omega_3 = third component of Omega_0)
def zeta_3d_matrix(Omega0, a, b):
    """eq:xiV3D (lines 539-542): $\\zeta = \\frac{-a}{2+a+b}\\begin{pmatrix}0&-\\bar\\Omega_3&0\\\\
    \\bar\\Omega_3&0&0\\\\0&0&0\\end{pmatrix}$."""
    O3 = Omega0[2]
    return -a / (2 + a + b) * sp.Matrix([[0, -O3, 0], [O3, 0, 0], [0, 0, 0]])


def zeta_3d_wedge(Omega0, a, b):
    """eq:xiV3D (line 543): $\\zeta = \\frac{-a}{2+a+b}\\big(\\hat\\Omega_0 - (\\hat\\Omega_0E_3)\\wedge E_3\\big)$."""
    W = hat(Omega0)
    E = _E(3)
    return -a / (2 + a + b) * (W - wedge(W * E, E))


# -- Th:Re, lines 591-592
def zeta_Th_Re(M0, gamma0, a, b):
    """Th:Re (lines 591-592): $\\zeta = -\\frac{a(2+b(1-x_0^2))}{2\\Delta(x_0)}M_0 + \\frac{1}{2\\Delta(x_0)}
    \\big(a(2+b)(M_0E_n)\\wedge E_n - abx_0(M_0E_n)\\wedge\\gamma_0\\big)$."""
    E = _E(M0.rows)
    x0 = _dot(E, gamma0)
    D = Delta(x0, a, b)
    return (-a * (2 + b * (1 - x0**2)) / (2 * D) * M0
            + (a * (2 + b) * wedge(M0 * E, E) - a * b * x0 * wedge(M0 * E, gamma0)) / (2 * D))


# -- Th:Re-tori, lines 579-580 (prose) and lines 904-906 (n = 4)
def tori_generic_dimension(n):
    """Th:Re-tori (lines 579-580), prose — the claim as a number. The sentence: ``Since $\\SO(n-1)$ is
    compact, the corresponding solutions on $P$ are quasi-periodic on tori whose generic dimension
    is $\\mbox{rank}(\\SO(n-1))=[\\frac{n-1}{2}]$``; for $n = 4$ (lines 904-906): ``Considering that
    $\\SO(3)$ has rank 1, we conclude that $\\mathcal{V}$ is foliated by periodic orbits``. Returned:
    the claimed generic torus dimension $[\\frac{n-1}{2}]$ (for every $-1 \\le a \\le 1$, $b > 0$)."""
    return (n - 1) // 2


# -- Th:Re, line 587: M(t) = \exp(\zeta t) M_0 \exp(-\zeta t), \gamma(t)= \exp(\zeta t) \gamma_0
def curve_Th_Re(zeta, M0, gamma0, t):
    """Th:Re (line 587): $M(t) = \\exp(\\zeta t) M_0 \\exp(-\\zeta t)$, $\\gamma(t) = \\exp(\\zeta t)\\gamma_0$."""
    return (zeta * t).exp() * M0 * (-zeta * t).exp(), (zeta * t).exp() * gamma0


# -- Th:Re-corollary, line 628: \Omega(t) = \exp(\zeta t) \Omega_0 \exp(-\zeta t)
def Omega_corollary(zeta, Omega0, t):
    """Th:Re-corollary (line 628): $\\Omega(t) = \\exp(\\zeta t)\\Omega_0\\exp(-\\zeta t)$."""
    return (zeta * t).exp() * Omega0 * (-zeta * t).exp()


# -- Th:Re, line 610
def Omega0_Th_Re(M0, gamma0, zeta, a, b):
    """Th:Re (line 610): $\\Omega_0 = -\\zeta + \\frac{(2+b)}{\\Delta(x_0)}M_0$."""
    x0 = _dot(_E(M0.rows), gamma0)
    return -zeta + (2 + b) / Delta(x0, a, b) * M0


# -- eq:xiVnD, lines 642-644
def zeta_xiVnD(Omega0, gamma0, a, b):
    """eq:xiVnD (lines 642-644): $\\zeta = -\\frac{a(2+b(1-x_0^2))}{\\Delta(x_0)}(\\Omega_0 - (\\Omega_0E_n)\\wedge E_n)
    - \\frac{abx_0}{\\Delta(x_0)}(\\Omega_0E_n)\\wedge(\\gamma_0 - x_0E_n)$."""
    E = _E(Omega0.rows)
    x0 = _dot(E, gamma0)
    D = Delta(x0, a, b)
    return (-a * (2 + b * (1 - x0**2)) / D * (Omega0 - wedge(Omega0 * E, E))
            - a * b * x0 / D * wedge(Omega0 * E, gamma0 - x0 * E))


# -- P:n3special, line 674
def mu_n3(x0, a, b):
    """P:n3special (line 674): $\\mu = -\\frac{(1-x_0^2)(2+b)}{x_0(2+a+b)}$."""
    return -(1 - x0**2) * (2 + b) / (x0 * (2 + a + b))


# -- P:n3special, line 671
def mu_n3_equation(mu, x0, a, b):
    """P:n3special (line 671): the scalar factor $-\\mu x_0\\frac{a+b+2}{2+b} - 1 + x_0^2$ multiplying $\\hat\\Omega_0E_3$."""
    return -mu * x0 * (a + b + 2) / (2 + b) - 1 + x0**2


# -- eq:itildendim, line 708
def Itilde(Omega, a, b):
    """eq:itildendim (line 708): $\\tilde{\\mathbb{I}}(\\Omega) = (2+b)\\Omega + a(\\Omega E_n)\\wedge E_n$."""
    E = _E(Omega.rows)
    return (2 + b) * Omega + a * wedge(Omega * E, E)


# -- line 712
def Itilde_gamma(Omega, gamma, a, b):
    """eq:itildendim (line 712): $\\tilde{\\mathbb{I}}(\\Omega)\\gamma = (2+b)\\Omega\\gamma + ax\\Omega E_n
    + a\\langle\\Omega\\gamma, E_n\\rangle E_n$."""
    E = _E(Omega.rows)
    x = _dot(gamma, E)
    return (2 + b) * Omega * gamma + a * x * Omega * E + a * _dot(Omega * gamma, E) * E


def Itilde_gamma_En(Omega, gamma, a, b):
    """eq:itildendim (line 712): $\\langle\\tilde{\\mathbb{I}}(\\Omega)\\gamma, E_n\\rangle = (2+a+b)\\langle\\Omega\\gamma, E_n\\rangle$."""
    return (2 + a + b) * _dot(Omega * gamma, _E(Omega.rows))


# -- eq:solManakov, line 728
def chi(Omega0, a, b):
    """eq:solManakov (line 728): $\\chi = \\frac{-a}{2+a+b}\\big(\\Omega_0 - (\\Omega_0E_n)\\wedge E_n\\big)$."""
    E = _E(Omega0.rows)
    return -a / (2 + a + b) * (Omega0 - wedge(Omega0 * E, E))


# -- line 736
def Omega0_Manakov(Omega0, chi_, a, b):
    """eq:solManakov (line 736): $\\Omega_0 = -\\chi + \\frac{1}{2+a+b}\\tilde{\\mathbb{I}}(\\Omega_0)$ (right side)."""
    return -chi_ + Itilde(Omega0, a, b) / (2 + a + b)


# -- Th:Re-tori, lines 579-580: "Since $\SO(n-1)$ is compact, the corresponding solutions on $P$ are
# quasi-periodic on tori whose generic dimension is $\mbox{rank}( \SO(n-1))= [\frac{n-1}{2} ]$."
def vertical_torus_dimension(n):
    """Th:Re-tori:frequencies (lines 579-580), our reading as a number: a generic solution on
    $\\mathcal{V}$ is quasi-periodic with $\\mathrm{rank}\\,SO(n-1) = [\frac{n-1}{2}]$ independent
    frequencies (the paper states no condition on $a$)."""
    return sp.floor(sp.Rational(n - 1, 2))
