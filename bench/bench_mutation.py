"""``chaplygin bench mutation``: the CPU seconds per mutant of ``chaplygin mutate-derivations``,
the rows run from the process parked at the mutated function's first call
(:mod:`chaplygin_nd.ledger.mutation.forkpoint`, the default) against the rows run whole in the
worker (the path before it), side by side in one run on one fixed sample, with the load; and
whether every mutant gets the same verdict both ways (it must).

The sample is every mutant of :data:`FUNCTIONS` (one function per kind of cheapest row the
undecided mutants had when it was chosen — ``S6:first-integrals``, no row (tests alone),
``S7:symmetry-fields``, ``S6:wedge-integrals``, ``S6:euler-jacobi-n5`` — 75 mutants in all). The mutants are planned once (the unmutated rows, the tests that reach
each function); then each path decides all of them in a fresh fork of that planned process,
grouped by function as a run groups them, one path after the other. The CPU counted is the
deciding process's and all its children's (parked processes and their copies). Writes
``bench/out/mutation.md`` and ``.json``; ``--quick``: the first function only.
"""

from __future__ import annotations

import json
import os
import pickle
import resource
import tempfile
import time
from pathlib import Path

FUNCTIONS = ("search.known_integrals.products", "search.weights.tensor_product",
             "search.sampled_field.axisymmetric", "family.wedge_integrals.interior",
             "family.euler_jacobi_n5.field")


def _cpu() -> float:
    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def in_fork(work):
    """Run ``work()`` in a fresh fork of this process: ``(its return value, wall seconds)`` (the value
    pickled back through a pipe; the fork ends with ``os._exit``, so nothing of it outlives the call)."""
    read, write = os.pipe()
    start = time.perf_counter()
    pid = os.fork()
    if pid == 0:
        status = 1
        try:
            os.close(read)
            data = pickle.dumps(work())
            with os.fdopen(write, "wb") as f:
                f.write(data)
            status = 0
        finally:
            os._exit(status)
    os.close(write)
    with os.fdopen(read, "rb") as f:
        data = f.read()
    os.waitpid(pid, 0)
    return pickle.loads(data), time.perf_counter() - start


def _decide(tasks, fork: bool) -> tuple[list[dict], float, float]:
    """Decide ``tasks`` in a fresh fork of this process with ``derivations.FORK = fork``:
    (records, CPU seconds of the fork and its children, wall seconds)."""
    def work():
        from chaplygin_nd.ledger.mutation import derivations, runloop

        derivations.FORK = fork
        c0 = _cpu()
        out = [r for g in runloop.groups(tasks, 1) for r in runloop.evaluate_group(g)]
        return out, _cpu() - c0

    (records, cpu), wall = in_fork(work)
    return records, cpu, wall


def compare(functions=FUNCTIONS) -> dict:
    """Plan every mutant of ``functions`` once, then decide them the old way and the new way
    (:func:`_decide`), one after the other: the figures and the verdicts of both."""
    from chaplygin_nd.ledger.mutation import derivations
    from chaplygin_nd.ledger.mutation import runtime as mr
    from chaplygin_nd.ledger.mutation.checks import init_worker

    init_worker()
    selection = derivations.sample("derivations", None, only=frozenset(functions))
    with tempfile.TemporaryDirectory(prefix="chaplygin-mutate-") as work:
        os.environ[mr.WORK_ENV] = work
        try:
            tasks = derivations.plan("derivations", selection, 1)
            result: dict = {"functions": list(functions), "mutants": len(tasks)}
            for name, fork in (("rows run whole in the worker", False),
                               ("rows run from the first call (forkpoint)", True)):
                load = os.getloadavg()[0]
                records, cpu, wall = _decide(tasks, fork)
                result[name] = {"cpu seconds": round(cpu, 1), "wall seconds": round(wall, 1),
                                "cpu per mutant": round(cpu / max(1, len(records)), 2),
                                "load at start": round(load, 2),
                                "verdicts": {f"{r['function']} {r['mutation']}": r["outcome"]
                                             for r in records}}
        finally:
            os.environ.pop(mr.WORK_ENV, None)
    old, new = (result[k]["verdicts"] for k in list(result)[2:4])
    result["verdicts differ"] = sorted(k for k in old if old[k] != new.get(k))
    return result


def main(out: Path, quick: bool = False) -> int:
    result = compare(FUNCTIONS[:1] if quick else FUNCTIONS)
    names = list(result)[2:4]
    lines = ["# Mutation of the derivations: CPU per mutant, old path against forkpoint", "",
             f"{result['mutants']} mutants of {len(result['functions'])} functions "
             f"({', '.join(result['functions'])}), planned once, then each path in a fresh fork.",
             "", "| path | mutants | CPU s | CPU s per mutant | wall s | load at start |",
             "|---|---|---|---|---|---|"]
    for name in names:
        r = result[name]
        lines.append(f"| {name} | {len(r['verdicts'])} | {r['cpu seconds']} | {r['cpu per mutant']}"
                     f" | {r['wall seconds']} | {r['load at start']} |")
    lines += ["", f"verdicts that differ: {len(result['verdicts differ'])}"
              + "".join(f"\n- {k}" for k in result["verdicts differ"])]
    out.mkdir(parents=True, exist_ok=True)
    (out / "mutation.md").write_text("\n".join(lines) + "\n", encoding="utf-8")
    (out / "mutation.json").write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    print("\n".join(lines))
    return 0 if not result["verdicts differ"] else 1
