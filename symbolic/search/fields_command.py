r"""``chaplygin symmetry-fields``: the exact search for commuting symmetry fields from the command
line (row S7:symmetry-fields; symbolic/search/symmetry_fields.py).

    chaplygin symmetry-fields 6 0 --pairs 1:2,-1/2:2       # n = 6, degree 0, (s, tau) pairs
    chaplygin symmetry-fields 4 2 --a 1/3 --b 2/5 --json out.json

Before each box: its size and a CPU-time estimate by stage (stderr; symbolic/search/fields_cost.py);
a box estimated above ``--max-hours`` is refused before anything runs. Then one line per box: sampled solutions,
the exact trivial ones (orbit fields, Delta X, orbit-direction fields proved), the excess (an upper
bound of the fields beyond them; 0 is an exact exclusion) and over which (a, b) it holds,
seconds. Bad input: one line ``error: ...`` and exit status 2.
"""

from __future__ import annotations

__all__ = ["main"]


def _over(generic: str) -> str:
    """Over which (a, b) the count holds, in a few words (the full argument is in --json)."""
    if not generic:
        return ""
    return " (for generic (a, b))" if generic.startswith("generic") else " (at this (a, b) only)"


def _refusal(n: int, degree: int, max_hours: float) -> str:
    """Why the box (n, degree) is refused before it runs ('' if it is not): its estimated CPU time
    with one orbit-direction candidate (symbolic/search/fields_cost.py) above ``max_hours``."""
    from chaplygin_nd.symbolic.search.cost import duration
    from chaplygin_nd.symbolic.search.fields_cost import field_cost

    est = field_cost(n, degree)
    if est.cpu() <= max_hours * 3600:
        return ""
    return (f"box n={n} d={degree} needs an estimated {duration(est.cpu())} of CPU "
            f"({duration(est.candidate)} per orbit-direction candidate), above --max-hours "
            f"{max_hours:g}; nothing was run (raise --max-hours to run it anyway, or ask for a "
            f"lower degree or a smaller n)")


def main(argv: list[str]) -> int:
    """Run the search; exit status 0, or 2 on bad input (one line)."""
    from chaplygin_nd.symbolic.search.command import parse_rational, write_json

    from chaplygin_nd.console import OneLineParser, fail, path_argument, positive_int

    parser = OneLineParser(prog="chaplygin symmetry-fields",
                           description="Exact search for fields Y = Delta^s Q commuting with "
                                       "Delta^tau X modulo so(n-1) (row S7:symmetry-fields).")
    parser.add_argument("n", type=positive_int, help="the dimension n >= 3")
    parser.add_argument("degree", type=int, help="the highest degree d in x = gamma_n")
    parser.add_argument("--pairs", default=None,
                        help="(s, tau) pairs as s:tau, comma-separated (default: (n-4)/2:(n-2)/2 "
                             "and -1/2:(n-2)/2, tau from the measure Delta^(-(n-2)/2))")
    parser.add_argument("--a", default="1/3", help="J = Id + a E_n E_n^T, a >= -1 (default 1/3)")
    parser.add_argument("--b", default="2/5", help="b > 0 (default 2/5)")
    parser.add_argument("--seed", type=int, default=None, help="the seed of the sampled points")
    parser.add_argument("--json", type=path_argument, help="write the table to this file")
    parser.add_argument("--max-hours", type=float, default=24.0,
                        help="refuse a box whose estimated CPU time (with one orbit-direction "
                             "candidate) is above this many hours (default 24)")
    args = parser.parse_args(argv)
    try:
        if args.n < 3:
            raise ValueError(f"n = {args.n}: the sphere needs n >= 3")
        if args.degree < 0:
            raise ValueError(f"degree {args.degree}: need >= 0")
        a, b = parse_rational(args.a, "a"), parse_rational(args.b, "b")
        if a < -1 or b <= 0:
            raise ValueError(f"(a, b) = ({a}, {b}) is outside a >= -1, b > 0")
        if args.pairs is None:
            import sympy as sp
            tau = sp.Rational(args.n - 2, 2)
            pairs = list(dict.fromkeys([(tau - 1, tau), (sp.Rational(-1, 2), tau)]))
        else:
            try:
                pairs = [tuple(parse_rational(v, "s:tau") for v in p.split(":")) for p in args.pairs.split(",")]
            except ValueError:
                raise ValueError(f"--pairs {args.pairs!r}: give s:tau pairs, e.g. 1:2,-1/2:2") from None
            if any(len(p) != 2 for p in pairs):
                raise ValueError(f"--pairs {args.pairs!r}: give s:tau pairs, e.g. 1:2,-1/2:2")
        if args.json is not None and not args.json.absolute().parent.is_dir():
            raise ValueError(f"--json {args.json}: no folder {args.json.absolute().parent}")
        refusal = _refusal(args.n, args.degree, args.max_hours)
        if refusal:
            raise ValueError(refusal)
    except ValueError as err:
        return fail(str(err))
    import sys

    from chaplygin_nd.symbolic.exact.points import ledger_seed
    from chaplygin_nd.symbolic.search import symmetry_fields as sf

    seed = ledger_seed() if args.seed is None else args.seed
    rows = []
    for s, tau in pairs:
        print(f"box: {sf.estimate(args.n, args.degree)}", file=sys.stderr, flush=True)
        r = sf.search_fields(args.n, args.degree, s, tau, a, b, seed=seed)
        rows.append(r.as_dict())
        print(f"n={args.n} d={args.degree} s={s} tau={tau}: {r.independent} unknowns, {r.solutions} "
              f"solutions, {r.trivial} trivial ({r.orbit_proved} orbit-direction proved), excess "
              f"{r.excess}: {r.outcome}{_over(r.generic)}, {r.seconds:.1f} s ({sum(r.stages.values()):.1f} s CPU)",
              flush=True)
    return write_json(args.json, rows)
