"""Emit verified SymPy expressions as vectorised NumPy kernels into ``generated/``.

One code path for every kernel: common-subexpression elimination (``sympy.cse``), a NumPy
printer, a banner per file (producer, claim ids, "do not edit", SHA-256 of the inputs, operation
count per kernel), and deterministic text (same input => byte-identical file; no timestamps,
symbols in a fixed order, CSE in canonical order).

Calling convention of a generated kernel ``f(*arguments)``: an argument is an array whose *last*
axis holds its components (``Argument.scalar``: no component axis); all leading axes are batch
axes and broadcast against each other, so a parameter may be a Python float or a batch array.
The result has shape ``batch + Kernel.shape``. The batch is flattened; up to ``CHUNK`` points
are evaluated in one call on the arguments' columns (no copies), more in chunks of ``CHUNK`` points
with component-major (contiguous) temporaries. ``CHUNK`` = 4096 keeps every temporary at 32 KiB:
below glibc's 128 KiB mmap threshold (the former 16384 points were exactly 128 KiB, so each
temporary was mapped and unmapped, ~600 page faults per call at 10^4 points) and inside L2.
``chaplygin bench throughput`` measures the sizes and chunk lengths behind this choice. Constant
outputs broadcast (every output is written into a pre-allocated array).

``chaplygin generate`` rewrites ``generated/``; :func:`stale_report` regenerates into a
temporary folder and returns the diff (empty when up to date) — ``make verify`` calls it.
"""

from __future__ import annotations

import difflib
import hashlib
import importlib
import sys
import tempfile
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import sympy as sp
from sympy.printing.numpy import NumPyPrinter

ROOT = Path(__file__).resolve().parents[2]
GENERATED = ROOT / "generated"
CODEGEN_VERSION = "2"
FIX_COMMAND = "make generate"

#: Kernel modules: (file stem in generated/, "module:function" returning a list of Kernel).
MODULES: tuple[tuple[str, str], ...] = (
    ("sphere3d", "chaplygin_nd.symbolic.codegen.emit.sphere3d:kernels"),
    ("axisym", "chaplygin_nd.symbolic.codegen.emit.axisym:kernels"),
    ("fourd", "chaplygin_nd.symbolic.codegen.emit.fourd:kernels"),
    ("reduced", "chaplygin_nd.symbolic.codegen.emit.reduced:kernels"),
    ("reduced5", "chaplygin_nd.symbolic.codegen.emit.reduced5:kernels"),
)


@dataclass(frozen=True)
class Argument:
    """A kernel argument: ``symbols`` are its components along the last axis (``scalar``: one
    symbol, passed as a number or a batch array without a component axis)."""

    name: str
    symbols: tuple[sp.Symbol, ...]
    scalar: bool = False


@dataclass(frozen=True)
class Kernel:
    """One generated function: ``outputs`` (a SymPy matrix, read row-major) of the arguments'
    symbols, returned with trailing shape ``shape``."""

    name: str
    claims: tuple[str, ...]
    doc: str
    arguments: tuple[Argument, ...]
    outputs: sp.Matrix
    shape: tuple[int, ...]  # trailing output shape, e.g. (3,) or (4, 4)

    def fingerprint(self) -> str:
        parts = [self.name, repr(self.claims), self.doc, repr(self.shape)]
        parts += [f"{a.name}:{a.scalar}:{[s.name for s in a.symbols]}" for a in self.arguments]
        parts += [sp.srepr(e) for e in self.outputs]
        return "\n".join(parts)


class KernelPrinter(NumPyPrinter):
    """NumPy printer with cheap integer powers: ``x**-1`` as a division and small powers as
    products (NumPy's float ``power`` is 10-20x slower than a multiplication)."""

    def __init__(self):
        super().__init__({"fully_qualified_modules": True, "inline": True,
                          "allow_unknown_functions": False})

    def _print_Pow(self, expr, rational=False):
        base, exp = expr.as_base_exp()
        if exp.is_Integer:
            e = int(exp)
            b = self.parenthesize(base, sp.printing.precedence.PRECEDENCE["Pow"])
            if e == 2:
                return f"{b}*{b}"
            if e == 3:
                return f"{b}*{b}*{b}"
            if 3 < e <= 8:
                return f"{b}**{e}"
            if e < 0:
                return f"1/({self._print(base ** (-e))})"
        if exp == sp.Rational(1, 2):
            return f"numpy.sqrt({self._print(base)})"
        return super()._print_Pow(expr, rational=rational)

    def _print_Rational(self, expr):
        return f"({expr.p}/{expr.q})"


def operation_count(replacements, reduced) -> int:
    """Arithmetic operations of a CSE'd kernel (``sympy.count_ops`` summed over all lines)."""
    return sum(sp.count_ops(e) for _, e in replacements) + sum(sp.count_ops(e) for e in reduced)


def _emit_kernel(k: Kernel) -> tuple[str, int]:
    printer = KernelPrinter()
    outputs = list(k.outputs)
    if len(outputs) != _size(k.shape):
        raise ValueError(f"{k.name}: {len(outputs)} outputs for shape {k.shape}")
    replacements, reduced = sp.cse(outputs, symbols=sp.numbered_symbols("t"), order="canonical")
    ops = operation_count(replacements, reduced)
    known = {s for a in k.arguments for s in a.symbols}
    unknown = set().union(*(e.free_symbols for e in outputs)) - known
    if unknown:
        raise ValueError(f"{k.name}: outputs use symbols that are not arguments: {sorted(map(str, unknown))}")
    names = [s.name for a in k.arguments for s in a.symbols]
    block = [f"def {k.name}_components({', '.join(names)}, out):",
             f'    """Component form of ``{k.name}``: one float or 1-D array per scalar component,',
             '    the output components written into ``out[0], out[1], ...`` (no broadcasting, no',
             '    checks; for tight loops on single points)."""']
    for sym, expr in replacements:
        block.append(f"    {sym} = {printer.doprint(expr)}")
    for i, expr in enumerate(reduced):
        block.append(f"    out[{i}] = {printer.doprint(expr)}")
    args = ", ".join(a.name for a in k.arguments)
    comps = ", ".join("0" if a.scalar else str(len(a.symbols)) for a in k.arguments)
    wrapper = [f"def {k.name}({args}):", f'    r"""{k.doc.strip()}', "",
               f"    Claims: {', '.join(k.claims)}. Operations after CSE: {ops}.", '    """',
               f"    return _run({k.name}_components, ({args},), ({comps},), {k.shape!r}, {args!r})"]
    return "\n".join(block) + "\n\n\n" + "\n".join(wrapper) + "\n", ops


def _size(shape: Sequence[int]) -> int:
    size = 1
    for s in shape:
        size *= s
    return size


HEADER = '''r"""{title}

GENERATED by symbolic/codegen/kernels.py (version {version}) from {producer} -- DO NOT EDIT BY HAND.
Regenerate with `make generate`; `make verify` fails when this file is stale.
Claims: {claims}
Source hash (sha256 of the kernel inputs): {digest}
Operation counts after CSE: {counts}
"""

import numpy
import numpy as np

from chaplygin_nd.generated._batching import _run

'''

#: The batching runtime shared by every kernel module (written once, as generated/_batching.py).
RUNTIME = '''"""Batching runtime of the generated kernels: broadcast, chunk, evaluate component-major.

GENERATED by symbolic/codegen/kernels.py (version {version}) -- DO NOT EDIT BY HAND.
Regenerate with `make generate`; `make verify` fails when this file is stale.
"""

import numpy as np

CHUNK = 4096


def _run(block, args, comps, shape, names):
    """Broadcast the batch axes and evaluate ``block`` component-major: up to CHUNK points in one
    call on column views (no copies), more in chunks of CHUNK points (contiguous temporaries)."""
    arrays, batch = [], ()
    for value, c, name in zip(args, comps, names.split(", ")):
        value = np.asarray(value, dtype=float)
        if c and (value.ndim == 0 or value.shape[-1] != c):
            raise ValueError(f"{name} must have shape (..., {c}), got {value.shape}")
        arrays.append(value)
        batch = np.broadcast_shapes(batch, value.shape[:-1] if c else value.shape)
    count = 1
    for s in batch:
        count *= s
    size = 1
    for s in shape:
        size *= s
    flat = []  # per argument: a list of numbers (no batch axes) or a (count, c) array
    for value, c in zip(arrays, comps):
        if (value.shape[:-1] if c else value.shape) == ():
            flat.append(list(value) if c else [float(value)])
        else:
            full = np.broadcast_to(value, batch + ((c,) if c else ()))
            flat.append(full.reshape((count, c) if c else (count, 1)))
    if count <= CHUNK:
        out = np.empty((size, count))
        parts = []
        for value in flat:
            parts.extend(value if type(value) is list else value.T)
        block(*parts, out)
        return out.T.reshape(batch + shape)
    out = np.empty((count, size))
    buffer = np.empty((size, CHUNK))
    for start in range(0, count, CHUNK):
        stop = min(count, start + CHUNK)
        parts = []
        for value in flat:
            parts.extend(value if type(value) is list else np.ascontiguousarray(value[start:stop].T))
        block(*parts, buffer[:, :stop - start])
        out[start:stop] = buffer[:, :stop - start].T
    return out.reshape(batch + shape)
'''


#: The Kernel lists derived in this process, by producer (:func:`kernels_of`). Not a
#: ``functools`` cache, so a recording of the regeneration's calls empties it itself
#: (:func:`ledger.reach.regenerated_and_emitted`); the tests fill it with kernels another worker derived.
KERNELS: dict[str, list[Kernel]] = {}


def kernels_of(producer: str) -> list[Kernel]:
    """The Kernel list a producer ``"module:function"`` returns (derived once per process:
    :data:`KERNELS`)."""
    if producer not in KERNELS:
        module, func = producer.split(":")
        make: Callable[[], list[Kernel]] = getattr(importlib.import_module(module), func)
        KERNELS[producer] = make()
    return KERNELS[producer]


def render(stem: str, producer: str) -> str:
    """The full text of ``generated/{stem}.py`` from the kernels that ``producer`` returns."""
    module = producer.split(":")[0]
    kernels = kernels_of(producer)
    title = (importlib.import_module(module).__doc__ or stem).strip().splitlines()[0]
    digest = hashlib.sha256(("\n\n".join([CODEGEN_VERSION] + [k.fingerprint() for k in kernels]))
                            .encode()).hexdigest()
    bodies, counts = [], []
    for k in kernels:
        body, ops = _emit_kernel(k)
        bodies.append(body)
        counts.append(f"{k.name}={ops}")
    claims = sorted({c for k in kernels for c in k.claims})
    head = HEADER.format(title=title, version=CODEGEN_VERSION, producer=producer,
                         claims=", ".join(claims), digest=digest, counts=", ".join(counts))
    return head + "\n" + "\n\n".join(bodies)


def write(target: Path = GENERATED) -> list[Path]:
    """Write every kernel module into ``target`` (created if needed); returns the paths."""
    target.mkdir(parents=True, exist_ok=True)
    paths = []
    init = target / "__init__.py"
    init.write_text('"""NumPy kernels and expression builders emitted by symbolic/codegen/kernels.py (do not edit; '
                    '`make generate`)."""\n')
    paths.append(init)
    runtime = target / "_batching.py"
    runtime.write_text(RUNTIME.replace("{version}", CODEGEN_VERSION), encoding="utf-8")
    paths.append(runtime)
    for stem, producer in MODULES:
        path = target / f"{stem}.py"
        path.write_text(render(stem, producer), encoding="utf-8")
        paths.append(path)
    from chaplygin_nd.symbolic.codegen.builders import STEM, render_builders

    path = target / f"{STEM}.py"
    path.write_text(render_builders(kernels_of, CODEGEN_VERSION), encoding="utf-8")
    paths.append(path)
    return paths


def diff_report(current_dir: Path, fresh_dir: Path) -> str:
    """'' if the ``*.py`` files of both folders agree byte for byte, else the unified diff and the
    command that fixes it."""
    fresh = {p.name: p.read_text() for p in fresh_dir.glob("*.py")}
    current = {p.name: p.read_text() for p in current_dir.glob("*.py")} if current_dir.exists() else {}
    diff: list[str] = []
    for name in sorted(set(fresh) | set(current)):
        a, b = current.get(name, ""), fresh.get(name, "")
        if a != b:
            diff += difflib.unified_diff(a.splitlines(), b.splitlines(), f"generated/{name}",
                                         f"regenerated/{name}", lineterm="", n=1)
    if not diff:
        return ""
    shown = diff[:80] + ([f"... ({len(diff) - 80} more diff lines)"] if len(diff) > 80 else [])
    return ("generated/ is stale (it differs from what symbolic/ produces now):\n"
            + "\n".join(shown) + f"\nFix: run `{FIX_COMMAND}` and commit generated/.")


def stale_report(target: Path = GENERATED) -> str:
    """Regenerate into a temporary folder; '' if ``target`` matches byte for byte, else the diff
    and the command that fixes it."""
    with tempfile.TemporaryDirectory() as tmp:
        write(Path(tmp))
        return diff_report(target, Path(tmp))


def main(argv: Sequence[str] | None = None) -> int:
    """``chaplygin generate``: rewrite ``generated/`` (arguments: only ``-h``)."""
    import argparse

    parser = argparse.ArgumentParser(
        prog="chaplygin generate",
        description="Rewrite generated/ (NumPy kernels) from the derived SymPy expressions; "
                    "the same as `make generate`.")
    parser.parse_args(argv)
    if not (ROOT / "pyproject.toml").is_file():
        print("error: chaplygin generate: rewrites generated/ of a source checkout (make "
              "generate); an installed package is never written into", file=sys.stderr)
        return 2
    for path in write():
        print(f"wrote {path.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
