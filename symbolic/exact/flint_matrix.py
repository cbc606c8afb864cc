r"""Printed matrix formulas evaluated in FLINT arithmetic: a SymPy-like matrix over ``fmpq``.

The printed formulas of :mod:`symbolic.printed` are written with matrix operators only
(``A * B``, ``A + B``, ``A - B``, ``-A``, ``c * A``, ``A.T``, ``A[i, j]``), e.g.
$H(M, \gamma) = M - (M\gamma)\wedge\gamma$ with $u\wedge v = uv^T - vu^T$ (eq:def-H-V). Called
with :class:`FlintMatrix` arguments they run, unchanged, on FLINT's ``fmpq_mat``: the
transcription stays literal (rule 1) while the arithmetic at a rational point is FLINT's, not
SymPy's generic ``Rational`` arithmetic (which dominates such checks at large $n$: the printed
$H$ on all $n(n-1)/2$ basis elements of $\mathfrak{so}(24)$ is ~1 s in SymPy, ~0.03 s here).

:func:`formula_matrix` gives a rational matrix in the *current engine's* formula type
(:func:`symbolic.exact.flint_engine.use_engine`): a SymPy ``Matrix`` for SymPy, a :class:`FlintMatrix`
for FLINT. A residual built from it is evaluated by each engine in its own arithmetic (it counts
as an engine-dispatched step), and :func:`symbolic.exact.identity.zero_at_points` compares the two values.
Domain: rational entries; anything else raises as :func:`symbolic.exact.flint_engine.to_fmpq` does.
"""

from __future__ import annotations

from collections.abc import Sequence

import flint
import sympy as sp
from chaplygin_nd.symbolic.exact.flint_engine import current_engine, note_call, to_fmpq

__all__ = ["FlintMatrix", "formula_matrix", "from_columns", "entries"]


class FlintMatrix:
    """A rational matrix (``fmpq_mat``) with the operators of a SymPy ``Matrix`` that the printed
    formulas use: ``* + -`` (with a FlintMatrix, a SymPy matrix of rationals on either side, or a
    rational scalar for ``*``), unary ``-``, ``.T``, ``.shape``, ``.rows``, ``.cols``, ``[i, j]``
    and column slices ``[:, j]``. A non-rational entry raises (``TypeError``/``ValueError``)."""

    __slots__ = ("mat",)
    #: SymPy's matrix operators defer to the operand of higher priority (a SymPy ``Matrix`` on
    #: the left of ``*``, ``+``, ``-`` calls our reflected operator)
    _op_priority = 20.0

    def __init__(self, mat: flint.fmpq_mat):
        if not isinstance(mat, flint.fmpq_mat):
            raise TypeError(f"FlintMatrix wraps an fmpq_mat, not {type(mat).__name__}")
        self.mat = mat

    @property
    def rows(self) -> int:
        return self.mat.nrows()

    @property
    def cols(self) -> int:
        return self.mat.ncols()

    @property
    def shape(self) -> tuple[int, int]:
        return self.rows, self.cols

    @property
    def T(self) -> FlintMatrix:  # noqa: N802 (SymPy's name)
        return FlintMatrix(self.mat.transpose())

    @staticmethod
    def _operand(other, *, scalar: bool = True):
        """``other`` as ``fmpq_mat`` (a FlintMatrix, or a SymPy matrix of rationals such as
        ``sp.eye(n)`` in a formula) or, if ``scalar``, as ``fmpq`` (a rational number)."""
        if isinstance(other, FlintMatrix):
            return other.mat
        if isinstance(other, sp.MatrixBase):
            return _to_fmpq_mat(other)
        if scalar and isinstance(other, (flint.fmpq, flint.fmpz, int)) and not isinstance(other, bool):
            return flint.fmpq(other)
        if scalar and isinstance(other, sp.Basic) and other.is_Rational:
            return to_fmpq(other)
        raise TypeError(f"a FlintMatrix combines with a rational matrix or number, not {other!r}")

    def __mul__(self, other) -> FlintMatrix:
        return FlintMatrix(self.mat * self._operand(other))

    def __rmul__(self, other) -> FlintMatrix:
        return FlintMatrix(self._operand(other) * self.mat)

    def __add__(self, other) -> FlintMatrix:
        return FlintMatrix(self.mat + self._operand(other, scalar=False))

    def __radd__(self, other) -> FlintMatrix:
        return FlintMatrix(self._operand(other, scalar=False) + self.mat)

    def __sub__(self, other) -> FlintMatrix:
        return FlintMatrix(self.mat - self._operand(other, scalar=False))

    def __rsub__(self, other) -> FlintMatrix:
        return FlintMatrix(self._operand(other, scalar=False) - self.mat)

    def __neg__(self) -> FlintMatrix:
        return FlintMatrix(-self.mat)

    def __eq__(self, other) -> bool:
        return isinstance(other, FlintMatrix) and self.mat == other.mat

    __hash__ = None  # type: ignore[assignment]  # mutable: unhashable, as list

    def __getitem__(self, key):
        if isinstance(key, tuple) and len(key) == 2:
            i, j = key
            if isinstance(i, slice) and i == slice(None) and isinstance(j, int):
                return FlintMatrix(flint.fmpq_mat(self.rows, 1,
                                                  [self.mat[r, j] for r in range(self.rows)]))
            if isinstance(i, int) and isinstance(j, int):
                return self.mat[i, j]
        if isinstance(key, int) and self.cols == 1:
            return self.mat[key, 0]
        raise TypeError(f"FlintMatrix supports [i, j], [i] of a column and [:, j], not {key!r}")

    def __repr__(self) -> str:
        return f"FlintMatrix({self.mat!r})"


def _to_fmpq_mat(A: sp.MatrixBase) -> flint.fmpq_mat:
    return flint.fmpq_mat(A.rows, A.cols, [to_fmpq(v) for v in _flat(A)])


def formula_matrix(A: sp.Matrix):
    """``A`` (rational entries) in the current engine's formula type: itself (a SymPy ``Matrix``)
    for SymPy, a :class:`FlintMatrix` for FLINT. Counts as an engine-dispatched step."""
    note_call()
    if current_engine() == "flint":
        return FlintMatrix(_to_fmpq_mat(A))
    return A


def from_columns(columns: Sequence[Sequence]):
    """The matrix whose columns are the given sequences of rationals, in the type of the first
    column's entries: :class:`FlintMatrix` for ``fmpq`` entries, a SymPy ``Matrix`` otherwise
    (built directly, not by repeated ``hstack``)."""
    columns = [list(c) for c in columns]
    if not columns:
        raise ValueError("from_columns needs at least one column")
    rows = len(columns[0])
    if any(len(c) != rows for c in columns):
        raise ValueError("columns of different lengths")
    flat = [columns[j][i] for i in range(rows) for j in range(len(columns))]
    if rows and isinstance(columns[0][0], flint.fmpq):
        return FlintMatrix(flint.fmpq_mat(rows, len(columns), flat))
    return sp.Matrix(rows, len(columns), flat)


def entries(A) -> list:
    """The entries of a SymPy ``Matrix`` or :class:`FlintMatrix`, row by row."""
    if isinstance(A, FlintMatrix):
        return A.mat.entries()
    return _flat(A)


def _flat(A: sp.Matrix) -> list:
    return [v for row in A.tolist() for v in row]
