"""The derived 3D field in (Omega, gamma) is checked where it can fail.

``symbolic.sphere3d.velocity_field_3d`` was used only for dH/dt in S2.1:integrals3D, which is blind
to both of its terms (<M x Omega, Omega> = 0); row eq:motion3D now compares it with the equations
of motion themselves (L_gamma Omega_dot = M x Omega - (d_gamma M) gamma_dot, exactly). Each mutant
below is a one-token change of the function's source; with it the row must stop being a
``definition`` (its consistency check fails with a counterexample).
"""

from __future__ import annotations

import inspect
import textwrap

import pytest
from chaplygin_nd.ledger.catalog import discover
from chaplygin_nd.ledger.registry import registry
from chaplygin_nd.symbolic import sphere3d

MUTANTS = {
    "sign of the M x Omega term": ("rhs = cross(M, Omega) -", "rhs = -cross(M, Omega) -"),
    "sign of the (d_gamma M) gamma_dot term": ("- M.jacobian(gamma) * gamma_dot",
                                               "+ M.jacobian(gamma) * gamma_dot"),
    "factor d_gamma M dropped": ("- M.jacobian(gamma) * gamma_dot", "- gamma_dot"),
    "gamma_dot = Omega x gamma": ("gamma_dot = cross(gamma, Omega)",
                                  "gamma_dot = cross(Omega, gamma)"),
}


def _mutant_code(old: str, new: str):
    fn = sphere3d.velocity_field_3d
    source = textwrap.dedent(inspect.getsource(fn))
    assert source.count(old) == 1, old
    namespace = dict(fn.__globals__)
    exec(compile(source.replace(old, new), "<mutant>", "exec"), namespace)  # noqa: S102
    return namespace[fn.__name__].__code__


def test_the_row_holds_unmutated():
    discover()
    assert registry()["eq:motion3D"].run().verdict == "definition"


@pytest.mark.parametrize("name", sorted(MUTANTS))
def test_each_mutant_of_the_derived_field_is_killed(name):
    discover()
    fn = sphere3d.velocity_field_3d
    original = fn.__code__
    fn.__code__ = _mutant_code(*MUTANTS[name])
    try:
        verdict = registry()["eq:motion3D"].run()
    finally:
        fn.__code__ = original
    assert verdict.verdict == "fails", name
    assert verdict.counterexample
