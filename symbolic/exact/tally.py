r"""Which engine decided which zero test, per process: the tally the runner reads after each row
(:func:`engine_tally`, :func:`engine_note`: the sentence a row's method ends with) and the seconds
each engine spent (:func:`point_timings`, read by ``chaplygin bench exact_growth``). The engines of
:mod:`symbolic.exact.identity` record here."""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping

__all__ = ["point_timings", "engine_tally", "reset_engine_tally", "engine_note", "record",
           "dimension", "timing"]


_TALLY: Counter = Counter()
#: (kind, label, size, engine, seconds) of every zero test (the bench reads it); size is n for a
#: seeded point, the number of variables for an identity
_TIMINGS: list[tuple[str, str, int | None, str, float]] = []


def point_timings(clear: bool = False) -> list[tuple[str, str, int | None, str, float]]:
    """(kind, label, size, engine, seconds) of each engine's part of each zero test: ``points``
    (one seeded point, value and zero test; size = n) and ``identity`` (one
    :func:`symbolic.exact.identity.rational_identity`; size = number of variables). ``clear`` empties the record."""
    out = list(_TIMINGS)
    if clear:
        _TIMINGS.clear()
    return out


def dimension(pt: dict) -> int | None:
    """n of a sampled point: its ``n``, else the length of its ``gamma``."""
    if isinstance(pt.get("n"), int):
        return pt["n"]
    g = pt.get("gamma")
    return len(g) if g is not None else None


def record(kind: str, engines: str, label: str = "", size: int | None = None,
           spent: Mapping[str, float] | None = None) -> None:
    """Count one zero test of ``kind`` decided by ``engines``, and the seconds each spent."""
    _TALLY[(kind, engines)] += 1
    for engine, seconds in (spent or {}).items():
        _TIMINGS.append((kind, label, size, engine, seconds))


def timing(kind: str, label: str, size: int | None, engine: str, seconds: float) -> None:
    """Record the seconds one engine spent on one zero test (:func:`point_timings`)."""
    _TIMINGS.append((kind, label, size, engine, seconds))


def engine_tally() -> dict[tuple[str, str], int]:
    """(kind, engines) -> number of zero tests since :func:`reset_engine_tally`; kind is
    ``identity`` (:func:`symbolic.exact.identity.rational_identity`) or ``points`` (one seeded point of
    :func:`symbolic.exact.identity.zero_at_points`)."""
    return dict(_TALLY)


def reset_engine_tally() -> None:
    """Forget the tally (the runner calls it before each row)."""
    _TALLY.clear()


def engine_note(tally: Mapping[tuple[str, str], int]) -> str:
    """The sentence a row's method ends with: which engines decided its zero tests."""
    if not tally:
        return ("engines: no zero test through symbolic.exact.identity (exact values computed in the "
                "proof's own SymPy code; one engine)")
    kinds = {"identity": "identities", "points": "points"}
    parts = []
    for kind in ("identity", "points"):
        items = sorted((e, c) for (k, e), c in tally.items() if k == kind)
        if items:
            parts.append(f"{kinds[kind]} " + ", ".join(f"{e} x{c}" for e, c in items))
    return "engines: " + "; ".join(parts) + " (expressions and point values built by SymPy)"
