r"""Running a ledger row with a mutant in place: its signature, its time budget, and the stop at
the first part that differs (:func:`run_row`); the unmutated baseline (:func:`baseline`)."""

from __future__ import annotations

import contextlib
import signal

#: A row's time budget under a mutant: this many times its unmutated time, at least MIN_BUDGET s.
BUDGET_FACTOR, MIN_BUDGET = 5.0, 15.0


def signature(verdict, error: str = "") -> tuple:
    """What a mutant must change: the verdict, the counterexample, and each part's."""
    if error:
        return ("error",)
    return (verdict.verdict, verdict.counterexample,
            tuple((p.name, p.verdict, p.counterexample) for p in verdict.parts))


class BudgetExceeded(BaseException):
    """A check under a mutant ran past its budget. Not an ``Exception``: a row's own ``except
    Exception``, or a replay's (a raise is a value there), must not take it for a result."""


def _alarm(signum, frame):
    raise BudgetExceeded()


@contextlib.contextmanager
def time_budget(seconds: float):
    """Within the block, :class:`BudgetExceeded` is raised once ``seconds`` have passed (SIGALRM;
    main thread only). The one time limit of the mutation tools: rows and replays."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


class _PartChanged(BaseException):  # not an Exception: a row's own ``except Exception`` must
    # not turn the stop into a part of its own
    def __init__(self, note: str):
        super().__init__(note)
        self.note = note


class PartContractError(RuntimeError):
    """A row announced a part with ``registry.decided`` that its verdict does not contain."""


def _part_watch(base: tuple):
    """The callback of :func:`registry.observing_parts` for a run compared with ``base`` (a
    signature): raises :class:`_PartChanged` at the first final part that is not the base's
    part of the same name (its k-th occurrence for the k-th announced)."""
    expected: dict[str, list[tuple]] = {}
    for p in base[2] if len(base) == 3 else ():
        expected.setdefault(p[0], []).append(p)
    count: dict[str, int] = {}

    def watch(part) -> None:
        k = count[part.name] = count.get(part.name, 0) + 1
        got = (part.name, part.verdict, part.counterexample)
        want = expected.get(part.name, [])
        if k > len(want):
            raise _PartChanged(f"part '{part.name}' is new (stopped there)")
        if want[k - 1] != got:
            what = f"{want[k - 1][1]} -> {got[1]}" + (
                " (counterexample changed)" if want[k - 1][1] == got[1] else "")
            raise _PartChanged(f"part '{part.name}': {what} (stopped at that part)")

    return watch


def run_row(claim_id: str, budget: float | None = None, base: tuple | None = None,
            ) -> tuple[tuple, str]:
    """Run one ledger row in this process: (signature, note). ``budget``: seconds, else raises.
    ``base`` (the unmutated row's signature): stop at the first part the row announces final
    (``registry.decided``) that differs from the base's; the signature is then ``("part
    changed", name)`` — it differs from the base, as the whole row's would."""
    from chaplygin_nd.ledger.registry import observing_parts, registry

    spec = registry()[claim_id]
    watch = observing_parts(_part_watch(base) if base is not None else (lambda part: None))
    try:
        with watch, (time_budget(budget) if budget else contextlib.nullcontext()):
            verdict = spec.run()
        missing = [p.name for p in watch.seen if p not in verdict.parts]
        if missing:
            raise PartContractError(f"{claim_id}: parts announced final are not in its verdict: "
                                    f"{', '.join(missing)}")
        return signature(verdict), ""
    except _PartChanged as stop:
        return ("part changed", stop.note), stop.note
    except BudgetExceeded:
        return ("timeout",), f"ran past its budget of {budget:.0f} s"
    except PartContractError:
        raise
    except Exception as err:  # noqa: BLE001 - a raising proof is an observed change
        return ("error",), f"raised {type(err).__name__}: {str(err)[:120]}"


def difference(base: tuple, got: tuple) -> str:
    """What changed between two signatures, in a few words (the reason of a kill)."""
    if got[0] in ("error", "timeout"):
        return f"row {got[0]}"  # (run_row's note, "raised ...", is preferred when present)
    if base[0] != got[0]:
        return f"verdict {base[0]} -> {got[0]}"
    if base[1] != got[1]:
        return "counterexample changed" if base[1] else "a counterexample appeared"
    for p, q in zip(base[2], got[2]):
        if p != q:
            return f"part '{p[0]}': {p[1]} -> {q[1]}" + (
                " (counterexample changed)" if p[1] == q[1] else "")
    return "parts changed"


def init_worker():
    """A worker process of a mutation run: the claim scripts discovered once, before any mutant."""
    from chaplygin_nd.ledger.catalog import discover

    discover()


def baseline(ids=None, jobs: int = 2, phase=None):
    """Run rows unmutated (all, or ``ids``): {row: (signature, seconds, printed functions)};
    ``phase`` (:class:`ledger.phase.Phase`) counts the rows as they are decided."""
    from chaplygin_nd.ledger.runner import run, select

    rows = select(ids or ())
    if phase is not None:
        phase.total = len(rows)
    results = run(rows, jobs=jobs, on_result=(lambda r: phase.add()) if phase is not None
                  else (lambda r: None), on_wake=phase.tick if phase is not None else None)
    bad = [r.row.id for r in results if r.error]
    if bad:
        raise RuntimeError(f"rows raise without any mutant: {', '.join(bad)}")
    return {r.row.id: (signature(r.verdict), r.seconds, list(r.printed))
            for r in results if r.module}

