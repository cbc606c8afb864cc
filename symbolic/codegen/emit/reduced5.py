r"""Kernels of the $SO(4)$-reduced $n = 5$ sphere on $r = (x, A_+, A_-, B, G, E_+, E_-, S_{uu}, S_{uq}, S_{qq})$.

Sources (derived): :mod:`symbolic.reduction.reduced_n5` (the reduced field and the known integrals, row
S6:reduced-n5), :mod:`symbolic.family.sixth_integral` (row S6:sixth-integral-n5) and
:mod:`symbolic.reduction.invariants_n5` (the generators and the relations $R_1, R_2$). The field is a
polynomial numerator over $D = 2(2+a+b)\Delta(x)$ with $\Delta$ in the stable form of row K:Delta.
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.codegen.emit.axisym import stable_Delta
from chaplygin_nd.symbolic.codegen.emit.fourd import stable_D
from chaplygin_nd.symbolic.codegen.kernels import Argument, Kernel
from chaplygin_nd.symbolic.family import sixth_integral as si
from chaplygin_nd.symbolic.reduction import invariants_n5 as ri5
from chaplygin_nd.symbolic.reduction import reduced_n5 as r5

__all__ = ["kernels"]

a, b, x = r5.a, r5.b, r5.x


def _integral(name: str, D) -> sp.Expr:
    num = r5._integral_numerators()[name].as_expr()
    return num / (2 * D) if name == "H" else num


def kernels() -> list[Kernel]:
    """The kernel list of ``generated/reduced5.py``."""
    R = Argument("r", tuple(r5.SYMBOLS[c] for c in r5.COORDS))
    A_, B_ = Argument("a", (a,), True), Argument("b", (b,), True)
    D = stable_D()
    N = r5.field_numerators()
    m = Argument("m", tuple(ri5.M[i, j] for i in range(5) for j in range(i + 1, 5)))
    g = Argument("gamma", tuple(ri5.gamma))
    M = [[ri5.M[i, j] for j in range(5)] for i in range(5)]
    gens = ri5.generators_from(M, list(ri5.q))
    inv = [x] + [sp.expand(gens[c]) for c in r5.COORDS[1:]]
    return [
        Kernel("reduced5_field", ("S6:reduced-n5", "K:Delta"),
               "dr/dt of the SO(4)-reduced n = 5 field on R^10, r = (x, Ap, Am, B, G, Ep, Em, Suu, Suq,\n"
               "    Sqq) (S6:reduced-n5, derived in symbolic.reduction.reduced_n5); shape (..., 10). Domain: the reduced\n"
               "    space (relations R1 = R2 = 0 of reduced5_relations).",
               (R, A_, B_), sp.Matrix([N[c].as_expr() / D for c in r5.COORDS]), (10,)),
        Kernel("reduced5_invariants", ("S6:reduced-n5",),
               "r = (x, Ap, Am, B, G, Ep, Em, Suu, Suq, Sqq) of a phase point (M, gamma) of the n = 5\n"
               "    sphere, M by its upper-triangular entries M_ij (i < j, row-major); shape (..., 10).",
               (m, g), sp.Matrix(inv), (10,)),
        Kernel("reduced5_integrals", ("S6:reduced-n5", "eq:pol-first-integrals", "K:Delta"),
               "The known integrals at r (S6:reduced-n5): the coefficients of lambda^3, lambda^1,\n"
               "    sigma lambda^2, sigma lambda^0 of p(lambda, sigma) and H; shape (..., 5).",
               (R, A_, B_), sp.Matrix([_integral(n, D) for n in r5.INTEGRAL_NAMES]), (5,)),
        Kernel("reduced5_sixth_integral", ("S6:sixth-integral-n5", "K:Delta"),
               "F = <w, B(2+B) w>/Delta at r (S6:sixth-integral-n5: w = *(M^M)/2, B = a E5 E5^T +\n"
               "    b gamma gamma^T), in the reduced coordinates; shape (..., 1).",
               (R, A_, B_), sp.Matrix([si.numerator_in_invariants().as_expr()
                                       / stable_Delta(x, a, b)]), (1,)),
        Kernel("reduced5_relations", ("S6:reduced-n5",),
               "(R1, R2) at r (S6:reduced-n5): zero on the reduced space; shape (..., 2).",
               (R,), sp.Matrix(r5.relations_on_P()), (2,)),
    ]
