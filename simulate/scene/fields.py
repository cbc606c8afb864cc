"""Reading the fields of a scene file: one :class:`SceneError` naming the field and the fix, and
the readers of numbers, arrays and known keys that every table of a scene (and of a frequency map)
validates with. ``fail(where, problem, fix)`` raises the error of the scene being read."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["SceneError", "unknown", "number", "array"]


class SceneError(ValueError):
    """A scene is invalid; the message names the field (not for ``where = "file"``: the file as a
    whole, which ``source`` names already) and the fix."""

    def __init__(self, source: str, where: str, problem: str, fix: str):
        self.field = where
        field = "" if where == "file" else f"{where}: "
        super().__init__(f"{source}: {field}{problem}. Fix: {fix}")



def unknown(table, allowed, prefix, fail):
    """Fail on the first key of ``table`` not in ``allowed`` (``prefix``: the table's name)."""
    for key in table:
        if key not in allowed:
            fail(f"{prefix}{key}", "unknown key", f"use only {', '.join(sorted(allowed))}")


def number(table, key, fail, integer=False, required=False, default=0.0, where=None):
    """The finite number (or integer) ``table[key]``; ``default`` when absent unless ``required``."""
    where = where or key
    if key not in table:
        if required:
            fail(where, "missing", f"add {key} = <{'integer' if integer else 'number'}>")
        return default
    v = table[key]
    ok = isinstance(v, int) if integer else isinstance(v, (int, float))
    if isinstance(v, bool) or not ok or (not integer and not math.isfinite(v)):
        fail(where, f"{v!r} is not a finite {'integer' if integer else 'number'}",
             f"write {key} = <{'integer' if integer else 'number'}>")
    return int(v) if integer else float(v)


def array(value, shape, where, fail):
    """``value`` as a finite float array of exactly ``shape``."""
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError, RecursionError, OverflowError):
        fail(where, "not a rectangular array of numbers", f"give an array of shape {shape}")
    if arr.shape != shape:
        fail(where, f"shape {arr.shape}, expected {shape}", f"give an array of shape {shape}")
    if not np.all(np.isfinite(arr)):
        fail(where, "contains a non-finite number", "give finite numbers")
    return arr
