r"""The record file of ``chaplygin mutate-derivations`` (``mutation-derivations.json``): reading and
writing it, its summary lines, and which records a ``--resume`` may keep (:func:`current`).

A record names its mutant by target, function and mutation text, and carries the digest of the
function's source when it was decided (``"source"``: :func:`operators.source_digest`). On
``--resume`` or ``--rerun`` a kept record is checked against the code as it is now:

* **gone** — the mutation text is no longer a mutant of the function (a line moved or changed):
  dropped, and the function's mutants as they are now are run;
* **stale** — the mutant still exists but the function's source changed since it was decided
  (the digest differs): dropped and run again; the functions are named in one line;
* **unstamped** — a record written before digests were kept: kept when its mutant exists, and
  stamped with the digest of the code it is kept for (said in one line, with the count);
* records of the same mutant twice are kept once, and each kept record takes the mutant's index
  in the code as it is now.

:func:`consistency` says whether a record file matches the code: no record of a mutant the code
no longer has, none stale, none twice, and which mutants are undecided.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

from chaplygin_nd.ledger.reach import write_json_atomic


def plural(count: int, noun: str) -> str:
    """``1 job``, ``2 jobs``."""
    return f"{count} {noun}{'' if count == 1 else 's'}"


def compared_outcomes(other: Path) -> dict[tuple[str, str], str] | str:
    """``(function, mutation) -> outcome`` of the run saved at ``other`` (a mutation.json), or the
    one-line error saying why it cannot be read: checked before the run, so a wrong ``--compare``
    never costs a whole mutation run and its results."""
    import json

    try:
        mutants = json.loads(Path(other).read_text(encoding="utf-8"))["mutants"]
        return {(r["function"], r["mutation"]): r["outcome"] for r in mutants}
    except OSError as exc:
        return f"--compare {other}: cannot read it ({exc.strerror or exc})"
    except (ValueError, KeyError, TypeError) as exc:
        return (f"--compare {other}: not a mutation.json of `chaplygin mutate` ({type(exc).__name__}:"
                f" {exc})")


def summary(records: list[dict], target: str, seconds: float | None = None, cpu: float = 0.0,
            ran: int | None = None) -> str:
    """One line per target: the outcomes of all its ``records``, and (``seconds`` given) the time
    of this run, which ran ``ran`` of them (the others were kept from the file resumed or re-run)."""
    count = {k: sum(r["outcome"] == k for r in records)
             for k in ("killed", "equivalent", "survived", "error")}
    functions = len({(r["target"], r["function"]) for r in records})
    line = (f"{target}: {plural(len(records), 'mutant')} of {plural(functions, 'function')}: "
            f"{count['killed']} killed, {count['equivalent']} equivalent, "
            f"{count['survived']} survived, {plural(count['error'], 'error')}")
    if seconds is None:
        return line
    ran = len(records) if ran is None else ran
    return f"{line}; this run: {ran} mutants in {seconds:.0f} s wall, {cpu:.0f} s CPU"


def _now(targets) -> dict[tuple[str, str, str], tuple[int, str]]:
    """Every mutant of ``targets`` as the code is now: ``(target, function, mutation) -> (index,
    source digest of its function)``."""
    from chaplygin_nd.ledger.mutation import derivations
    from chaplygin_nd.ledger.mutation.operators import source_digest

    out: dict[tuple[str, str, str], tuple[int, str]] = {}
    for target in sorted(targets):
        every = derivations.functions(target)
        digests: dict[str, str] = {}
        for m in derivations.sample(target, None):
            if m.function not in digests:
                digests[m.function] = source_digest(every[m.function])
            out[(target, m.function, f"{m.operator}: {m.description}")] = (m.index,
                                                                           digests[m.function])
    return out


def _sorted_by_kind(records: list[dict], now: dict) -> dict[str, list[dict]]:
    """The records of :func:`current`, sorted into ``kept``, ``gone``, ``stale``, ``twice`` and
    ``unstamped`` (a record is in ``kept`` and, when it has no digest, in ``unstamped`` too)."""
    kinds: dict[str, list[dict]] = {k: [] for k in ("kept", "gone", "stale", "twice", "unstamped")}
    seen: set[tuple[str, str, str]] = set()
    for r in reversed(records):  # the last record of a mutant is the latest decision
        key = (r["target"], r["function"], r["mutation"])
        if key not in now:
            kinds["gone"].append(r)
        elif key in seen:
            kinds["twice"].append(r)
        elif r.get("source", now[key][1]) != now[key][1]:
            kinds["stale"].append(r)
        else:
            seen.add(key)
            kinds["kept"].append(r)
            if "source" not in r:
                kinds["unstamped"].append(r)
    kinds["kept"].reverse()
    return kinds


def _functions_of(records: list[dict]) -> str:
    return ", ".join(sorted({r["function"] for r in records}))


def current(records: list[dict]) -> list[dict]:
    """The records kept from an earlier run (``--resume``, ``--rerun``) that still stand for the
    code as it is now, each with its mutant's index now; the others are dropped, each kind with one
    line naming its functions, and their mutants are run as not yet decided: a record of a mutant
    the code no longer has (a line moved, the code changed), a stale one (the mutant's text is
    still there, but its function's source changed since), a second record of one mutant. A
    record without a digest (written before digests were kept) is kept when its mutant exists, and
    stamped with the digest of the code it is now kept for (said in one line)."""
    if not records:
        return records
    now = _now({r["target"] for r in records})
    kinds = _sorted_by_kind(records, now)
    said = {"gone": "of mutants the code no longer has ({}): their functions changed since that "
                    "run",
            "stale": "decided on another source of their function ({}): stale, decided again",
            "twice": "of a mutant recorded twice ({}): the latest kept"}
    for kind, text in said.items():
        if kinds[kind]:
            print(f"dropped {plural(len(kinds[kind]), 'record')} "
                  + text.format(_functions_of(kinds[kind])), flush=True)
    if kinds["unstamped"]:
        print(f"kept {plural(len(kinds['unstamped']), 'record')} written without the digest of "
              "their function's source: their mutants exist, but whether their functions changed "
              "since cannot be told; stamped with the digest of the code as it is now",
              flush=True)
    for r in kinds["kept"]:
        index, digest = now[(r["target"], r["function"], r["mutation"])]
        r.update(index=index, source=digest)
    return kinds["kept"]


def consistency(records: list[dict], targets=("derivations", "runtime")) -> dict[str, list]:
    """How a record file stands against the code as it is now (``--check``): the records of
    mutants the code no longer has (``gone``), decided on another source of their function
    (``stale``), recorded twice (``twice``), without a digest (``unstamped``), whose index is not
    the mutant's index now (``moved``), and the mutants of ``targets`` no record decides
    (``undecided``). Consistent when all are empty but ``unstamped``."""
    now = _now(set(targets) | {r["target"] for r in records})
    kinds = _sorted_by_kind(records, now)
    decided = {(r["target"], r["function"], r["mutation"]) for r in kinds["kept"]}
    return {"gone": kinds["gone"], "stale": kinds["stale"], "twice": kinds["twice"],
            "unstamped": kinds["unstamped"],
            "moved": [r for r in kinds["kept"]
                      if r.get("index") != now[(r["target"], r["function"], r["mutation"])][0]],
            "undecided": sorted(k for k in now if k[0] in targets and k not in decided)}


def cpu_seconds() -> float:
    """CPU seconds of this process and its finished children (the workers, once joined; not the
    baseline's forkserver workers, grandchildren of this process)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def read(path) -> tuple[list[dict], list[dict]]:
    """The records and runs of an earlier run written to ``path`` (none if there is no file)."""
    import json

    if not path.is_file():
        return [], []
    data = json.loads(path.read_text(encoding="utf-8"))
    return data["mutants"], data.get("runs", [])


def progress(run: dict, ran: int, tasks: int, t0: float, c0: float) -> None:
    run.update({"mutants run": ran, "of": tasks, "wall seconds": round(time.perf_counter() - t0),
                "cpu seconds (this process and joined workers)": round(cpu_seconds() - c0)})


def write(records, runs, args) -> None:
    """``--out``: one summary line per target over all its records, the runs that made them
    (command, mutants run, wall and CPU seconds, load), ``complete`` when every run finished."""
    order = {"derivations": 0, "runtime": 1}
    targets = sorted({r["target"] for r in records}, key=lambda t: order.get(t, 2))
    lines = [summary([r for r in records if r["target"] == t], t) for t in targets]
    if len(targets) > 1:
        lines.append(summary(records, "total"))
    write_json_atomic({"summary": lines, "seed": args.seed, "sample": args.sample, "runs": runs,
                       "complete": all(r.get("complete") for r in runs),
                       "mutants": sorted(records, key=lambda r: (order.get(r["target"], 2),
                                                                 r["function"], r["index"]))},
                      args.out)

