r"""An exact counterexample of the identity engine (:mod:`symbolic.exact.identity`): a rational point and
the exact non-zero residual there, rendered as text and as LaTeX (components gathered into
vectors, $\gamma = (\tfrac{2}{3}, \dots)$)."""

from __future__ import annotations

import re
from dataclasses import dataclass

import sympy as sp

__all__ = ["Counterexample"]


@dataclass(frozen=True)
class Counterexample:
    """An exact point where a claimed identity fails, with the exact non-zero residual there."""

    point: tuple[tuple[str, object], ...]
    residual: object
    where: str = ""

    def text(self) -> str:
        at = ", ".join(f"{name} = {_text_value(value)}" for name, value in _grouped(self.point))
        loc = f" ({self.where})" if self.where else ""
        return f"at {at}: residual{loc} = {_text_value(self.residual)} != 0"

    def latex(self) -> str:
        r"""The point as a reader writes it: components gathered into vectors
        ($\gamma = (\tfrac{2}{3}, \dots)$), then the exact non-zero residual."""
        at = ",\\; ".join(f"{_latex_name(name)} = {_latex_value(value)}"
                          for name, value in _grouped(self.point))
        loc = f"\\ \\text{{({self.where})}}" if self.where else ""
        return (f"{at} \\;\\Rightarrow\\; \\text{{residual}}{loc} = "
                f"{_latex_value(self.residual)} \\neq 0")


_INDEXED = re.compile(r"^([A-Za-z]+)_?(\d+)$")
#: indexed names that are separate quantities, not the components of one vector (the integrals)
_NOT_VECTORS = {"F", "f"}


def _grouped(point) -> list[tuple[str, object]]:
    """``gamma1, gamma2, gamma3`` (in any order) -> ``gamma = (gamma1, gamma2, gamma3)`` when the
    indices of one base name are exactly 1..k (k >= 2); other names stay as they are, in order."""
    bases: dict[str, dict[int, object]] = {}
    for name, value in point:
        m = _INDEXED.match(name)
        if m:
            bases.setdefault(m.group(1), {})[int(m.group(2))] = value
    vectors = {base: comps for base, comps in bases.items()
               if len(comps) >= 2 and sorted(comps) == list(range(1, len(comps) + 1))
               and base not in {name for name, _ in point} and base not in _NOT_VECTORS}
    out: list[tuple[str, object]] = []
    done: set[str] = set()
    for name, value in point:
        m = _INDEXED.match(name)
        if m and m.group(1) in vectors:
            if m.group(1) not in done:
                comps = vectors[m.group(1)]
                out.append((m.group(1), tuple(comps[i] for i in sorted(comps))))
                done.add(m.group(1))
            continue
        out.append((name, value))
    return out


def _as_tuple(value):
    """A vector (tuple, list, or a one-row/one-column matrix) as a tuple; anything else: None."""
    if isinstance(value, (tuple, list)):
        return tuple(value)
    if isinstance(value, sp.MatrixBase) and 1 in value.shape:
        return tuple(value)
    return None


def _text_value(value) -> str:
    vec = _as_tuple(value)
    if vec is not None:
        return "(" + ", ".join(sp.sstr(v) for v in vec) + ")"
    if isinstance(value, sp.MatrixBase):
        return "[" + "; ".join(", ".join(sp.sstr(v) for v in value.row(i))
                               for i in range(value.rows)) + "]"
    return sp.sstr(value)


def _latex_value(value) -> str:
    vec = _as_tuple(value)
    if vec is not None:
        return "(" + ", ".join(_latex_value(v) for v in vec) + ")"
    if isinstance(value, sp.MatrixBase):  # full-size fractions keep the rows of a matrix apart
        return sp.latex(value).replace("\\frac", "\\dfrac")
    return sp.latex(value).replace("\\frac", "\\tfrac").replace("\\dfrac", "\\tfrac")


def _latex_name(name: str) -> str:
    return sp.latex(sp.Symbol(name))


