"""A deliberately altered variant of each Section 2-3 printed formula must come out `fails`.

Each mutation replaces one function of ``symbolic.printed`` (what the paper prints) with a
materially different formula and re-runs the ledger row that checks it. The row must be
``fails`` with an exact counterexample: the checks see the formula, they do not bless anything.
"""

import pytest
import sympy as sp
from chaplygin_nd.proofs import s2_sphere3d, s2_spheren, s3_vertical_horizontal
from chaplygin_nd.symbolic.algebra import basis_vector, commutator, killing, wedge
from chaplygin_nd.symbolic.printed import section2, section3

E3 = sp.Matrix([0, 0, 1])


def _dot(u, v):
    return (u.T * v)[0]


MUTATIONS = [
    # (row function, printed module, name, altered formula)
    (s2_sphere3d.motion_velocity_3d, section2, "motion_velocity_3d_residual",
     lambda O, Od, g, I, b: I * Od - ((I * O).cross(O) + b * g.cross(Od.cross(g)))),
    (s2_sphere3d.det_L_3d, section2, "det_L_3d",
     lambda g, I, b: (I + b * sp.eye(3)).det() * (1 + b * _dot((I + b * sp.eye(3)).inv() * g, g))),
    (s2_sphere3d.inverse_3d, section2, "inverse_L_3d",
     lambda M, g, I, b: (I + b * sp.eye(3)).inv() * M),
    (s2_sphere3d.integrals_3d, section2, "integrals_3d",
     lambda M, g, O: {"f1": _dot(M, g), "f2": _dot(M, M), "H": _dot(O, O) / 2}),
    (s2_sphere3d.measure_3d, section2, "measure_3d_exponents",
     lambda: {"dM dgamma": sp.Integer(-1), "dOmega dgamma": sp.Integer(0)}),
    (s2_spheren.motion_velocity_nd, section2, "motion_velocity_nd_residual",
     lambda O, Od, g, I, b: I(Od) - (commutator(I(O), O) + b * wedge(Od * g, g))),
    (s2_spheren.iso_spectral, section2, "iso_spectral_rhs",
     lambda M, g, O, s: commutator(M - s * g * g.T, O)),
    (s2_spheren.polynomial_integrals, section2, "characteristic_polynomial",
     lambda M, g, s, lam: (M + s * basis_vector(g.rows, 0) * g.T - lam * sp.eye(g.rows)).det()),
    (s2_spheren.energy, section2, "energy_nd", lambda M, O: killing(O, O) / 2),
    (s2_spheren.invariant_measure, section2, "measure_nd_exponents",
     lambda: {"dM dgamma": sp.Integer(-1), "dOmega dgamma": sp.Integer(0)}),
    (s3_vertical_horizontal.vertical_horizontal_3d, section3, "V_3d", lambda M, g: M.cross(E3)),
    (s3_vertical_horizontal.vertical_horizontal_3d, section3, "dimensions_3d",
     lambda: {"V": 2, "H": 4, "V∩H": 2}),
    (s3_vertical_horizontal.euler_equations_on_V, section3, "vert_3d_residual",
     lambda O, Od, T: T * Od - O.cross(T * O)),
    (s3_vertical_horizontal.euler_top, section3, "euler_top_energy_step",
     lambda lam, O, g: lam**2 * _dot(O, g)),
    (s3_vertical_horizontal.vertical_horizontal_nd, section3, "V_nd",
     lambda M, g: M * basis_vector(g.rows, g.rows - 1)),
    (s3_vertical_horizontal.vertical_horizontal_nd, section3, "H_nd",
     lambda M, g: M - wedge(M * g, basis_vector(g.rows, g.rows - 1))),
    (s3_vertical_horizontal.vertical_horizontal_nd, section3, "dimensions_nd",
     lambda n: {"V": n * (n - 1) // 2 + 1, "H": 2 * (n - 1)}),
]


@pytest.mark.slow
@pytest.mark.parametrize("row, module, name, altered", MUTATIONS,
                         ids=[f"{m[2]}" for m in MUTATIONS])
def test_altered_printed_formula_fails(monkeypatch, row, module, name, altered):
    assert row().verdict in ("holds", "corrected", "definition")   # as printed: not fails
    monkeypatch.setattr(module, name, altered)
    verdict = row()
    assert verdict.verdict == "fails", f"altered {name} was not refuted: {verdict.method}"
    assert verdict.counterexample, "a refutation must carry an exact counterexample"
