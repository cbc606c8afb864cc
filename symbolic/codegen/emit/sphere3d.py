r"""Kernels of the classical 3D Chaplygin sphere with a general diagonal inertia $\mathbb{I}$ (Section 2.1).

Every expression comes from :mod:`symbolic.sphere3d` (derived from the definition eq:mom3D by an
exact solve), the same derivation the ledger rows eq:invL3D, S2.1:detL3D and S2.1:integrals3D
compare with the paper; never from the printed inverse.
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from chaplygin_nd.symbolic import sphere3d
from chaplygin_nd.symbolic.algebra import column
from chaplygin_nd.symbolic.codegen.kernels import Argument, Kernel
from chaplygin_nd.symbolic.model import motion3d

M_ = sp.symbols("M1:4", real=True)
G_ = sp.symbols("gamma1:4", real=True)
I_ = sp.symbols("I1:4", positive=True)
b_ = sp.Symbol("b", positive=True)


@cache
def _L_gamma() -> sp.Matrix:
    return sphere3d.L_gamma_matrix_3d(column(G_), sp.diag(*I_), b_)


@cache
def _Omega() -> sp.Matrix:
    return sphere3d.angular_velocity_3d(column(M_), column(G_), sp.diag(*I_), b_)


def kernels() -> list[Kernel]:
    """The kernel list of ``generated/sphere3d.py``."""
    M, gamma = Argument("M", M_), Argument("gamma", G_)
    inertia, b = Argument("inertia", I_), Argument("b", (b_,), scalar=True)
    Omega = _Omega()
    Mdot, gdot = motion3d(column(M_), column(G_), Omega)
    Mv, gv = column(M_), column(G_)
    integrals = [(Mv.T * gv)[0], (Mv.T * Mv)[0], (Mv.T * Omega)[0] / 2]
    return [
        Kernel("L_gamma_3d", ("eq:mom3D",),
               "Matrix of L_gamma (eq:mom3D): M = L_gamma @ Omega; any gamma, inertia = diag(I).",
               (gamma, inertia, b), _L_gamma(), (3, 3)),
        Kernel("angular_velocity_3d", ("eq:mom3D", "eq:invL3D"),
               "Omega = L_gamma^{-1} M (derived from eq:mom3D; equals eq:invL3D on |gamma| = 1).\n"
               "    Domain: det L_gamma != 0, e.g. |gamma| = 1 and I_j, b > 0.",
               (M, gamma, inertia, b), Omega, (3,)),
        Kernel("vector_field_3d", ("eq:motion3D", "eq:mom3D"),
               "(dM/dt, dgamma/dt) = (M x Omega, gamma x Omega), Omega = L_gamma^{-1} M (eq:motion3D);\n"
               "    returns shape (..., 6). Domain as angular_velocity_3d.",
               (M, gamma, inertia, b), sp.Matrix.vstack(Mdot, gdot), (6,)),
        Kernel("det_L_gamma_3d", ("eq:mom3D", "S2.1:detL3D"),
               "det L_gamma (derived determinant of eq:mom3D, expanded); any gamma. Positive on\n"
               "    |gamma| = 1 with I_j, b > 0 (S2.1:detL3D); the measure density is det^(-1/2).",
               (gamma, inertia, b), sp.Matrix([sp.expand(_L_gamma().det())]), (1,)),
        Kernel("integrals_3d", ("S2.1:integrals3D", "eq:mom3D"),
               "(f1, f2, H) = (<M, gamma>, |M|^2, 1/2 <M, Omega>), Omega = L_gamma^{-1} M derived from\n"
               "    eq:mom3D (S2.1:integrals3D). Domain as angular_velocity_3d.",
               (M, gamma, inertia, b), sp.Matrix(integrals), (3,)),
    ]
