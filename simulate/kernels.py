r"""The one binding of :mod:`simulate` to the verified kernels of :mod:`generated`.

Every right-hand side and every derived formula the simulator evaluates comes through a
:class:`Kernels` object; :mod:`simulate` never writes a derived formula by hand. The interface
is in matrix form, batched over leading axes ($M, \Omega$: ``(..., n, n)``; $\gamma$: ``(..., n)``;
$a, b$: floats):

* ``L_gamma(Omega, gamma, a, b) -> M``        — eq:M-O-axi-symm (forward map, a definition);
* ``angular_velocity(M, gamma, a, b) -> Omega`` — $L_\gamma^{-1}$ (P:inversion, derived);
* ``zeta(M0, gamma0, a, b) -> zeta``          — the velocity of Th:Re (derived), optional;
* ``reduced_field(r, a, b) -> rdot``          — eq:red-system on $r = (A, B, E, G, F_1, x, \delta)$,
  optional;
* ``reduced_integrals(r, a, b) -> (F1, F2, F3, H)`` — S5:red-integrals, optional;
* ``horizontal(x0, G0, F2, H, a, b, t) -> (x, G)`` — S5:H-linear solution (corrected), optional;
* ``horizontal_A(x, G, h, a, b) -> A`` — eq:A-on-J, $A$ on $\mathcal H/SO(3)\cap\{H = h\}$, optional;
* ``horizontal_blocks(x, G, F2) -> (A, B)`` — the blocks of $M$ on $\mathcal H$, any $n$
  (S5:H-linear-nD), optional.

A missing optional kernel is reported by :meth:`Kernels.missing`; the planner then falls back to a
model that does not need it and says so. :func:`active` returns the kernels in use (by default those
of :mod:`generated`); :func:`use` swaps them (tests compare the generated kernels with an
independent route this way).

Binding (:func:`from_generated`): :mod:`generated.axisym` holds component kernels for $n = 3, 4$
($M$, $\Omega$, $\zeta$ as ``vec`` coordinates, entries $i<j$ in lexicographic order — the order of
:func:`simulate.dynamics.so.vec`) and coefficient kernels for every $n$, assembled into $n\times n$
matrices by :mod:`runtime.axisym`; where neither exists, a kernel raises :class:`KernelMissing`
naming what is missing. Nothing here computes a derived formula: it only reshapes arguments and
results.

Beside the matrix interface, the generated code that is not a kernel of this interface comes through
here too, so that this module stays the one place :mod:`simulate` reaches :mod:`generated`
(``tests/test_simulate_layers.py``): :func:`p_coefficients` (the coefficients of
$p(\lambda, \sigma)$ at any $n$), :func:`reduced5` (the $n = 5$ reduced invariants and integrals)
and :func:`expression_builders` (the expression graphs heyoka compiles).
"""

from __future__ import annotations

import contextlib
import importlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass, fields

import numpy as np
from chaplygin_nd.simulate.dynamics import so

__all__ = ["Kernels", "KernelMissing", "OPTIONAL", "active", "use", "from_generated",
           "RUNTIME_MODULES", "p_coefficients", "reduced5", "expression_builders"]

OPTIONAL = ("zeta", "reduced_field", "reduced_integrals", "horizontal", "horizontal_A",
            "horizontal_blocks")


class KernelMissing(RuntimeError):
    """A computation needs a kernel that :mod:`generated` does not (yet) provide."""


@dataclass(frozen=True)
class Kernels:
    """A set of kernels in the matrix interface described in the module docstring."""

    name: str
    L_gamma: Callable | None = None
    angular_velocity: Callable | None = None
    zeta: Callable | None = None
    reduced_field: Callable | None = None
    reduced_integrals: Callable | None = None
    horizontal: Callable | None = None
    horizontal_A: Callable | None = None
    horizontal_blocks: Callable | None = None
    note: str = ""

    def missing(self) -> tuple[str, ...]:
        """Names of the kernels this set lacks."""
        return tuple(f.name for f in fields(self)
                     if f.name not in ("name", "note") and getattr(self, f.name) is None)

    def has(self, kernel: str) -> bool:
        """True when ``kernel`` is available."""
        return getattr(self, kernel) is not None

    def require(self, kernel: str) -> Callable:
        """The kernel ``kernel``, or :class:`KernelMissing` naming it and where it should come from."""
        fn = getattr(self, kernel)
        if fn is None:
            raise KernelMissing(f"kernel {kernel!r} is not available from {self.name} "
                                f"({self.note or 'not emitted yet'}); run `make generate`")
        return fn


_ACTIVE: list[Kernels] = []


def active() -> Kernels:
    """The kernels in use: the innermost :func:`use`, else those of :mod:`generated`."""
    if not _ACTIVE:
        _ACTIVE.append(from_generated())
    return _ACTIVE[-1]


@contextlib.contextmanager
def use(kernels: Kernels) -> Iterator[Kernels]:
    """Use ``kernels`` inside the ``with`` block (e.g. an independent reference in a test)."""
    _ACTIVE.append(kernels)
    try:
        yield kernels
    finally:
        _ACTIVE.pop()


# -- binding of generated/ ----------------------------------------------------------------------

#: Where the runtime assembly of the coefficient kernels (any n) may live, first match wins.
RUNTIME_MODULES = ("chaplygin_nd.runtime.axisym",)


_BROKEN: dict[str, str] = {}


def _module(name):
    try:
        return importlib.import_module(name)
    except ImportError:
        return None
    except SyntaxError as exc:  # e.g. an invalid escape under -W error: report, do not crash
        _BROKEN[name] = f"{name} does not import ({exc.msg}, {exc.filename}:{exc.lineno})"
        return None


def _runtime():
    for name in RUNTIME_MODULES:
        mod = _module(name)
        if mod is not None:
            return mod
    return None


def _component(gen, stem, n):
    """The public component kernel ``{stem}_{n}d``, wrapped with a fast path for one point.

    A single integration calls the kernel on one point thousands of times; the public kernel's
    batching costs ~50 us there, while the same generated block evaluated on Python floats costs
    ~5 us. For a batch of one we therefore call the generated component form ``{stem}_{n}d_components``
    (same expressions, same file) on floats; any other batch goes through the public kernel."""
    fn = getattr(gen, f"{stem}_{n}d", None) if gen is not None else None
    block = getattr(gen, f"{stem}_{n}d_components", None) if gen is not None else None
    return _fast(fn, block, _SHAPES.get((stem, n)))


def _fast(fn, block, shape):
    """``fn(*arrays, a, b)`` with the one-point fast path through ``block`` (see :func:`_component`)."""
    if fn is None or block is None or shape is None:
        return fn
    size = int(np.prod(shape))

    def call(*args):
        *arrays, a, b = args
        arrays = [np.asarray(v, dtype=float) for v in arrays]
        if all(v.ndim <= 2 and v.size == v.shape[-1] for v in arrays):
            flat = [c for v in arrays for c in v.ravel().tolist()]
            out = [0.0] * size
            block(*flat, float(a), float(b), out)
            return np.array(out).reshape(arrays[0].shape[:-1] + shape)
        return fn(*args)
    return call


_SHAPES = {("angular_velocity_axisym", 3): (3,), ("angular_velocity_axisym", 4): (6,),
           ("zeta", 3): (3,), ("zeta", 4): (6,),
           ("L_matrix_axisym", 3): (3, 3), ("L_matrix_axisym", 4): (6, 6)}


def _missing(what, n):
    broken = "; ".join(_BROKEN.values())
    raise KernelMissing(f"{what} for n = {n}: generated/ has component kernels for n = 3, 4 only "
                        f"and no runtime assembly for other n ({', '.join(RUNTIME_MODULES)})"
                        + (f"; {broken}" if broken else ""))


def from_generated() -> Kernels:
    """The kernels :mod:`generated` provides today, in the matrix interface."""
    gen = _module("chaplygin_nd.generated.axisym")
    runtime = _runtime()
    if gen is None and runtime is None:
        return Kernels(name="generated", note="generated/axisym.py does not exist yet")

    def dispatch(stem, runtime_name, label, apply, doc):
        """``f(X, gamma, a, b)``: the component kernel ``{stem}_{n}d`` where it is generated for this
        n (``apply(kernel, vec(X), gamma, a, b)`` gives vec-coordinates), else the ``kernels``
        runtime (any n), else an error naming what is missing."""
        def call(X, gamma, a, b):
            n = gamma.shape[-1]
            fn = _component(gen, stem, n)
            if fn is not None:
                return so.unvec(apply(fn, so.vec(X), gamma, a, b), n)
            rt = getattr(runtime, runtime_name, None) if runtime is not None else None
            if rt is not None:
                return rt(X, gamma, a, b)
            _missing(label, n)
        call.__doc__ = doc
        return call

    def direct(fn, x, gamma, a, b):
        return fn(x, gamma, a, b)

    def matrix(fn, x, gamma, a, b):
        return np.einsum("...ij,...j->...i", fn(gamma, a, b), x)

    angular_velocity = dispatch("angular_velocity_axisym", "angular_velocity", "L_gamma^{-1}",
                                direct, r"$\Omega = L_\gamma^{-1}(M)$ (P:inversion).")
    L_gamma = dispatch("L_matrix_axisym", "L_gamma", "L_gamma", matrix,
                       r"$M = L_\gamma(\Omega)$ (eq:M-O-axi-symm).")
    zeta = dispatch("zeta", "zeta", "zeta", direct,
                    r"$\zeta$ of Th:Re for $(M_0, \gamma_0)\in\mathcal V$.")

    red = _module("chaplygin_nd.generated.reduced")
    reduced_field = _fast(getattr(red, "reduced_field", None),
                          getattr(red, "reduced_field_components", None), (7,))
    reduced_integrals = _fast(getattr(red, "reduced_integrals", None),
                              getattr(red, "reduced_integrals_components", None), (4,))
    horizontal = getattr(red, "horizontal_solution", None) if red is not None else None
    return Kernels(name="generated", L_gamma=L_gamma, angular_velocity=angular_velocity,
                   zeta=zeta, reduced_field=reduced_field, reduced_integrals=reduced_integrals,
                   horizontal=horizontal,
                   horizontal_A=getattr(red, "horizontal_A", None) if red is not None else None,
                   horizontal_blocks=getattr(red, "horizontal_blocks", None) if red is not None else None,
                   note="generated/axisym.py" + (f" + {runtime.__name__}" if runtime else "")
                   + (" + generated/reduced.py" if red is not None else ""))


# -- the other generated code simulate/ evaluates ------------------------------------------------


def p_coefficients(M, gamma) -> np.ndarray:
    r"""Coefficients of $p(\lambda,\sigma) = \det(M + \sigma\gamma\gamma^T - \lambda\,\mathrm{Id})$
    (eq:pol-first-integrals), ``out[..., i, j]`` multiplying $\lambda^i\sigma^j$, any $n$:
    :func:`runtime.axisym.p_coefficients` (the generated closed form for $n = 3, 4$, batched
    eigenvalues otherwise)."""
    from chaplygin_nd.runtime.axisym import p_coefficients as kernel

    return kernel(M, gamma)


def reduced5():
    r"""The module :mod:`generated.reduced5`: the ten $SO(4)$-invariants of $n = 5$ and the reduced
    integrals in them (S6:reduced-n5), as emitted by ``make generate``."""
    return importlib.import_module("chaplygin_nd.generated.reduced5")


def expression_builders():
    r"""The module :mod:`generated.expression_builders`: the derived fields written over an
    arithmetic object (NumPy, heyoka expressions), from which the heyoka systems are built."""
    return importlib.import_module("chaplygin_nd.generated.expression_builders")
