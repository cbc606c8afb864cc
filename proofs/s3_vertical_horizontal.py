r"""Section 3 — vertical and horizontal momentum, decided exactly.

**3D (eq:VHgeneraln, P:EulerTop, eq:vert-3D).** The paper defines
$\mathcal V = \{M\times\gamma = 0\}$ and $\mathcal H = \{f_2 = \langle M,\gamma\rangle = 0\}$ in
$P = \mathbb{R}^3\times S^2$, states that they are invariant submanifolds of dimensions 3 and 4 with
$\mathcal V\cap\mathcal H = \{M = 0\}$, and proves that on $\mathcal V$ the angular velocity solves
Euler's equations $\tilde{\mathbb I}\dot\Omega = (\tilde{\mathbb I}\Omega)\times\Omega$.

* Invariance is proved by a *linear* evolution of the defining functions, valid for any $\Omega$:
  $w = M\times\gamma$ satisfies $\dot w = w\times\Omega$, and $\langle M,\gamma\rangle$ is constant; so a
  zero value stays zero (uniqueness for linear ODEs).
* Dimensions: over each $\gamma\in S^2$ the fibre of $\mathcal V$ is $\ker(M\mapsto M\times\gamma) =
  \mathbb{R}\gamma$ (dimension 1) and that of $\mathcal H$ is $\gamma^\perp$ (dimension 2): vector bundles
  over $S^2$ of total dimensions 3 and 4. The fibre dimensions are exact ranks at seeded points; that
  they are the same for every unit $\gamma$ is the one-line argument just given.
* **Finding.** The integral in the definition of $\mathcal H$ is misnamed: $f_2 = \lVert M\rVert^2$
  (line 185), not $\langle M,\gamma\rangle = f_1$. Read literally, $\{f_2 = 0\} = \{M = 0\}$ has dimension
  2, not 4. Correction: $\mathcal H = \{f_1 = \langle M,\gamma\rangle = 0\}$.
* **Finding.** In the proof of P:EulerTop, $f_1(M,\gamma) = \langle\lambda\gamma,\gamma\rangle = \lambda$ on
  $S^2$, not $\lambda^2$ (it is $f_2$ that equals $\lambda^2$). The conclusion ($\lambda$ constant) is
  unaffected. The proposition itself holds (eq:vert-3D is verified along $\mathcal V$ directly). When
  $\lambda = 0$ the step "$2H = \lambda\langle\Omega,\gamma\rangle$ so $\langle\Omega,\gamma\rangle$ is
  constant" says nothing, but then $M = 0$, $\Omega = 0$ and the claim is trivial.

**nD (eq:def-H-V).** $\mathcal V = \{M\gamma = 0\}$, $\mathcal H = \{M = (M\gamma)\wedge\gamma\}$:

* invariance for any $\Omega$ (so any inertia): $\tfrac{d}{dt}(M\gamma) = -\Omega(M\gamma)$ and, with
  $g = M - (M\gamma)\wedge\gamma$, $\dot g = [g, \Omega]$ — identities of matrix algebra, proved
  symbolically for $n = 3..6$ and at exact points up to $n = 24$; they use only
  $[u\wedge v, \Omega] = -(\Omega u)\wedge v - u\wedge(\Omega v)$, which holds for every $n$;
* space forms: for a rational rotation $R$ with $R\gamma = e_n$, $M_s = RMR^T$ satisfies
  $M_s e_n = R(M\gamma)$ and $M_s - (M_s e_n)\wedge e_n = R\,g\,R^T$, which gives the printed block forms;
* dimensions $n(n-1)/2$ and $2(n-1)$ from the fibre dimensions $(n-1)(n-2)/2$ and $n-1$ (the map
  $M\mapsto M\gamma$ is onto $\gamma^\perp$ for every unit $\gamma$, as $(v\wedge\gamma)\gamma = v$ for $v\perp\gamma$).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.symbolic.algebra import (
    basis_vector,
    hat,
    skew_symbols,
    vector_symbols,
    wedge,
)
from chaplygin_nd.symbolic.exact import points
from chaplygin_nd.symbolic.exact.flint_engine import det as exact_det
from chaplygin_nd.symbolic.exact.flint_engine import rank as exact_rank
from chaplygin_nd.symbolic.exact.flint_matrix import entries, formula_matrix, from_columns
from chaplygin_nd.symbolic.exact.identity import (
    Check,
    point_engines,
    rational_identity,
    zero_at_points,
)
from chaplygin_nd.symbolic.model import commutator, cross, mom3d, motion, motion3d
from chaplygin_nd.symbolic.printed import section2 as printed2
from chaplygin_nd.symbolic.printed import section3 as printed
from chaplygin_nd.symbolic.sphere3d import L_gamma_matrix_3d, tilde_inertia

M = vector_symbols("M", 3)
gamma = vector_symbols("gamma", 3)
Omega = vector_symbols("Omega", 3)
Omega_dot = vector_symbols("Omegadot", 3)
lam = sp.Symbol("lambda", real=True)
I1, I2, I3 = sp.symbols("I1:4", positive=True)
b = sp.Symbol("b", positive=True)
inertia = sp.diag(I1, I2, I3)
SPHERE = tuple(gamma)
SAMPLERS = {s: (lambda r: points.rational(r, 0, 4, 6, open_lo=True)) for s in (I1, I2, I3, b)}
SYMBOLIC_N = (3, 4, 5, 6)
#: eq:def-H-V's dimension count evaluates the printed H_nd on all n(n-1)/2 basis elements in the
#: engine's own arithmetic (FLINT alone above n = 12), so its points reach n = 24
POINT_N = points.all_n(3)


def _nullity(A: sp.Matrix) -> int:
    """Exact nullity (columns minus rank over Q) of a rational matrix."""
    return A.cols - exact_rank(A)  # in the engine of this evaluation


def _fibre_point(rng):
    return {"gamma": points.sphere_point(rng, 3)}


def _lie(f, Mdot, gdot, Mv=M, gv=gamma):
    return sum(sp.diff(f, Mv[i]) * Mdot[i] + sp.diff(f, gv[i]) * gdot[i] for i in range(len(Mv)))


@claim("eq:VHgeneraln", uses=("eq:motion3D", "S2.1:integrals3D"))
def vertical_horizontal_3d() -> Verdict:
    Mdot, gdot = motion3d(M, gamma, Omega)
    w = printed.V_3d(M, gamma)
    w_dot = sp.Matrix([_lie(wi, Mdot, gdot) for wi in w])
    v_invariant = rational_identity(w_dot - w.cross(Omega))
    H = printed.H_3d(M, gamma)
    h_invariant = rational_identity(_lie(H["<M,gamma>"], Mdot, gdot))
    f1 = printed2.integrals_3d(M, gamma, Omega)["f1"]
    # The printed H equates f_2 (= ||M||^2, line 185) with <M, gamma>: false as functions.
    name_printed = rational_identity(H["f_2"] - H["<M,gamma>"], sphere=SPHERE, label="f2")
    name_fixed = rational_identity(f1 - H["<M,gamma>"], sphere=SPHERE)

    dims = printed.dimensions_3d()

    def dimension_residual(p):
        g = p["gamma"]
        V_fibre = _nullity(hat(g))                   # {M : M x gamma = 0} = ker hat(gamma)
        H_fibre = _nullity(g.T)                      # {M : <M, gamma> = 0}
        both = _nullity(sp.Matrix.vstack(hat(g), g.T))
        return [V_fibre + 2 - dims["V"], H_fibre + 2 - dims["H"], both + 2 - dims["V∩H"]]

    dims_check = zero_at_points(dimension_residual, _fibre_point, count=6, label="dims3",
                                describe="S^2 (fibre dimensions)")
    literal = zero_at_points(lambda p: _nullity(sp.eye(3)) + 2 - dims["H"], _fibre_point, count=1,
                             label="dims3-literal", describe="S^2 (fibre of {f_2 = 0} = {M = 0})")
    parts = [
        Verdict.all_of([("d/dt(M x gamma) = (M x gamma) x Omega, any Omega", v_invariant)],
                       n_values=(3,)).as_part("V invariant"),
        Verdict.all_of([("d/dt <M, gamma> = 0, any Omega", h_invariant)],
                       n_values=(3,)).as_part("H = {<M,gamma> = 0} invariant"),
        Verdict.decide(name_printed, corrected=name_fixed, n_values=(3,), kind="formula",
                       printed_latex=r"\mathcal{H} = \{ (M,\gamma) \in P : f_2=\langle M, \gamma \rangle=0\},\quad f_2 = \|M\|^2",
                       correction_latex=r"\mathcal{H} = \{ (M,\gamma) \in P : f_1=\langle M, \gamma \rangle=0\}")
        .as_part("name of the integral in H"),
        Verdict.decide(literal, corrected=dims_check, n_values=(3,),
                       printed_latex=r"\dim\{f_2 = \|M\|^2 = 0\} = 4",
                       correction_latex=r"\dim\{f_1 = \langle M,\gamma\rangle = 0\} = 4 \quad "
                                        r"(\{f_2 = 0\} = \{M = 0\} \text{ has dimension } 2)")
        .as_part("literal reading {f_2 = 0} has the stated dimension 4"),
        Verdict.all_of([("dim V = 3, dim H = 4, V∩H = {M = 0} (fibres over S^2)", dims_check)],
                       n_values=(3,)).as_part("dimensions and intersection"),
    ]
    return Verdict.of_parts(parts, n_values=(3,))


mu = sp.Symbol("mu", real=True)


def _euler_along_V() -> Check:
    # V in the coordinates (Omega, gamma): M = L Omega parallel to gamma. On S^2,
    # L I~^{-1} gamma = (1 - b<I~^{-1} gamma, gamma>) gamma with a positive factor (S2.1:detL3D),
    # so V = {Omega = mu I~^{-1} gamma, mu real} (both directions; L is invertible).
    L = L_gamma_matrix_3d(gamma, inertia, b)
    tilde = tilde_inertia(inertia, b)
    t_inv_gamma = tilde.inv() * gamma
    parametrisation = rational_identity(
        L * t_inv_gamma - (1 - b * (gamma.T * t_inv_gamma)[0]) * gamma, sphere=SPHERE)
    # The flow's Omega' is the unique solution X of L X = rhs (rhs from the definitions, see
    # symbolic.sphere3d.velocity_field_3d). The printed Euler equation has the unique solution
    # X = I~^{-1} c with c = -residual(Omega, 0). So Euler holds along V iff L I~^{-1} c = rhs.
    Omega_V = mu * t_inv_gamma
    c = -printed.vert_3d_residual(Omega_V, sp.zeros(3, 1), tilde)
    M_of_Omega = mom3d(Omega, gamma, inertia, b)
    rhs = cross(M_of_Omega, Omega) - M_of_Omega.jacobian(gamma) * cross(gamma, Omega)
    rhs_V = rhs.xreplace(dict(zip(Omega, Omega_V)))
    euler = rational_identity(L * tilde.inv() * c - rhs_V, sphere=SPHERE, samplers=SAMPLERS,
                              label="euler")
    ok = parametrisation.ok and euler.ok
    return Check(ok, "V = {Omega = mu I~^-1 gamma} on S^2 (" + parametrisation.method
                 + "); Euler's Omega' solves L_gamma Omega' = rhs along V (" + euler.method + ")",
                 euler.counterexample or parametrisation.counterexample)


@claim("eq:vert-3D", uses=("eq:motion3D", "eq:mom3D", "eq:VHgeneraln"),
       adds=("Section 3 — vertical and horizontal momentum",
             "the Euler equations Ĩ Ω̇ = (ĨΩ)×Ω of P:EulerTop hold along V (labelled equation "
             "without its own CLAIMS row)"))
def euler_equations_on_V() -> Verdict:
    check = _euler_along_V()
    return Verdict.decide(
        check, n_values=(3,),
        method=check.method + " (general I_1, I_2, I_3, b, mu)")


@claim("P:EulerTop", uses=("eq:vert-3D", "eq:VHgeneraln", "eq:motion-velocity3D", "S2.1:integrals3D"))
def euler_top() -> Verdict:
    f = printed2.integrals_3d(lam * gamma, gamma, Omega)
    step_lambda = printed.euler_top_lambda_step(lam)["f_1"]
    lambda_printed = rational_identity(f["f1"] - step_lambda, sphere=SPHERE, label="lambda2")
    lambda_fixed = rational_identity(sp.Matrix([f["f1"] - lam, f["f2"] - lam**2]), sphere=SPHERE)
    energy_step = rational_identity(2 * f["H"] - printed.euler_top_energy_step(lam, Omega, gamma))
    gdot = motion3d(lam * gamma, gamma, Omega)[1]
    derivative_step = rational_identity((Omega.T * gdot)[0])  # <Omega, gamma'> = 0
    velocity = printed2.motion_velocity_3d_residual(Omega, Omega_dot, gamma, inertia, b)
    vert = printed.vert_3d_residual(Omega, Omega_dot, tilde_inertia(inertia, b))
    rewrite = rational_identity(velocity - vert + b * gamma * (gamma.T * Omega_dot)[0],
                                sphere=SPHERE)
    parts = [
        Verdict.decide(_euler_along_V(), n_values=(3,)).as_part("statement (eq:vert-3D on V)"),
        Verdict.decide(lambda_printed, corrected=lambda_fixed, n_values=(3,), kind="proof",
                       printed_latex=r"f_1(M_0,\gamma_0)=f_1(M(t),\gamma (t))=\lambda^2",
                       correction_latex=r"f_1(M(t),\gamma(t)) = \langle \lambda\gamma,\gamma\rangle = \lambda"
                                        r"\quad(\text{and } f_2 = \lambda^2),\ \text{so } \lambda = f_1 \text{ is constant}")
        .as_part("proof step: f_1 = lambda^2"),
        Verdict.all_of([("2H = lambda <Omega, gamma> on V", energy_step)]).as_part("proof step: 2H"),
        Verdict.all_of([("d/dt <Omega, gamma> = <Omega', gamma>", derivative_step)])
        .as_part("proof step: derivative of <Omega, gamma>"),
        Verdict.all_of([("velocity form = Euler form + b gamma <gamma, Omega'> on S^2", rewrite)])
        .as_part("proof step: rewriting eq:motion-velocity3D"),
    ]
    return Verdict.of_parts(parts, n_values=(3,), notes=(
        "The proposition holds; its proof misnames the integral: on V, f_1 = lambda (not lambda^2). "
        "For lambda = 0 the energy step is vacuous but M = Omega = 0 there."))


def rotation_to_pole(g: sp.Matrix) -> sp.Matrix:
    r"""A rational $R \in SO(n)$ with $R\gamma = e_n$ (Householder reflection composed with a
    reflection fixing $e_n$); exact for rational $\gamma \in S^{n-1}$."""
    n = g.rows
    e = basis_vector(n, n - 1)
    if g == e:
        return sp.eye(n)
    v = g - e
    householder = sp.eye(n) - 2 * v * v.T / (v.T * v)[0]
    flip = sp.diag(*([-1] + [1] * (n - 1)))
    return flip * householder


def _nd_invariance(n, p=None):
    if p is None:
        Mv, Om, g = skew_symbols("M", n), skew_symbols("Omega", n), vector_symbols("gamma", n)
    else:
        Mv, Om, g = p["M"], p["Omega"], p["gamma"]
    Mdot, gdot = motion(Mv, g, Om)
    V = printed.V_nd(Mv, g)
    H = printed.H_nd(Mv, g)
    V_dot = Mdot * g + Mv * gdot
    MgDot = V_dot
    H_dot = Mdot - wedge(MgDot, g) - wedge(Mv * g, gdot)
    # not expanded: the exact engines read the residual as polynomials (SymPy's expand
    # of the symbolic n = 3..6 residual was most of the row; at a point the entries are numbers)
    return sp.Matrix(list(V_dot + Om * V) + list(H_dot - commutator(H, Om)))


def _nd_point(n):
    def sample(rng):
        return {"M": points.skew_matrix(rng, n), "Omega": points.skew_matrix(rng, n),
                "gamma": points.sphere_point(rng, n), "S": points.skew_matrix(rng, n)}
    return sample


def _space_forms(n, p):
    g, S = p["gamma"], p["S"]
    R = rotation_to_pole(g)
    e = basis_vector(n, n - 1)
    masks = printed.space_forms(n)
    P = sp.eye(n) - g * g.T
    M_V = P * S * P                               # a point of V: M gamma = 0
    v = P * S[:, 0]
    M_H = wedge(v, g)                              # a point of H: v perp gamma
    out = list(R * g - e) + [exact_det(R) - 1]
    for Mp, mask in ((M_V, masks["V"]), (M_H, masks["H"])):
        Ms = R * Mp * R.T
        out += [Ms[i, j] for i in range(n) for j in range(n) if mask[i, j] == 0]
    # Conversely a masked space matrix pulls back into V / into H.
    for key, test in (("V", printed.V_nd), ("H", printed.H_nd)):
        Ss = S.multiply_elementwise(masks[key])
        out += list(test(R.T * Ss * R, g))
    return out


def _dimension_residual(n, p):
    # the printed V_nd, H_nd on the basis E_i ^ E_j of so(n), evaluated in the arithmetic of this
    # evaluation's engine (SymPy Matrix or flint_matrix.FlintMatrix: the transcription is the same)
    g, eye = formula_matrix(p["gamma"]), formula_matrix(sp.eye(n))
    basis = [wedge(eye[:, i], eye[:, j]) for i in range(n) for j in range(i + 1, n)]
    upper = [i * n + j for i in range(n) for j in range(i + 1, n)]  # so(n) coordinates (vec)
    maps = {"V": from_columns([entries(printed.V_nd(B, g)) for B in basis]),
            "H": from_columns([[h[k] for k in upper]
                               for h in (entries(printed.H_nd(B, g)) for B in basis)])}
    dims = printed.dimensions_nd(n)
    return [_nullity(maps[k]) + (n - 1) - dims[k] for k in ("V", "H")]


@claim("eq:def-H-V", uses=("eq:motion-general",))
def vertical_horizontal_nd() -> Verdict:
    invariance = [(f"symbolic n={n}", rational_identity(_nd_invariance(n))) for n in SYMBOLIC_N]
    invariance += [(f"points n={n}", zero_at_points(
        lambda p, n=n: _nd_invariance(n, p), _nd_point(n), count=2, label=f"inv{n}",
        describe=f"so({n}) x so({n}) x S^{n - 1}", engines=point_engines(n))) for n in POINT_N]
    forms = [(f"n={n}", zero_at_points(lambda p, n=n: _space_forms(n, p), _nd_point(n), count=2,
                                       label=f"forms{n}", describe=f"S^{n - 1} x so({n})",
                                       engines=point_engines(n)))
             for n in POINT_N]
    dims = [(f"n={n}", zero_at_points(lambda p, n=n: _dimension_residual(n, p), _nd_point(n),
                                      count=2, label=f"dims{n}", describe=f"S^{n - 1}",
                                      engines=point_engines(n)))
            for n in POINT_N]
    parts = [
        Verdict.all_of(invariance, n_values=POINT_N, method=(
            "d/dt(M gamma) = -Omega (M gamma) and d/dt g_H = [g_H, Omega] for any skew Omega: "
            f"exact symbolic n=3..6, exact at 2 seeded points for n={points.n_text(POINT_N)}")).as_part("V and H invariant"),
        Verdict.all_of(forms, n_values=POINT_N, method=(
            "R gamma = e_n with R rational in SO(n); R M R^T has the printed block form on V and H, "
            f"and masked matrices pull back into V and H: exact at 2 seeded points, n={points.n_text(POINT_N)}"))
        .as_part("space forms"),
        Verdict.all_of(dims, n_values=POINT_N, method=(
            "fibre dimensions (exact ranks) + (n-1) equal n(n-1)/2 and 2(n-1): exact at 2 seeded "
            f"points, n={points.n_text(POINT_N)}; M -> M gamma is onto gamma-perp for every unit gamma")).as_part("dimensions"),
    ]
    return Verdict.of_parts(parts, n_values=POINT_N)

