r"""Exact identities along printed curves $t \mapsto e^{\Omega t}\cdots$ (registers no ledger row).

The paper writes some solutions with matrix exponentials (P:steady-rot, Th:Re and its corollary).
To check such a printed curve *as printed*, a proof evaluates it with SymPy's exact ``Matrix.exp``
at a concrete rational exponent matrix whose rotation rates are integers, so that every entry is a
polynomial in $\cos t, \sin t$ (after ``rewrite(cos)`` and ``expand_trig``), and the claim becomes
a polynomial identity in $(c, s) = (\cos t, \sin t)$ modulo $c^2 + s^2 = 1$ — decided by the exact
engine like any other identity (the circle is irreducible, so the remainder criterion is exact).
"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.exact.identity import Check, rational_identity

T = sp.Symbol("t", real=True)
C, S = sp.symbols("cos_t sin_t", real=True)


def trig_polynomial(expr, t=T) -> sp.Expr:
    r"""``expr`` (built from $\cos, \sin, e^{\pm i k t}$ with integer $k$) as a polynomial in
    $C = \cos t$, $S = \sin t$. Raises ``ValueError`` if $t$ survives (a non-integer rate)."""
    e = sp.expand_trig(sp.expand(sp.sympify(expr).rewrite(sp.cos)))
    e = sp.expand(e.subs({sp.cos(t): C, sp.sin(t): S}))
    if e.has(t):
        raise ValueError(f"not a polynomial in cos t, sin t: {e}")
    return e


def trig_identity(residual, *, label: str, samplers=None, t=T) -> Check:
    """Exact proof that every entry of ``residual`` (a matrix or list of expressions in ``t``)
    vanishes for all real ``t``: polynomial identity in (cos t, sin t) modulo cos^2 + sin^2 = 1."""
    entries = list(residual) if not isinstance(residual, sp.MatrixBase) else list(residual)
    polys = [trig_polynomial(e, t) for e in entries]
    chk = rational_identity(polys, sphere=(C, S), samplers=samplers, label=label)
    return Check(chk.ok, chk.method.replace(f"||{C},{S}||^2", "cos^2 t + sin^2 t"),
                 chk.counterexample, chk.seconds)
