r"""``chaplygin first-integrals``: the exact first-integral search from the command line
(row S6:first-integrals; symbolic/search/box_search.py and its strategies).

    chaplygin first-integrals 5 4 --a -1/3 --b 3/2          # axisymmetric n = 5, M-degree 1..4
    chaplygin first-integrals 3 3 --J 1,3/2,7/3 --b 1/2     # a generic mass tensor
    chaplygin first-integrals 5 8 --from 6 --d-gamma 8 --k 2 --json out.json
    chaplygin first-integrals 5 4 --a -1/3 --b 3/2 --space weight-zero

``--space``: ``invariant`` (default where the invariant generators are derived: n = 4..7
axisymmetric, any generic mass tensor; symbolic/search/invariant_search.py) searches the
$SO(n-1)$-invariant integrals, those of the reduced system; ``weight-zero``
(symbolic/search/integral_search.py) the larger class of integrals of weight zero for a maximal
torus, in a much larger space. The first lines name the class and the parameters.

Before the first block: one line per box with its unknowns and the estimated time and memory
(symbolic/search/cost.py). A box whose estimated memory exceeds what the machine has available
(or whose estimated time exceeds ``--max-hours``) is refused before anything runs: one line
``error: ...`` naming the figure and the option that overrides it, exit status 2. Then one line
per degree: unknowns, the F_p nullity (``found``, an upper bound of the dimension of the
integrals), the F_p rank of the known algebra (``known``, a lower bound), ``settled`` when they
agree (then exactly: nothing beyond the known integrals), seconds, and the estimated time left.
Progress per block on stderr. ``--primes N`` runs every box at N primes and combines the bounds;
the (box, prime) tasks then run in ``--workers`` processes or on a Dask cluster (``--scheduler
ADDRESS`` or ``local``), with the same table. Bad input: one line ``error: ...`` and exit status
2; nothing is written.
"""

from __future__ import annotations

import json
from fractions import Fraction

__all__ = ["main", "parse_model"]


def parse_rational(text: str, name: str):
    """The command-line value ``text`` of the parameter ``name`` (a, b, J_i, ...) as an exact SymPy
    rational ("-1/3", "0.4" = 2/5); ``ValueError`` naming the parameter otherwise."""
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
        raise ValueError("b is required: give --b (b = m r^2 > 0, eq:M-O)")
    b = parse_rational(str(b), "b")
    if b <= 0:
        raise ValueError(f"b = {b} is outside the domain b > 0 (eq:M-O)")
    if J is not None:
        if a is not None:
            raise ValueError("give either a (axisymmetric) or J (a diagonal mass tensor), not both")
        Js = [parse_rational(str(j), "J") for j in (J.split(",") if isinstance(J, str) else J)]
        if len(Js) != n or any(j <= 0 for j in Js):
            raise ValueError(f"J must be {n} positive rationals (the diagonal mass tensor, eq:Inertia)")
        return sampled_field.general(Js, b)
    if a is None:
        raise ValueError("give --a (axisymmetric, eq:axisymm) or --J (a diagonal mass tensor)")
    a = parse_rational(str(a), "a")
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
    parser.add_argument("--space", choices=("invariant", "weight-zero"), default=None,
                        help="the unknowns: SO(n-1)-invariant polynomials (default where derived) "
                             "or weight-zero monomials of a maximal torus")
    parser.add_argument("--max-memory", type=float, default=None,
                        help="refuse a box estimated above this many GB (default: the memory "
                             "available now)")
    parser.add_argument("--max-hours", type=float, default=24.0,
                        help="refuse a box estimated above this many hours (default 24)")
    parser.add_argument("--primes", type=positive_int, default=1,
                        help="run every box at this many primes and combine the bounds "
                             "(symbolic/search/multimodular.py; default 1)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="map the (box, prime) tasks over a Dask scheduler at ADDRESS, or "
                             "'local' for a local cluster of --workers processes")
    parser.add_argument("--workers", type=positive_int, default=None,
                        help="worker processes for --primes / --scheduler local (default 1 / cores)")
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

    from chaplygin_nd.symbolic.search import cost, strategies
    from chaplygin_nd.symbolic.search import integral_search as fi

    try:
        search = strategies.make_search(model, args.space, include_new=not args.paper_only)
        boxes = [fi.box_for(d, args.k, args.d_gamma) for d in range(args.start, args.degree + 1)]
        limit = (args.max_memory * 2**30 if args.max_memory is not None else cost.available_bytes())
        params = (f"a = {model.a}, b = {model.b}" if model.kind == "axisymmetric"
                  else f"J = ({', '.join(str(j) for j in model.J)}), b = {model.b}")
        print(f"n = {model.n} ({model.kind}, {params}); unknowns: {search.invariance}", flush=True)
        # box by box, refusing at the first box past a limit: the boxes grow with the degree, and
        # estimating the ones after it (an exact weight count each) could itself take minutes
        estimates = []
        for box in boxes:
            est = cost.estimate(search, box)
            estimates.append(est)
            print("  " + est.line(), flush=True)
            name = f"box (M-degree {box[0]}, gamma-degree <= {box[1]}, D^{box[2]})"
            past = est.seconds > args.max_hours * 3600 or est.bytes > limit
            if past and box is not boxes[-1]:
                print(f"  boxes M-degree {box[0] + 1}..{boxes[-1][0]}: larger still, not estimated",
                      flush=True)
            if est.seconds > args.max_hours * 3600:
                why = (f" (the weight-zero split passes over 2^{model.n} characters)"
                       if est.split_seconds > est.seconds / 2 else "")
                raise ValueError(f"{name} needs an estimated {cost.duration(est.seconds)}{why}, "
                                 f"above --max-hours {args.max_hours:g}; nothing was run "
                                 f"(raise --max-hours to run it anyway, or ask for a lower degree or a smaller n)")
            if est.bytes > limit:
                raise ValueError(f"{name} needs an estimated {est.bytes / 2**30:.3g} GB, above the "
                                 f"{limit / 2**30:.1f} GB {'allowed' if args.max_memory else 'available'}"
                                 f"; nothing was run (--max-memory GB overrides, --space invariant "
                                 f"or a lower degree is smaller)")
    except ValueError as err:
        return fail(str(err))
    if args.primes > 1 or args.scheduler is not None:
        return _mapped(model, args, boxes, search)
    rows = []
    spent, planned = 0.0, 0.0
    for i, (box, est) in enumerate(zip(boxes, estimates)):
        t0 = time.perf_counter()
        r = search.run_box(box, progress=lambda s: print(s, file=sys.stderr, flush=True))
        rows.append({**r.as_dict(), "space": args.space or strategies.default_space(model),
                     "invariance": search.invariance})
        took = time.perf_counter() - t0
        spent, planned = spent + took, planned + est.seconds
        left = sum(e.seconds for e in estimates[i + 1:]) * (spent / planned if planned else 1.0)
        print(f"n={model.n} d={box[0]} d_gamma={box[1]} k={box[2]}: {r.unknowns} unknowns, found "
              f"{r.found}, known {r.known}, {'settled' if r.settled else 'NOT settled (candidates)'}, "
              f"{took:.1f} s" + (f"; about {left:.0f} s left" if i + 1 < len(boxes) else ""),
              flush=True)
    return write_json(args.json, rows)


def _mapped(model, args, boxes, search) -> int:
    """The boxes at ``--primes`` primes, mapped over processes or Dask (multimodular)."""
    import os
    import time

    from chaplygin_nd.symbolic.search import multimodular, strategies

    from chaplygin_nd.console import fail

    count = args.workers or (os.cpu_count() or 1 if args.scheduler == "local" else 1)
    where = (f"a local Dask cluster of {count} processes" if args.scheduler == "local" else
             f"Dask scheduler {args.scheduler}" if args.scheduler else
             f"{count} process{'es' if count > 1 else ''}")
    print(f"{len(boxes) * args.primes} tasks ({len(boxes)} boxes x {args.primes} primes) on {where}",
          flush=True)
    t0 = time.perf_counter()
    try:
        rows = multimodular.run(model, args.space, boxes, args.primes, not args.paper_only,
                                args.scheduler, args.workers)
    except ValueError as err:
        return fail(str(err))
    for r in rows:
        r.update(space=args.space or strategies.default_space(model), invariance=search.invariance)
        print(f"n={r['n']} d={r['d']} d_gamma={r['d_gamma']} k={r['k']}: {r['unknowns']} unknowns, "
              f"found {r['found']}, known {r['known']} (primes {len(r['primes'])}), "
              f"{'settled' if r['settled'] else 'NOT settled (candidates)'}", flush=True)
    print(f"{time.perf_counter() - t0:.1f} s", flush=True)
    return write_json(args.json, rows)


def write_json(path, rows) -> int:
    """Write a search's table to ``--json`` ``path`` atomically (if one was given): 0, or one line
    and exit 1 on a full disk, a quota or a read-only folder (the table is printed above; nothing
    half-written). Every search command writes its table with it."""
    if path:
        from chaplygin_nd.console import fail
        from chaplygin_nd.writing import write_atomic

        try:
            write_atomic(path.absolute(), json.dumps(rows, indent=1, default=str))
        except OSError as exc:
            return fail(f"--json {path}: cannot write it ({exc.strerror or exc}); nothing "
                        "written, the degree table is printed above")
    return 0
