r"""Which printed formulas each ledger row reaches — the map behind ``make mutate``.

DESIGN rule: every printed object a row checks is one function of :mod:`symbolic.printed` and the
row calls it. This module *observes* that while rows run, without decorating anything:

* :func:`printed_functions` lists the public functions of ``symbolic/printed/section*.py``
  (name not starting with ``_``, defined in that module), keyed ``"section4.K"``.
* :class:`Recorder` swaps each function's ``__code__`` for a two-line trampoline that records the
  key and calls an untouched clone of the original. Because the code object of the function
  itself is replaced, every route is seen: ``printed.K(...)`` in a proof, a name imported with
  ``from ... import K``, and calls between printed functions (``Omega_inverse`` calling ``K``).
  The cost is one extra Python call per printed call (unlike ``sys.settrace``, which roughly
  doubled the time of a row). On exit the original code objects are put back.

The runner records, per row, the printed functions it reached (``Result.printed``); a run of the
whole ledger fails when a public printed function is reached by no row (:func:`unreached`).
``python -m chaplygin_nd.ledger.remap`` runs every row and writes ``ledger/reach.json`` (row -> functions and
function -> rows) atomically; ``make mutate`` uses the same map to pick the rows a mutant must
change, and the test suite uses it only to choose which rows to re-run live.
"""

from __future__ import annotations

import importlib
import json
import os
import tempfile
from pathlib import Path
from types import FunctionType

PRINTED_MODULES = ("section2", "section3", "section4", "section5")
MAP_PATH = Path(__file__).resolve().parent / "reach.json"
_HOOK = "__printed_reach_hook__"


def printed_functions() -> dict[str, FunctionType]:
    """``{"sectionN.name": function}`` for every public function of ``symbolic/printed/``."""
    out: dict[str, FunctionType] = {}
    for name in PRINTED_MODULES:
        mod = importlib.import_module(f"chaplygin_nd.symbolic.printed.{name}")
        for attr, obj in sorted(vars(mod).items()):
            if (not attr.startswith("_") and isinstance(obj, FunctionType)
                    and obj.__module__ == mod.__name__):
                out[f"{name}.{attr}"] = obj
    return out


def _clone(fn: FunctionType) -> FunctionType:
    copy = FunctionType(fn.__code__, fn.__globals__, fn.__name__, fn.__defaults__, fn.__closure__)
    copy.__kwdefaults__ = fn.__kwdefaults__
    return copy


def _trampoline(key: str, fn: FunctionType):
    source = f"def {fn.__name__}(*args, **kwargs):\n    return {_HOOK}({key!r})(*args, **kwargs)\n"
    namespace: dict = {}
    exec(compile(source, f"<reach {key}>", "exec"), namespace)  # noqa: S102 - fixed template
    return namespace[fn.__name__].__code__


class Recorder:
    """Context manager recording which printed functions are called inside it (``.calls``)."""

    def __init__(self, functions: dict[str, FunctionType] | None = None):
        self.functions = functions if functions is not None else printed_functions()
        self.calls: set[str] = set()
        self._saved: dict[str, object] = {}

    def __enter__(self) -> Recorder:
        clones = {key: _clone(fn) for key, fn in self.functions.items()}

        def hook(key: str):
            self.calls.add(key)
            return clones[key]

        for key, fn in self.functions.items():
            fn.__globals__[_HOOK] = hook
            self._saved[key] = fn.__code__
            fn.__code__ = _trampoline(key, fn)
        return self

    def __exit__(self, *exc) -> None:
        for key, code in self._saved.items():
            fn = self.functions[key]
            fn.__code__ = code
            fn.__globals__.pop(_HOOK, None)
        self._saved.clear()


def unreached(printed_by_row: dict[str, list[str]]) -> list[str]:
    """Public printed functions reached by no row of ``printed_by_row`` (row -> functions)."""
    seen = {f for fs in printed_by_row.values() for f in fs}
    return sorted(set(printed_functions()) - seen)


def rows_by_function(printed_by_row: dict[str, list[str]]) -> dict[str, list[str]]:
    """Invert the map: function -> the rows that reach it (ledger order kept)."""
    out: dict[str, list[str]] = {key: [] for key in printed_functions()}
    for row, fs in printed_by_row.items():
        for f in fs:
            out.setdefault(f, []).append(row)
    return out


def write_json_atomic(data: dict, path: Path) -> None:
    """Write ``data`` as JSON to ``path`` through a temporary file and ``os.replace``."""
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            json.dump(data, fh, indent=1, sort_keys=True)
            fh.write("\n")
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def load(path: Path = MAP_PATH) -> tuple[dict[str, list[str]], dict[str, float]]:
    """The stored map (row -> functions, row -> seconds), written by ``python -m chaplygin_nd.ledger.remap``."""
    data = json.loads(path.read_text(encoding="utf-8"))
    return data["rows"], data.get("seconds", {})


def cover(printed_by_row: dict[str, list[str]], seconds: dict[str, float]) -> list[str]:
    """A small set of rows reaching every function the map reaches (greedy: most new functions
    per second first) — what a test re-runs live to show every printed function is reached."""
    todo = {f for fs in printed_by_row.values() for f in fs}
    chosen: list[str] = []
    while todo:
        best = max(printed_by_row, key=lambda r: (len(todo & set(printed_by_row[r]))
                                                  / (0.2 + seconds.get(r, 1.0)), r))
        gain = todo & set(printed_by_row[best])
        if not gain:
            break
        chosen.append(best)
        todo -= gain
    return chosen


def save(printed_by_row: dict[str, list[str]], seconds: dict[str, float] | None = None,
         path: Path = MAP_PATH) -> None:
    """Write the map (and each row's seconds, to choose cheap rows) atomically."""
    write_json_atomic({"rows": printed_by_row, "functions": rows_by_function(printed_by_row),
                       "seconds": {r: round(t, 2) for r, t in (seconds or {}).items()}}, path)
