r"""The vector field $X$ of eq:motion-general at seeded points of $P$, modulo a prime (row
S6:first-integrals).

$X$: $\dot M = [M, \Omega]$, $\dot\gamma = -\Omega\gamma$ with $\Omega = L_\gamma^{-1}(M)$ (eq:M-O).
Two models, both exact modulo $p$:

* ``axisymmetric`` ($\mathbb{J} = \mathrm{Id} + aE_nE_n^T$, eq:axisymm): $\Omega = \sum_k c_k(a, b, x)\,
  T_k(M)$, the project's *derived* inverse (symbolic/axisym_inverse.py, P:inversion), whose
  denominators are $\Delta(x)$ (eq:Delta) and $2(2+a+b)$. The denominator of the search is
  $D = \Delta$.
* ``general`` (any diagonal $\mathbb{J}$): $\Omega$ by solving the definition $L_\gamma\Omega = M$
  (eq:M-O, the matrix of symbolic/model.py's ``L_matrix``) modulo $p$; $D = \det L_\gamma$ and
  $X(D)/D = \operatorname{tr}(L_\gamma^{-1}\dot L_\gamma)$ (Jacobi's formula).

Points: $\gamma$ is the inverse stereographic projection of an integer $t \in \mathbb{Z}^{n-1}$
(a rational point of $S^{n-1}$, reduced mod $p$); $M$ has random integer entries. A point is
dropped when $D$, $2+a+b$ or a pivot vanishes mod $p$ (dropping rows only weakens the conditions,
see symbolic/search/integral_search.py).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import sympy as sp
from chaplygin_nd.symbolic.search import backend
from chaplygin_nd.symbolic.search.backend import inv_mod

__all__ = ["Model", "axisymmetric", "general", "field_at", "sample", "PRIMES", "mod"]

PRIMES = backend.PRIMES


def mod(q, p: int) -> int:
    """The rational ``q`` as a residue mod ``p`` (ZeroDivisionError when p divides its denominator)."""
    q = sp.Rational(q)
    den = int(q.q) % p
    if den == 0:
        raise ZeroDivisionError(f"{q} has no value mod {p}")
    return int(q.p) * pow(den, p - 2, p) % p


@dataclass(frozen=True)
class Model:
    """A Chaplygin sphere: n, the diagonal mass tensor J, b (exact rationals), its kind and the
    torus planes the search may use (the symmetry of J)."""

    n: int
    J: tuple
    b: sp.Rational
    kind: str                # "axisymmetric" or "general"
    a: sp.Rational | None = None

    @property
    def planes(self) -> int:
        return (self.n - 1) // 2 if self.kind == "axisymmetric" else 0


def axisymmetric(n: int, a, b) -> Model:
    r"""The axisymmetric sphere eq:axisymm, $\mathbb{J} = \mathrm{Id} + aE_nE_n^T$."""
    a, b = sp.Rational(a), sp.Rational(b)
    return Model(n, tuple([sp.Integer(1)] * (n - 1) + [1 + a]), b, "axisymmetric", a)


def general(J, b) -> Model:
    r"""Any diagonal mass tensor $\mathbb{J} = \mathrm{diag}(J)$ (eq:Inertia); no torus is used."""
    J = tuple(sp.Rational(j) for j in J)
    return Model(len(J), J, sp.Rational(b), "general")


@lru_cache(maxsize=8)
def _inverse_coefficients_mod(a, b, p: int):
    """(numerator, denominator) coefficient lists in x, mod p, of the derived c_k (P:inversion)."""
    from chaplygin_nd.symbolic.axisym_inverse import inverse_coefficients
    from chaplygin_nd.symbolic.axisymmetric import a as A
    from chaplygin_nd.symbolic.axisymmetric import b as B
    from chaplygin_nd.symbolic.axisymmetric import x as X

    out = []
    for c in inverse_coefficients():
        num, den = sp.fraction(sp.together(c.subs({A: a, B: b})))
        pn, pd = sp.Poly(sp.expand(num), X), sp.Poly(sp.expand(den), X)
        out.append(([mod(q, p) for q in pn.all_coeffs()], [mod(q, p) for q in pd.all_coeffs()]))
    return tuple(out)


def _horner(coeffs, x, p):
    v = np.zeros_like(x)
    for c in coeffs:
        v = (v * x + c) % p
    return v


def _matmul(A, B, p):
    return np.einsum("rij,rjk->rik", A % p, B % p) % p


def _wedge(u, v, p):
    return (u[:, :, None] * v[:, None, :] - v[:, :, None] * u[:, None, :]) % p


def _omega_axisymmetric(model, M, g, p):
    R, n = g.shape
    x = g[:, -1]
    e = np.zeros((R, n), dtype=np.int64)
    e[:, -1] = 1
    Mg = np.einsum("rij,rj->ri", M, g) % p
    Me = M[:, :, -1] % p
    inner = Mg[:, -1]
    terms = [M, _wedge(Mg, g, p), _wedge(Me, e, p), _wedge(Mg, e, p), _wedge(Me, g, p),
             inner[:, None, None] * _wedge(g, e, p) % p]
    Om = np.zeros_like(M)
    ok = np.ones(R, dtype=bool)
    for (num, den), T in zip(_inverse_coefficients_mod(model.a, model.b, p), terms, strict=True):
        dv = _horner(den, x, p)
        ok &= dv != 0
        c = _horner(num, x, p) * inv_mod(dv, p) % p
        Om = (Om + c[:, None, None] * T) % p
    a, b = mod(model.a, p), mod(model.b, p)
    delta = ((2 + a) * (2 + b) - a * b % p * x % p * x) % p
    ok &= delta != 0
    return Om, delta, ok


def _L_batch(model, g, p, gdot=None):
    """The matrix of L_gamma (or of its derivative along gdot) in the basis E_i^E_j, per point."""
    n = model.n
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    R = g.shape[0]
    b = mod(model.b, p)
    Jd = [mod(j, p) for j in model.J]
    L = np.zeros((R, len(pairs), len(pairs)), dtype=np.int64)
    for c, (i, j) in enumerate(pairs):
        B = np.zeros((n, n), dtype=np.int64)
        B[i, j], B[j, i] = 1, -1
        Bg = (g @ B.T) % p                       # rows: B gamma
        if gdot is None:
            W = _wedge(Bg, g, p)
            img = (b * W + (Jd[i] + Jd[j]) * B[None]) % p
        else:
            Bgd = (gdot @ B.T) % p
            img = b * (_wedge(Bgd, g, p) + _wedge(Bg, gdot, p)) % p
        L[:, :, c] = np.stack([img[:, k, l] for k, l in pairs], axis=1)
    return L % p


def _solve_batch(L, rhs, p):
    """Gauss-Jordan without pivot search, batched; ok[r] False where a pivot vanishes."""
    L, rhs = L.copy() % p, rhs.copy() % p
    R, m, _ = L.shape
    ok = np.ones(R, dtype=bool)
    det = np.ones(R, dtype=np.int64)
    for c in range(m):
        piv = L[:, c, c]
        ok &= piv != 0
        det = det * piv % p
        inv = inv_mod(piv, p)
        L[:, c, :] = L[:, c, :] * inv[:, None] % p
        rhs[:, c, :] = rhs[:, c, :] * inv[:, None] % p
        for r in range(m):
            if r != c:
                f = L[:, r, c].copy()
                L[:, r, :] = (L[:, r, :] - f[:, None] * L[:, c, :]) % p
                rhs[:, r, :] = (rhs[:, r, :] - f[:, None] * rhs[:, c, :]) % p
    return rhs, det, ok


def _omega_general(model, M, g, p):
    n = model.n
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    L = _L_batch(model, g, p)
    m = np.stack([M[:, i, j] for i, j in pairs], axis=1)[:, :, None]
    sol, det, ok = _solve_batch(L, m, p)
    Om = np.zeros_like(M)
    for c, (i, j) in enumerate(pairs):
        Om[:, i, j], Om[:, j, i] = sol[:, c, 0], (-sol[:, c, 0]) % p
    return Om, det, ok, L


def field_at(model: Model, z: np.ndarray, p: int) -> dict:
    r"""The field at points ``z`` $= ((M_{ij})_{i<j}, \gamma)$ mod $p$ (on the sphere): ``zdot``
    $= X(z)$, ``Omega``, ``D``, ``dlogD`` $= X(D)/D$ and ``ok`` (False where a denominator or
    pivot vanishes mod $p$)."""
    n = model.n
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    R = z.shape[0]
    g = z[:, len(pairs):] % p
    M = np.zeros((R, n, n), dtype=np.int64)
    for c, (i, j) in enumerate(pairs):
        M[:, i, j], M[:, j, i] = z[:, c] % p, (-z[:, c]) % p
    if model.kind == "axisymmetric":
        Om, D, ok = _omega_axisymmetric(model, M, g, p)
    else:
        Om, D, ok, L = _omega_general(model, M, g, p)
    Mdot = (_matmul(M, Om, p) - _matmul(Om, M, p)) % p
    gdot = (-np.einsum("rij,rj->ri", Om, g)) % p
    if model.kind == "axisymmetric":
        a, b = mod(model.a, p), mod(model.b, p)
        dD = (-2 * a * b % p * g[:, -1] % p * gdot[:, -1]) % p
        dlog = dD * inv_mod(D, p) % p
    else:
        Ld = _L_batch(model, g, p, gdot)
        X, _, ok2 = _solve_batch(L, Ld, p)
        ok &= ok2
        dlog = np.einsum("rii->r", X) % p
    zd = np.concatenate([np.stack([Mdot[:, i, j] for i, j in pairs], 1), gdot], axis=1)
    return {"zdot": zd, "Omega": Om, "D": D, "dlogD": dlog, "ok": ok}


def sample(model: Model, count: int, p: int, rng: np.random.Generator) -> dict:
    r"""``count`` valid points of $P$ mod $p$ (module docstring) with the field there: ``z``
    and the entries of :func:`field_at`."""
    n = model.n
    dim = n * (n - 1) // 2
    out: dict[str, list] = {}
    have = 0
    while have < count:
        R = max(64, int(1.2 * (count - have)) + 16)
        t = rng.integers(0, p, size=(R, n - 1))
        s = (t * t % p).sum(axis=1) % p
        den = (s + 1) % p
        inv = inv_mod(den, p)
        g = np.concatenate([2 * t % p * inv[:, None] % p, ((s - 1) % p * inv % p)[:, None]], axis=1)
        z = np.concatenate([rng.integers(0, p, size=(R, dim)), g], axis=1)
        f = field_at(model, z, p)
        ok = f.pop("ok") & (den != 0)
        f["z"] = z
        for k, v in f.items():
            out.setdefault(k, []).append(v[ok])
        have += int(ok.sum())
    return {k: np.concatenate(v)[:count] for k, v in out.items()}
