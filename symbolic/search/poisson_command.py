r"""``chaplygin poisson``: the exact Hamiltonisation search from the command line (rows
S7:poisson-controls, S7:poisson-n4, S7:poisson-n5; symbolic/search/poisson.py).

    chaplygin poisson 3 2 --a 1/3 --b 2/5            # n = 3, degrees 0..2, e in -1..3
    chaplygin poisson 4 6 --from 4 --e 1,2 --a 1/3 --b 2/5 --json out.json
    chaplygin poisson 4 2 --e 1 --jacobi-generic     # a Jacobi box carried to generic (a, b)

Before each box: one line with its size and a CPU-time estimate by stage (stderr;
symbolic/search/poisson_cost.py); boxes estimated above ``--max-hours`` (one degree, or all together) are refused before any runs. Then one line per box:
the linear stage (inconsistent, or the dimension of the sampled affine space), the Gröbner basis
of the Jacobi stage, the outcome (``excluded (linear)``, ``excluded (Jacobi)`` — both exact —
or ``solutions``) and over which (a, b) an exclusion holds (``for generic (a, b)`` or ``at this
(a, b) only``; the argument is in the JSON's ``generic``, a Jacobi box's certificate over
$\mathbb{Q}(a, b)$ in its ``certificate`` with ``--jacobi-generic``), seconds. Bad input: one line ``error: ...`` and exit status 2.
"""

from __future__ import annotations

__all__ = ["main"]


def _over(generic: str) -> str:
    """Over which (a, b) an exclusion holds, in a few words (the full argument is in --json)."""
    if not generic:
        return ""
    return " for generic (a, b)" if generic.startswith("generic") else " at this (a, b) only"


def _plan(n: int, start: int, degree: int, exponents: int, max_hours: float) -> tuple[str, float]:
    """``(refusal, cpu)``: the estimated CPU seconds of the boxes d = ``start``..``degree`` for
    ``exponents`` values of e, Jacobi stage included (symbolic/search/poisson_cost.py), and why
    they are refused before any runs ('' if not): one degree, or all of them together, above
    ``max_hours`` (each box alone may be small while the request is not)."""
    from chaplygin_nd.symbolic.search.cost import duration
    from chaplygin_nd.symbolic.search.poisson_cost import poisson_cost

    override = "nothing was run (raise --max-hours to run it anyway, or ask for a lower degree or a smaller n)"
    total = 0.0
    for d in range(start, degree + 1):
        cpu = exponents * poisson_cost(n, d).cpu()
        total += cpu
        if cpu > max_hours * 3600:
            return (f"box n={n} d={d} needs an estimated {duration(cpu)} of CPU for {exponents} "
                    f"exponent(s) e, above --max-hours {max_hours:g}; {override}"), total
    if total > max_hours * 3600:
        return (f"boxes n={n} d={start}..{degree} need an estimated {duration(total)} of CPU in all "
                f"for {exponents} exponent(s) e, above --max-hours {max_hours:g}; {override}"), total
    return "", total


def main(argv: list[str]) -> int:
    """Run the search; exit status 0, or 2 on bad input (one line)."""
    from chaplygin_nd.symbolic.search.command import parse_rational, write_json

    from chaplygin_nd.console import OneLineParser, fail, path_argument, positive_int

    parser = OneLineParser(prog="chaplygin poisson",
                           description="Exact search for a Hamiltonisation Pi = Delta^sigma P, "
                                       "rho = Delta^(sigma+e), box by box (rows S7:poisson-*).")
    parser.add_argument("n", type=positive_int, help="the dimension n >= 3")
    parser.add_argument("degree", type=int, help="the highest degree d in x = gamma_n searched")
    parser.add_argument("--from", dest="start", type=int, default=0, help="the lowest degree (default 0)")
    parser.add_argument("--e", default="-1,0,1,2,3", help="the exponents e, comma-separated")
    parser.add_argument("--a", default="1/3", help="J = Id + a E_n E_n^T, a >= -1 (default 1/3)")
    parser.add_argument("--b", default="2/5", help="b >= 0 (default 2/5; b = 0 is the free body)")
    parser.add_argument("--seed", type=int, default=None, help="the seed of the sampled points")
    parser.add_argument("--json", type=path_argument, help="write the table to this file")
    parser.add_argument("--jacobi-generic", action="store_true",
                        help="carry each box excluded by Jacobi to generic (a, b) by a certificate "
                             "over Q(a, b) (symbolic/search/jacobi_generic.py; not in the estimate: "
                             "27-89 CPU s per box at n = 4, d <= 3; boxes above "
                             "jacobi_generic.MAX_FREE unknowns are not attempted)")
    parser.add_argument("--max-hours", type=float, default=24.0,
                        help="refuse when a degree's estimated CPU time over all e (with the "
                             "Jacobi stage) is above this many hours (default 24)")
    args = parser.parse_args(argv)
    try:
        if args.n < 3:
            raise ValueError(f"n = {args.n}: the sphere needs n >= 3")
        if args.degree < 0 or args.start < 0 or args.start > args.degree:
            raise ValueError(f"degrees {args.start}..{args.degree}: need 0 <= --from <= degree")
        a, b = parse_rational(args.a, "a"), parse_rational(args.b, "b")
        if a < -1 or b < 0:
            raise ValueError(f"(a, b) = ({a}, {b}) is outside a >= -1, b >= 0")
        try:
            es = [int(v) for v in args.e.split(",")]
        except ValueError:
            raise ValueError(f"--e {args.e!r}: comma-separated integers, e.g. 0,1,2") from None
        if args.json is not None and not args.json.absolute().parent.is_dir():
            raise ValueError(f"--json {args.json}: no folder {args.json.absolute().parent}")
        refusal, planned = _plan(args.n, args.start, args.degree, len(es), args.max_hours)
        if refusal:
            raise ValueError(refusal)
    except ValueError as err:
        return fail(str(err))
    import sys

    from chaplygin_nd.symbolic.exact.points import ledger_seed
    from chaplygin_nd.symbolic.search import poisson as ps

    seed = ledger_seed() if args.seed is None else args.seed
    from chaplygin_nd.symbolic.search.cost import duration

    print(f"plan: boxes n={args.n} d={args.start}..{args.degree}, {len(es)} exponent(s) e: an "
          f"estimated {duration(planned)} of CPU in all", file=sys.stderr, flush=True)
    rows = []
    for d in range(args.start, args.degree + 1):
        print(f"box: {ps.estimate(args.n, d)} per e", file=sys.stderr, flush=True)
        for e in es:
            r = ps.search_box(args.n, d, e, a, b, seed=seed, jacobi_generic=args.jacobi_generic,
                              progress=lambda s: print(s, file=sys.stderr, flush=True))
            rows.append(r.as_dict())
            gb = [str(g) for g in r.groebner][:6]
            print(f"n={args.n} d={d} e={e} a={a} b={b}: {r.independent} unknowns, linear "
                  f"{r.linear}, Groebner {gb}, {r.outcome}{_over(r.generic)}, {r.seconds:.1f} s "
                  f"({sum(r.stages.values()):.1f} s CPU)", flush=True)
    return write_json(args.json, rows)
