r"""``chaplygin first-integrals``: the exact first-integral search from the command line
(row S6:first-integrals; symbolic/search/integral_search.py).

    chaplygin first-integrals 5 4 --a -1/3 --b 3/2          # axisymmetric n = 5, M-degree 1..4
    chaplygin first-integrals 3 3 --J 1,3/2,7/3 --b 1/2     # a generic mass tensor
    chaplygin first-integrals 5 6 --from 6 --d-gamma 6 --k 2 --json out.json

One line per degree: unknowns, the F_p nullity (``found``, an upper bound of the dimension of
the integrals), the F_p rank of the known algebra (``known``, a lower bound), ``settled`` when
they agree (then exactly: nothing beyond the known integrals), seconds. Progress per block on
stderr. Bad input: one line ``error: ...`` and exit status 2; nothing is written.
"""

from __future__ import annotations

import json
from fractions import Fraction

__all__ = ["main", "parse_model"]


def _rational(text: str, name: str):
    import sympy as sp

    try:
        q = Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise ValueError(f"{name} = {text!r} is not a rational number (e.g. -1/3, 0.5)") from None
    return sp.Rational(q.numerator, q.denominator)


def parse_model(n: int, a, b, J):
    """The model of the search from user input, or ValueError with one line naming the field:
    n >= 3; b > 0; either a >= -1 (axisymmetric, eq:axisymm) or J (n positive rationals)."""
    from chaplygin_nd.symbolic.search import sampled_field

    if not isinstance(n, int) or n < 3:
        raise ValueError(f"n = {n!r}: the sphere needs an integer n >= 3")
    if b is None:
        raise ValueError("b is required (b = m r^2 > 0, eq:M-O)")
    b = _rational(str(b), "b")
    if b <= 0:
        raise ValueError(f"b = {b} is outside the domain b > 0 (eq:M-O)")
    if J is not None:
        if a is not None:
            raise ValueError("give either a (axisymmetric) or J (a diagonal mass tensor), not both")
        Js = [_rational(str(j), "J") for j in (J.split(",") if isinstance(J, str) else J)]
        if len(Js) != n or any(j <= 0 for j in Js):
            raise ValueError(f"J must be {n} positive rationals (the diagonal mass tensor, eq:Inertia)")
        return sampled_field.general(Js, b)
    if a is None:
        raise ValueError("give a (axisymmetric, eq:axisymm) or J (a diagonal mass tensor)")
    a = _rational(str(a), "a")
    if a < -1:
        raise ValueError(f"a = {a} is outside the domain a >= -1 (eq:axisymm)")
    return sampled_field.axisymmetric(n, a, b)


def main(argv: list[str]) -> int:
    """Run the search; exit status 0, or 2 on bad input (one line)."""
    from chaplygin_nd.console import OneLineParser, fail, path_argument, positive_int
    from chaplygin_nd.writing import probe_problem

    parser = OneLineParser(prog="chaplygin first-integrals",
                           description="Exact search for polynomial and rational first integrals "
                                       "P/D^k, degree by degree (row S6:first-integrals).")
    parser.add_argument("n", type=positive_int, help="the dimension n >= 3")
    parser.add_argument("degree", type=positive_int, help="the highest M-degree searched")
    parser.add_argument("--a", help="axisymmetric sphere: J = Id + a E_n E_n^T, a >= -1")
    parser.add_argument("--J", help="a diagonal mass tensor instead: n comma-separated rationals")
    parser.add_argument("--b", help="b = m r^2 > 0")
    parser.add_argument("--from", dest="start", type=positive_int, default=1,
                        help="the lowest M-degree searched (default 1)")
    parser.add_argument("--d-gamma", type=int, default=None,
                        help="gamma-degree bound of P (default: d + 2k)")
    parser.add_argument("--k", type=int, default=1, help="the power of the denominator D (default 1)")
    parser.add_argument("--paper-only", action="store_true",
                        help="count only the paper's integrals as known (the new one then shows "
                             "as an excess)")
    parser.add_argument("--json", type=path_argument,
                        help="write the degree table to this file (atomically)")
    args = parser.parse_args(argv)
    try:
        model = parse_model(args.n, args.a, args.b, args.J)
        if args.k < 0 or (args.d_gamma is not None and args.d_gamma < 0):
            raise ValueError("--k and --d-gamma must be >= 0")
        if args.start > args.degree:
            raise ValueError(f"--from {args.start} is above the degree {args.degree}")
        if args.json is not None and args.json.is_dir():
            raise ValueError(f"--json {args.json}: is a folder; give a file name")
        if args.json is not None and not args.json.absolute().parent.is_dir():
            raise ValueError(f"--json {args.json}: no folder {args.json.absolute().parent}")
        if args.json is not None and (problem := probe_problem(args.json.absolute().parent)):
            raise ValueError(f"--json {args.json}: cannot write into its folder ({problem})")
    except ValueError as err:
        return fail(str(err))
    import sys
    import time

    from chaplygin_nd.symbolic.search import integral_search as fi

    rows = []
    for d in range(args.start, args.degree + 1):
        dg = d + 2 * args.k if args.d_gamma is None else args.d_gamma
        t0 = time.perf_counter()
        r = fi.search_degree(model, d, dg, args.k, include_new=not args.paper_only,
                             progress=lambda s: print(s, file=sys.stderr, flush=True))
        rows.append(r.as_dict())
        print(f"n={model.n} d={d} d_gamma={dg} k={args.k}: {r.unknowns} unknowns, found {r.found}, "
              f"known {r.known}, {'settled' if r.settled else 'NOT settled (candidates)'}, "
              f"{time.perf_counter() - t0:.1f} s", flush=True)
    if args.json:
        from chaplygin_nd.writing import write_atomic

        try:
            write_atomic(args.json.absolute(), json.dumps(rows, indent=1, default=str))
        except OSError as exc:  # full disk, quota, read-only: the table is printed above
            return fail(f"--json {args.json}: cannot write it ({exc.strerror or exc}); nothing "
                        "written, the degree table is printed above")
    return 0
