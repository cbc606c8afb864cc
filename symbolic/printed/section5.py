r"""Section 5 of the paper *as printed* — a literal transcription, written once.

Each function is one displayed formula of chaplygin-sphere-nd.tex (Section 5, "The 4-dimensional
Chaplygin sphere"), tagged with its ledger id and the LaTeX source line, transcribed symbol by
symbol. Nothing here is derived, corrected or simplified; no derivation imports this module
(DESIGN.md rule 1) — only ``proofs/s5_*`` compare it with :mod:`symbolic.fourd` and
:mod:`symbolic.reduction.reduced_n4`.

Vectors are SymPy 3x1 matrices ($k, u, q, \xi, \eta$); $x$, $a$, $b$ and the invariants are SymPy
expressions. $\Delta(x) = (2+a)(2+b) - abx^2$ is eq:Delta (line 389) as printed in Section 4.
"""

from __future__ import annotations

import sympy as sp

__all__ = [
    "SOURCE", "Delta", "motion_n4", "F1", "F2", "F3", "charpoly", "H", "H_set", "V_set",
    "k_of", "u_of", "xi_of", "eta_of", "measure_density", "action", "velocity_action",
    "isotropy_dimension", "Lambda", "princ_minors",
    "red_system", "red_F2", "red_F3", "red_H", "red_measure_density", "red_measure_on_R", "H_SO3", "V_SO3", "A_on_J",
    "H_linear_system", "H_linear_solution", "omega_squared", "motion_velocity", "steady_rotation",
    "euler_jacobi_torus_dimension", "reconstruction_statement", "so3_rank",
]

#: claim id -> LaTeX source lines transcribed in this module.
SOURCE = {
    "eq:motion-n4": (764, 765), "S5:F123": (771, 772, 776), "S5:H4D": (780,),
    "S5:HV4D": (787, 788, 789), "S5:ku": (798,), "eq:inverse-Leg": (804, 805),
    "S5:measure4D": (811,), "S5:SO3-action": (819, 821, 825, 971), "eq:PrincMinors": (837, 842),
    "eq:red-system": (857, 858, 859, 860, 862, 863, 864, 865), "S5:red-integrals": (872, 873, 874),
    "S5:red-measure": (878, 880, 882), "S5:H-SO3": (894,), "S5:V-SO3": (898,), "eq:A-on-J": (916,),
    "S5:H-linear": (922, 926, 930), "eq:Motion-Velocity": (947, 948, 949),
    "P:steady-rot": (958, 961), "S5:EJ-tori": (884, 885), "S5:reconstruction": (885, 904),
}


def _cr(p, r):
    return p.cross(r)


def _dt(p, r):
    return (p.T * r)[0, 0]


def Delta(a, b, x):
    """eq:Delta (line 389): $\\Delta(x) = (2+a)(2+b)-abx^2$."""
    return (2 + a) * (2 + b) - a * b * x**2


# -- eq:motion-n4, lines 764-765:
# \dot k = k\times \eta+ u \times \xi, \dot u = k\times \xi + u\times \eta,
# \dot q =q \times \eta -x\xi, \dot x = \langle q,\xi \rangle
def motion_n4(k, u, q, x, xi, eta):
    """eq:motion-n4 (lines 764-765): $(\\dot k, \\dot u, \\dot q, \\dot x)$."""
    return (_cr(k, eta) + _cr(u, xi), _cr(k, xi) + _cr(u, eta), _cr(q, eta) - x * xi, _dt(q, xi))


# -- S5:F123, lines 771-772
def F1(k, u):
    """S5:F123 (line 771): $F_1 = \\langle k,u\\rangle$."""
    return _dt(k, u)


def F2(k, u):
    """S5:F123 (line 772): $F_2 = \\|k\\|^2+\\|u\\|^2$."""
    return _dt(k, k) + _dt(u, u)


def F3(k, u, q, x):
    """S5:F123 (line 772): $F_3=\\| u\\times q\\|^2+x^2\\|k\\|^2+\\langle k,q \\rangle^2-2x\\langle u,k\\times q\\rangle$."""
    uq = _cr(u, q)
    return _dt(uq, uq) + x**2 * _dt(k, k) + _dt(k, q)**2 - 2 * x * _dt(u, _cr(k, q))


# -- S5:F123, line 776:
# p = \lambda^4 -\lambda^3\sigma \|\gamma\|^2 +\lambda^2F_2 +\lambda \sigma F_3 -F_1^2
def charpoly(lam, sig, k, u, q, x):
    """S5:F123 (line 776): $p(\\lambda,\\sigma) = \\lambda^4 -\\lambda^3\\sigma \\|\\gamma\\|^2 +\\lambda^2F_2
    +\\lambda \\sigma F_3 -F_1^2$ (right-hand side as printed)."""
    gamma2 = _dt(q, q) + x**2
    return (lam**4 - lam**3 * sig * gamma2 + lam**2 * F2(k, u) + lam * sig * F3(k, u, q, x)
            - F1(k, u)**2)


# -- S5:H4D, line 780: H=\frac{1}{2} ( \langle u,\xi \rangle +\langle k,\eta\rangle)
def H(k, u, xi, eta):
    """S5:H4D (line 780): $H = \\tfrac12(\\langle u,\\xi\\rangle + \\langle k,\\eta\\rangle)$."""
    return sp.Rational(1, 2) * (_dt(u, xi) + _dt(k, eta))


# -- S5:HV4D, lines 787-789
def H_set(k, u, q, x):
    """S5:HV4D (lines 787-788): the two vector equations of $\\mathcal{H}$,
    $x^2k +\\langle k, q \\rangle q - xq\\times u=0$, $(1-x^2)u- x k\\times q - \\langle u,q \\rangle q=0$."""
    return (x**2 * k + _dt(k, q) * q - x * _cr(q, u), (1 - x**2) * u - x * _cr(k, q) - _dt(u, q) * q)


def V_set(k, u, q, x):
    """S5:HV4D (line 789): the equations of $\\mathcal{V}$, $\\langle u,q \\rangle =0$, $k\\times q +xu =0$."""
    return (_dt(u, q), _cr(k, q) + x * u)


# -- S5:ku, line 798
def k_of(eta, xi, q, x, a, b):
    """S5:ku (line 798): $k=2\\eta+b q\\times (\\eta \\times q)- bx \\xi \\times q$."""
    return 2 * eta + b * _cr(q, _cr(eta, q)) - b * x * _cr(xi, q)


def u_of(eta, xi, q, x, a, b):
    """S5:ku (line 798): $u=(2+a+b)\\xi -b q\\times (\\xi \\times q) +bx \\eta \\times q$."""
    return (2 + a + b) * xi - b * _cr(q, _cr(xi, q)) + b * x * _cr(eta, q)


# -- eq:inverse-Leg, lines 804-805
def xi_of(k, u, q, x, a, b):
    """eq:inverse-Leg (line 804): $\\xi = \\frac{b(2+b)(1-x^2)+\\Delta(x)}{(a+b+2)\\Delta(x)} u
    - \\frac{b(2+b)\\langle u,q \\rangle }{(a+b+2)\\Delta(x)}q - \\frac{bx}{\\Delta(x)} k\\times q$."""
    D = Delta(a, b, x)
    return ((b * (2 + b) * (1 - x**2) + D) / ((a + b + 2) * D) * u
            - b * (2 + b) * _dt(u, q) / ((a + b + 2) * D) * q - b * x / D * _cr(k, q))


def eta_of(k, u, q, x, a, b):
    """eq:inverse-Leg (line 805): $\\eta = \\frac{(a+2+bx^2)}{\\Delta(x)} k
    + \\frac{(a+2)b\\langle k,q \\rangle}{2\\Delta (x)} q + \\frac{bx}{\\Delta(x)} u \\times q$."""
    D = Delta(a, b, x)
    return ((a + 2 + b * x**2) / D * k + (a + 2) * b * _dt(k, q) / (2 * D) * q
            + b * x / D * _cr(u, q))


# -- S5:measure4D, line 811: \mu = \frac{dk \,du \, dq \, dx}{\Delta(x)}
def measure_density(a, b, x):
    """S5:measure4D (line 811): density $1/\\Delta(x)$ of $\\mu$ w.r.t. $dk\\,du\\,dq\\,dx$."""
    return 1 / Delta(a, b, x)


# -- S5:SO3-action, line 819: h\cdot (k, u, (q,x)) = (hk,hu,(hq,x))
def action(h, k, u, q, x):
    """S5:SO3-action (line 819): $h\\cdot(k,u,(q,x)) = (hk, hu, (hq, x))$."""
    return h * k, h * u, h * q, x


# -- S5:SO3-action, lines 821-822: (\xi, \eta) transform to (h\xi, h\eta)
def velocity_action(h, xi, eta):
    """S5:SO3-action (lines 821-822): ``It is seen from \\eqref{eq:inverse-Leg} that $(\\xi, \\eta)$
    transform to $(h\\xi, h\\eta)$``."""
    return h * xi, h * eta


# -- S5:SO3-action, line 825 (prose, our reading): isotropy of the action
def isotropy_dimension(k, u, q, x):
    """S5:SO3-action (lines 825-826), prose — *our reading*, not a displayed formula. The sentence:
    ``The action is not free since points in $P$ where $k$, $u$ and $q$ are parallel have a
    one-dimensional isotropy subgroup isomorphic to $\\SO(2)$``, with line 971: ``points in $P$ with
    non-trivial $\\SO(3)$ isotropy are those for which $k, u$ and $q$ are collinear``. Read as: the
    dimension of the isotropy group of $(k, u, (q, x))$ is 1 when $k, u, q$ are parallel (all on one
    line, zero vectors included) and 0 otherwise."""
    parallel = sp.Matrix.hstack(k, u, q).rank() <= 1
    return 1 if parallel else 0


# -- eq:PrincMinors, lines 837, 842
def Lambda(A, B, E, G, F1, x):
    """eq:PrincMinors (line 837): $\\Lambda = \\begin{pmatrix} A & F_1 & E \\\\ F_1 & B & G \\\\ E & G & 1-x^2
    \\end{pmatrix}$ (with $\\delta^2 = \\det\\Lambda$)."""
    return sp.Matrix([[A, F1, E], [F1, B, G], [E, G, 1 - x**2]])


def princ_minors(A, B, E, G, F1, x):
    """eq:PrincMinors (line 842): the three expressions claimed $\\ge 0$:
    $AB-F_1^2$, $B(1-x^2)-G^2$, $A(1-x^2)-E^2$."""
    return (A * B - F1**2, B * (1 - x**2) - G**2, A * (1 - x**2) - E**2)


# -- eq:red-system, lines 857-865
def red_system(A, B, E, G, F1, x, delta, a, b):
    """eq:red-system (lines 857-865): dict name -> printed right-hand side, names
    ``A, B, E, G, F1, x, delta``."""
    D = Delta(a, b, x)
    S = a + b + 2
    return {
        "A": -2 * b * (2 + b) * G * delta / (S * D) + 2 * b * x / D * (F1 * E - G * A),          # 857
        "B": 2 * b * (2 + b) * G * delta / (S * D) - 2 * b * x / D * (F1 * E - G * A),           # 858
        "E": -a * b * x / (S * D) * G * E - 2 * x / D * F1,                                       # 859
        "G": (b * x / D * (A * (1 - x**2) - E**2 + (2 + b) / (2 + a + b) * G**2)                 # 860
              - x * ((b * (2 + b) * (1 - x**2) + D) / (S * D)) * B + (2 + b - 2 * b * x**2) / D * delta),
        "F1": sp.Integer(0),                                                                      # 862
        "x": G / S,                                                                               # 862
        "delta": (((b * x**2 * S - D) / (S * D)) * A * G                                          # 863
                  - (b * (2 + b) * (1 - x**2) / (S * D)) * B * G
                  + ((2 + b - 2 * b * x**2) / D) * F1 * E                                         # 864
                  + b * (2 + b) / (S * D) * G * (G**2 - E**2) - a * b * x / (S * D) * G * delta),  # 865
    }


# -- S5:red-integrals, lines 872-874
def red_F3(A, B, E, G, x, delta):
    """S5:red-integrals (line 872): $F_3=x^2A+B(1-x^2)+E^2-G^2+2x\\delta$ ($F_2 = A+B$ on the same line)."""
    return x**2 * A + B * (1 - x**2) + E**2 - G**2 + 2 * x * delta


def red_F2(A, B):
    """S5:red-integrals (line 872): $F_2 = A + B$."""
    return A + B


def red_H(A, B, E, G, x, delta, a, b):
    """S5:red-integrals (lines 873-874): $H=\\frac{a+2+bx^2}{2\\Delta(x)} A + \\frac{2+b(1-x^2)}{2\\Delta(x)} B
    - \\frac{b(2+b)}{2(a+b+2)\\Delta(x)} G^2 + \\frac{b(2+a)}{4\\Delta(x)} E^2 +\\frac{bx}{\\Delta}\\delta$."""
    D = Delta(a, b, x)
    return ((a + 2 + b * x**2) / (2 * D) * A + (2 + b * (1 - x**2)) / (2 * D) * B
            - b * (2 + b) / (2 * (a + b + 2) * D) * G**2 + b * (2 + a) / (4 * D) * E**2
            + b * x / D * delta)


# -- S5:red-measure, line 880: \mu_r= \frac{dA dB dE dG dF_1 dx d\delta}{\Delta(x)^2}
def red_measure_density(a, b, x):
    """S5:red-measure (line 880): density $\\Delta(x)^{-2}$ of $\\mu_r$ on $\\mathbb{R}^7$."""
    return 1 / Delta(a, b, x)**2


# -- S5:red-measure, lines 878-882 (prose, our reading of "restriction")
def red_measure_on_R(a, b, x, delta):
    """S5:red-measure (lines 878-882), prose — *our reading*, not a displayed formula. The sentence:
    ``The invariant measure also passes to the quotient. It is the restriction of the volume form
    $\\mu_r$ [...] on the ambient space $\\R^7$ to $\\mathcal{R}$.`` A 7-form has no restriction to
    the 6-dimensional $\\mathcal{R} = \\{\\delta^2 = \\det\\Lambda\\}$; we read "restriction" as the
    induced (Leray residue) measure along the relation the paper writes, $\\Phi = \\delta^2 - \\det
    \\Lambda$: density $\\Delta(x)^{-2}/|\\partial_\\delta\\Phi| = \\Delta(x)^{-2}/(2\\delta)$ with respect to
    $dA\\,dB\\,dE\\,dG\\,dF_1\\,dx$ on the sheet $\\delta > 0$ (built from :func:`red_measure_density`)."""
    return red_measure_density(a, b, x) / (2 * delta)


# -- S5:H-SO3, line 894 / S5:V-SO3, line 898 (equations as expressions that must vanish)
def H_SO3(A, B, E, G, F1, x, delta):
    """S5:H-SO3 (line 894): $F_1=0$, $E=0$, $xA=-\\delta$, $(1-x^2)B-G^2=-x\\delta$ (as lhs - rhs)."""
    return (F1, E, x * A + delta, (1 - x**2) * B - G**2 + x * delta)


def V_SO3(A, B, E, G, F1, x, delta):
    """S5:V-SO3 (line 898): $G=0$, $F_1=0$, $xB=\\delta$, $(1-x^2)A-E^2=x\\delta$ (as lhs - rhs)."""
    return (G, F1, x * B - delta, (1 - x**2) * A - E**2 - x * delta)


# -- eq:A-on-J, line 916
def A_on_J(G, x, h, f2, a, b):
    """eq:A-on-J (line 916): the two printed expressions for $A$:
    $\\frac{(2h(1-x^2)(a+b+2) -G^2)\\Delta(x)}{(a+b+2)(2+a(1-x^2))}$ and $(1-x^2)f_2 -G^2$."""
    D = Delta(a, b, x)
    return ((2 * h * (1 - x**2) * (a + b + 2) - G**2) * D / ((a + b + 2) * (2 + a * (1 - x**2))),
            (1 - x**2) * f2 - G**2)


# -- S5:H-linear, lines 922, 926, 930
def H_linear_system(G, x, h, f2, a, b):
    """S5:H-linear (line 922): $(\\dot G, \\dot x) = (- \\frac{f_2-2bh}{2+a}x, \\frac{G}{a+b+2})$."""
    return (-(f2 - 2 * b * h) / (2 + a) * x, G / (a + b + 2))


def H_linear_solution(t, x0, omega, a, b):
    """S5:H-linear (line 926): $x(t) = x_0 \\cos \\omega t$, $G(t) = -(a+b+2)x_0 \\omega \\sin \\omega t$."""
    return (x0 * sp.cos(omega * t), -(a + b + 2) * x0 * omega * sp.sin(omega * t))


def omega_squared(h, f2, G0, x0, a, b):
    """S5:H-linear (line 930): the two printed expressions for $\\omega^2$:
    $\\frac{f_2-2bh}{2+a}$ and $\\frac{aG_0^2+4h(a+b+2)}{(a+b+2)(2+a(1-x_0^2))}$."""
    return ((f2 - 2 * b * h) / (2 + a),
            (a * G0**2 + 4 * h * (a + b + 2)) / ((a + b + 2) * (2 + a * (1 - x0**2))))


# -- eq:Motion-Velocity, lines 947-949
def motion_velocity(xi, eta, q, x, a, b):
    """eq:Motion-Velocity (lines 947-949): $(\\dot\\xi, \\dot\\eta, \\dot q, \\dot x)$ with
    $\\dot \\xi = \\frac{a(2+b(1-x^2))}{\\Delta(x)} \\xi \\times \\eta - \\frac{ab(b+2)\\langle q,\\xi\\times \\eta
    \\rangle}{(2+a+b)\\Delta (x)} q$, $\\dot \\eta=-\\frac{abx}{\\Delta(x)} q\\times ( \\xi\\times \\eta)$,
    $\\dot q =q \\times \\eta -x\\xi$, $\\dot x = \\langle q,\\xi \\rangle$."""
    D = Delta(a, b, x)
    xe = _cr(xi, eta)
    return (a * (2 + b * (1 - x**2)) / D * xe - a * b * (b + 2) * _dt(q, xe) / ((2 + a + b) * D) * q,
            -a * b * x / D * _cr(q, xe), _cr(q, eta) - x * xi, _dt(q, xi))


# -- P:steady-rot, line 961: M(t)= \exp (-\Omega_0 t) M_0 \exp (\Omega_0 t), \gamma(t)= \exp (-\Omega_0 t) \gamma_0
def steady_rotation(Omega0, M0, gamma0, t):
    """P:steady-rot (line 961): $M(t)= e^{-\\Omega_0 t} M_0 e^{\\Omega_0 t}$, $\\gamma(t)= e^{-\\Omega_0 t}\\gamma_0$."""
    return (-Omega0 * t).exp() * M0 * (Omega0 * t).exp(), (-Omega0 * t).exp() * gamma0


# -- S5:EJ-tori, lines 884-885: "the regular compact level sets of the integrals which have no
# equilibrium points are 2-tori where the flow is quasi-periodic after a time reparametrisation."
def euler_jacobi_torus_dimension():
    r"""S5:EJ-tori (lines 884-885), our reading as a number: on a regular compact level set of
    $(F_1, F_2, F_3, H)$ in $\mathcal{R}$ without equilibria the reduced flow is quasi-periodic with
    2 independent frequencies (the time change of Euler-Jacobi makes it linear on the 2-torus)."""
    return sp.Integer(2)


# -- S5:reconstruction, line 885: "Determining the nature of the reconstruction of this type of
# dynamics to $P$ is a difficult problem for which little is known~\cite{Zung, FGNG}."
def reconstruction_statement():
    """S5:reconstruction (line 885): the paper states no number of frequencies for the
    reconstructed flow on $P$; our reading: ``None`` (open in the paper)."""
    return None


# -- line 904: "Considering that $\SO(3)$ has rank 1, we conclude that the $\mathcal{V}$ is foliated
# by periodic orbits."
def so3_rank():
    r"""S5:reconstruction uses it (line 904, the S5:V-SO3 paragraph): $\mathrm{rank}\,SO(3) = 1$."""
    return sp.Integer(1)
