r"""The interface between :mod:`simulate` and the verified kernels of :mod:`generated`.

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
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields

__all__ = ["Kernels", "KernelMissing", "OPTIONAL"]

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
