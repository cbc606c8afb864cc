r"""A search box at several primes, the primes mapped over processes or a Dask cluster.

Each prime $p$ gives an independent exact sandwich $\mathrm{rank}_p(\text{known}) \le \dim K \le
\dim V \le \mathrm{nullity}_p$ (symbolic/search/box_search.py), so over the primes run
$\max_p \mathrm{rank}_p \le \dim K \le \dim V \le \min_p \mathrm{nullity}_p$: the box is settled when
these agree (a prime that divides a minor can only loosen one side; another prime tightens it).
The tasks (box, prime) share nothing, so they run here, in worker processes, or on a Dask cluster
(``scheduler``: an address, or ``"local"`` for a local cluster; the project's ``--scheduler`` as
for frequency maps); the table is the same wherever they ran.
"""

from __future__ import annotations

import os

__all__ = ["run", "combine"]


def _task(args) -> dict:
    model, space, include_new, box, prime_index = args
    from chaplygin_nd.symbolic.search.strategies import make_search

    search = make_search(model, space, include_new=include_new)
    search.prime_index = prime_index
    r = search.run_box(tuple(box)).as_dict()
    r.pop("seconds")
    return r


def combine(per_prime: list[dict]) -> dict:
    """One box from its results at several primes (module docstring)."""
    first = per_prime[0]
    found = min(r["found"] for r in per_prime)
    known = max(r["known"] for r in per_prime)
    return {"n": first["n"], "kind": first["kind"], "d": first["d"], "d_gamma": first["d_gamma"],
            "k": first["k"], "unknowns": first["unknowns"], "primes": [r["prime"] for r in per_prime],
            "found": found, "known": known, "settled": found == known,
            "recovered": all(r["recovered"] is not False for r in per_prime)}


def run(model, space: str | None, boxes, primes: int = 2, include_new: bool = True,
        scheduler: str | None = None, workers: int | None = None) -> list[dict]:
    """Every box of ``boxes`` at the first ``primes`` primes of backend.PRIMES, combined per box;
    here (``workers`` 1), in worker processes, or on Dask (``scheduler``)."""
    from chaplygin_nd.symbolic.search import backend

    if not 1 <= primes <= len(backend.PRIMES):
        raise ValueError(f"primes must lie in 1..{len(backend.PRIMES)}")
    tasks = [(model, space, include_new, tuple(b), i) for b in boxes for i in range(primes)]
    if scheduler is not None:
        out = _on_dask(tasks, scheduler, workers)
    elif (workers or 1) == 1:
        out = [_task(t) for t in tasks]
    else:
        import multiprocessing as mp

        from chaplygin_nd import processes

        with processes.pool(min(workers or 1, len(tasks)), mp.get_context("spawn")) as pool:
            out = [f.result() for f in [pool.submit(_task, t) for t in tasks]]
    return [combine(out[i * primes:(i + 1) * primes]) for i in range(len(boxes))]


def _on_dask(tasks, scheduler: str, workers: int | None) -> list[dict]:
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise ValueError("--scheduler needs Dask: pip install 'chaplygin-nd[cluster]'") from None
    if scheduler == "local":
        import logging

        from chaplygin_nd import processes

        with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                          processes=True, host="127.0.0.1", dashboard_address=None,
                          scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
                          silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
            client.run(processes.die_with_parent, os.getpid())
            return client.gather(client.map(_task, tasks, pure=False))
    try:
        client = Client(scheduler, timeout="20s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise ValueError(f"cannot reach the Dask scheduler {scheduler!r} ({exc})") from None
    with client:
        return client.gather(client.map(_task, tasks, pure=False))
