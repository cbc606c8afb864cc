r"""The derived fields as heyoka ODE systems (built from ``generated.expression_builders``).

Three systems, all from derived expressions (never a printed formula, never hand-typed):

* ``full(n, reconstruct)`` — eq:motion-general for the axisymmetric sphere in $(\mathrm{vec}\,M, \gamma)$
  [$+ (g, c)$], any $n \ge 3$, $\Omega = L_\gamma^{-1}M$ assembled by :mod:`runtime.expressions` from
  the derived coefficients of P:inversion; parameters $(a, b, r)$;
* ``reduced()`` — eq:red-system on $(A, B, E, G, F_1, x, \delta)$ ($n = 4$); parameters $(a, b)$;
* ``reduced5()`` — the $SO(4)$-reduced $n = 5$ field (row S6:reduced-n5) on
  $(x, A_+, A_-, B, G, E_+, E_-, S_{uu}, S_{uq}, S_{qq})$; parameters $(a, b)$;
* ``sphere3d()`` — eq:motion3D with general diagonal inertia (derived from eq:mom3D); parameters
  $(I_1, I_2, I_3, b)$.

The parameters are heyoka runtime parameters (``par[i]``): one compiled integrator serves every
$a, b$. heyoka is imported only when a system is built; its own import loads SymPy (heyoka._core
registers ``to_sympy``), so only runs that use heyoka pay that.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

from chaplygin_nd.simulate.kernels import expression_builders

__all__ = ["System", "full", "reduced", "reduced5", "sphere3d", "for_field"]


@dataclass(frozen=True)
class System:
    """A heyoka ODE system: ``name``, state names in order, parameter names, and ``build(hy, ops)``
    returning the right-hand sides (heyoka expressions) for the variables ``names``."""

    name: str
    names: tuple[str, ...]
    parameters: tuple[str, ...]
    build: Callable

    @property
    def dim(self) -> int:
        """Dimension of the state."""
        return len(self.names)

    def equations(self, hy, ops) -> list[tuple]:
        """``[(variable, rhs), ...]`` for ``hy.taylor_adaptive``."""
        variables = [hy.expression(v) for v in self.names]
        pars = [hy.par[i] for i in range(len(self.parameters))]
        rhs = self.build(variables, pars, ops)
        return [(v, r if not isinstance(r, int) else hy.expression(float(r)))
                for v, r in zip(variables, rhs, strict=True)]

    def fingerprint(self, hy, ops) -> str:
        """SHA-256 of the expressions heyoka will compile (the source hash of the cache key)."""
        text = "\n".join(f"{v} = {r}" for v, r in self.equations(hy, ops))
        return hashlib.sha256(f"{self.name}|{self.parameters}\n{text}".encode()).hexdigest()


@cache
def full(n: int, reconstruct: bool = False) -> System:
    r"""eq:motion-general (axisymmetric, any $n \ge 3$), state of :class:`simulate.dynamics.field.FullField`;
    parameters $(a, b)$, and the radius $r$ with the reconstruction (one object per $(n,$ reconstruct$)$,
    so a warm integrate call does not rebuild the names). Domain: $\gamma \in S^{n-1}$, $|a| \le 1$, $b > 0$."""
    from chaplygin_nd.runtime import expressions as rx

    pairs = rx.pairs(n)
    names = [f"M{i + 1}_{j + 1}" for i, j in pairs] + [f"gamma{i + 1}" for i in range(n)]
    if reconstruct:
        names += [f"g{i + 1}_{j + 1}" for i in range(n) for j in range(n)]
        names += [f"c{i + 1}" for i in range(n)]

    def build(v, p, ops):
        N = len(pairs)
        m, gamma = v[:N], v[N:N + n]
        g = None
        if reconstruct:
            flat = v[N + n:N + n + n * n]
            g = [flat[i * n:(i + 1) * n] for i in range(n)]
        return rx.vector_field(m, gamma, p[0], p[1], ops, g=g, radius=p[2] if reconstruct else None)

    tag = "full" + ("+reconstruction" if reconstruct else "")
    return System(f"{tag} n={n}", tuple(names), ("a", "b", "radius") if reconstruct else ("a", "b"),
                  build)


@cache
def reduced() -> System:
    r"""eq:red-system on $r = (A, B, E, G, F_1, x, \delta)$ ($n = 4$); parameters $(a, b)$."""
    def build(v, p, ops):
        return expression_builders().reduced_field(v, p[0], p[1], ops)

    return System("reduced 7D", ("A", "B", "E", "G", "F1", "x", "delta"), ("a", "b"), build)


@cache
def reduced5() -> System:
    r"""The $SO(4)$-reduced $n = 5$ field (S6:reduced-n5) on
    $r = (x, A_+, A_-, B, G, E_+, E_-, S_{uu}, S_{uq}, S_{qq})$; parameters $(a, b)$."""
    def build(v, p, ops):
        return expression_builders().reduced5_field(v, p[0], p[1], ops)

    return System("reduced5 10D", ("x", "Ap", "Am", "B", "G", "Ep", "Em", "Suu", "Suq", "Sqq"),
                  ("a", "b"), build)


@cache
def sphere3d() -> System:
    r"""eq:motion3D, $(\dot M, \dot\gamma) = (M\times\Omega, \gamma\times\Omega)$ with the derived
    $\Omega = L_\gamma^{-1}M$ of eq:mom3D; parameters $(I_1, I_2, I_3, b)$."""
    def build(v, p, ops):
        return expression_builders().vector_field_3d(v[:3], v[3:], p[:3], p[3], ops)

    return System("sphere3d general inertia", ("M1", "M2", "M3", "gamma1", "gamma2", "gamma3"),
                  ("I1", "I2", "I3", "b"), build)


def for_field(field) -> tuple[System, list[float]]:
    """The system and parameter values of a :class:`simulate.dynamics.field.FullField` or
    :class:`simulate.dynamics.field.ReducedField`."""
    from chaplygin_nd.simulate.dynamics.field import FullField, ReducedField

    if isinstance(field, FullField):
        values = [field.a, field.b] + ([field.radius] if field.reconstruct else [])
        return full(field.n, field.reconstruct), values
    if isinstance(field, ReducedField):
        return reduced(), [field.a, field.b]
    raise TypeError(f"no heyoka system for {type(field).__name__}")
