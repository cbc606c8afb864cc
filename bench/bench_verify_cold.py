"""Where a cold ``chaplygin verify`` spends its time: the whole run, and each heavy row by stage.

``chaplygin bench verify-cold`` (``--quick``: the rows only, no whole run) writes
``verify-cold.md`` and ``verify-cold.json`` into the output folder:

* **per row** — each evidence row (and the heaviest exact rows, :data:`ROWS`) decided alone in a
  new process by :mod:`bench.row_profile`, twice: *cold* (an empty project cache and an empty heyoka
  LLVM disk cache, both inside a new temporary folder: ``$CHAPLYGIN_ND_CACHE`` and
  ``$XDG_CACHE_HOME``, which heyoka's own disk cache follows) and *warm* (the same folders again,
  now filled). Its wall time is split into LLVM compilation (with the expression graph), loading
  compiled integrators, integration (heyoka's ``propagate_grid``), MEGNO, the integrals' drift,
  NAFF and the classification, the result cache, the draws, the exact part and the rest (Python
  overhead). A row alone pays for the ensembles it shares with others (the n = 4 control, the
  P ensemble of S5:reconstruction): the per-row sums exceed the whole run's proof time;
* **whole run** — ``chaplygin verify --check-generated`` cold and then warm (:func:`measure`: the
  wall time, the CPU of every process it started, the load before and after, the proof time the
  run reports).

``python -m chaplygin_nd.bench.bench_verify_cold [ARGS...]`` keeps the one-line measurement of a
cold ``chaplygin verify ARGS`` (default ``--check-generated``).

``time`` (and ``/usr/bin/time``) miss most of that CPU: the ledger's workers are children of the
multiprocessing fork server, which is orphaned when the run ends and never waited for by it. Here
the measuring process is a child subreaper (Linux ``PR_SET_CHILD_SUBREAPER``): the orphaned server
is re-parented to it and reaped, so ``RUSAGE_CHILDREN`` holds the CPU of the whole tree. On a shared
machine compare CPU rather than wall, and only runs made side by side.
"""

from __future__ import annotations

import ctypes
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from chaplygin_nd import processes

#: ``<linux/prctl.h>``: become the reaper of orphaned descendants.
PR_SET_CHILD_SUBREAPER = 36


def measure(command: list[str], env: dict[str, str] | None = None, stdout=None) -> dict:
    """Run ``command`` to its end (with every descendant reaped); ``{"rc", "wall", "user",
    "sys", "load_before", "load_after"}`` (seconds; the load is the 1-minute average). Linux only
    for the descendants' CPU (elsewhere only the direct child's tree that was waited for counts)."""
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
    load_before = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)  # earlier runs of this process
    start = time.perf_counter()
    rc = subprocess.run(command, env=env, check=False, stdout=stdout,
                        **processes.popen_kwargs()).returncode
    while True:  # the fork server and anything else handed to this process
        try:
            os.wait()
        except ChildProcessError:
            break
    wall = time.perf_counter() - start
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return {"rc": rc, "wall": wall, "user": usage.ru_utime - before.ru_utime,
            "sys": usage.ru_stime - before.ru_stime,
            "load_before": load_before, "load_after": os.getloadavg()[0]}


#: the rows profiled one by one: every drawn evidence row, then the heaviest exact rows
ROWS = ("S5:EJ-tori", "S5:reconstruction", "Th:Re-tori:frequencies", "S6:open-reduced-n5",
        "S6:open-reduced-n6", "P:Measure", "S6:reduced-n5")
#: the stages of :mod:`bench.row_profile`, in the table's order
STAGES = ("compile", "load", "integrate", "megno", "integrals", "naff", "cache", "draws", "exact",
          "other")


def cold_env(folder: str) -> dict[str, str]:
    """The environment of a run whose every cache is inside ``folder``: the project's
    (``$CHAPLYGIN_ND_CACHE``) and heyoka's LLVM disk cache (under ``$XDG_CACHE_HOME``)."""
    return dict(os.environ, CHAPLYGIN_ND_CACHE=os.path.join(folder, "cache"),
                XDG_CACHE_HOME=os.path.join(folder, "xdg"))


def profile(claim_id: str, env: dict[str, str]) -> dict:
    """One row decided alone in a new process under the profiler (:mod:`bench.row_profile`): its
    stages, verdict, the process's wall and CPU time (on a shared machine compare CPU) and the
    load before it."""
    with tempfile.TemporaryDirectory(prefix="row-profile-") as tmp:
        out = os.path.join(tmp, "row.json")
        m = measure([sys.executable, "-m", "chaplygin_nd.bench.row_profile", claim_id, out], env)
        if m["rc"] != 0 or not os.path.exists(out):
            return {"id": claim_id, "failed": f"exit {m['rc']}", "process": m["wall"],
                    "loadavg": m["load_before"]}
        with open(out, encoding="utf-8") as fh:
            record = json.load(fh)
    record.update(process=m["wall"], cpu=m["user"] + m["sys"], loadavg=m["load_before"])
    return record


def rows(ids=ROWS) -> list[dict]:
    """Every row of ``ids`` cold and then warm, each in its own fresh cache folder."""
    out = []
    for claim_id in ids:
        with tempfile.TemporaryDirectory(prefix="verify-cold-row-") as tmp:
            env = cold_env(tmp)
            cold = profile(claim_id, env)
            warm = profile(claim_id, env)
        print(f"{claim_id:24s} cold {_line(cold)}\n{'':24s} warm {_line(warm)}", flush=True)
        out.append({"id": claim_id, "cold": cold, "warm": warm})
    return out


def _line(r: dict) -> str:
    if "failed" in r:
        return f"FAILED {r['failed']}"
    return (f"{r['wall']:6.1f} s ({r['status']}): "
            + ", ".join(f"{k} {r[k]:.1f}" for k in STAGES if r.get(k, 0.0) >= 0.05)
            + f"; CPU {r['cpu']:.1f} s; load average {r['loadavg']:.1f}")


_TOTALS = re.compile(r"\(([0-9.]+) s of proof time\); wall ([0-9.]+) s")


def whole(env: dict[str, str]) -> dict:
    """``chaplygin verify --check-generated`` in ``env``: :func:`measure` and the proof time and
    wall the run printed, and each row's verdict and seconds (from verification.json, written
    into a temporary report folder)."""
    with tempfile.TemporaryDirectory(prefix="verify-report-") as rep:
        cmd = [sys.executable, "-m", "chaplygin_nd", "verify", "--check-generated", "--report-dir", rep]
        log = os.path.join(rep, "stdout.txt")
        with open(log, "w", encoding="utf-8") as fh:
            m = measure(cmd, env, stdout=fh)
        text = Path(log).read_text(encoding="utf-8")
        found = _TOTALS.search(text)
        m["proof_time"] = float(found.group(1)) if found else float("nan")
        try:
            data = json.loads(Path(rep, "verification.json").read_text(encoding="utf-8"))
            m["verdicts"] = {r["id"]: r["verdict"] for r in data["rows"]}
            m["seconds"] = {r["id"]: r["seconds"] for r in data["rows"]}
        except (OSError, KeyError, ValueError, TypeError):
            m["verdicts"], m["seconds"] = {}, {}
    return m


def markdown(result: dict) -> str:
    """The per-row table (cold and warm) and the whole runs."""
    lines = ["# Where a cold `chaplygin verify` spends its time", "",
             f"{result['machine']}", "",
             "Per row, decided alone in a new process (seconds of wall time; a row alone pays for "
             "the ensembles it shares; `import` is before the row and not in its wall):", "",
             "| row | run | wall | " + " | ".join(STAGES) + " | import | CPU | verdict | load average |",
             "|---|---|---:|" + "---:|" * len(STAGES) + "---:|---:|---|---:|"]
    for r in result["rows"]:
        for run in ("cold", "warm"):
            x = r[run]
            if "failed" in x:
                lines.append(f"| {r['id']} | {run} | FAILED {x['failed']} |")
                continue
            lines.append(f"| {r['id']} | {run} | {x['wall']:.1f} | "
                         + " | ".join(f"{x.get(k, 0.0):.1f}" for k in STAGES)
                         + f" | {x['imported']:.1f} | {x['cpu']:.1f} | {x['status']} | {x['loadavg']:.1f} |")
    for run in ("cold", "warm"):
        w = result.get("whole", {}).get(run)
        if w:
            lines += ["", f"Whole `chaplygin verify --check-generated`, {run}: rc {w['rc']}, wall "
                      f"{w['wall']:.1f} s, proof time {w['proof_time']:.1f} s, CPU "
                      f"{w['user'] + w['sys']:.1f} s, load {w['load_before']:.2f} -> {w['load_after']:.2f}"]
    return "\n".join(lines) + "\n"


def main(out: Path, quick: bool = False) -> int:
    """``chaplygin bench verify-cold``: the per-row breakdown cold and warm and (unless ``quick``)
    the whole run cold and warm, into ``out/verify-cold.md`` and ``.json``."""
    result: dict = {"machine": f"{os.cpu_count()} cores, load {os.getloadavg()[0]:.2f} at the start",
                    "rows": rows()}
    status = 0
    if not quick:
        with tempfile.TemporaryDirectory(prefix="verify-cold-") as tmp:
            env = cold_env(tmp)
            result["whole"] = {"cold": whole(env), "warm": whole(env)}
        for run, w in result["whole"].items():
            print(f"verify {run}: rc {w['rc']}, wall {w['wall']:.1f} s, proof time "
                  f"{w['proof_time']:.1f} s, load {w['load_before']:.2f} -> {w['load_after']:.2f}",
                  flush=True)
            status |= int(w["rc"] != 0)
    status |= int(any("failed" in r[k] for r in result["rows"] for k in ("cold", "warm")))
    from chaplygin_nd.bench.report import write_atomic

    write_atomic(out / "verify-cold.json", json.dumps(result, indent=1, sort_keys=True))
    write_atomic(out / "verify-cold.md", markdown(result))
    return status


def cli(argv: list[str] | None = None) -> int:
    """Measure a cold ``chaplygin verify`` (arguments passed on) and print one line."""
    args = list(sys.argv[1:] if argv is None else argv) or ["--check-generated"]
    with tempfile.TemporaryDirectory(prefix="verify-cold-") as tmp:
        m = measure([sys.executable, "-m", "chaplygin_nd", "verify", *args], cold_env(tmp))
    print(f"verify cold: rc {m['rc']}, wall {m['wall']:.1f} s, CPU {m['user'] + m['sys']:.1f} s "
          f"(user {m['user']:.1f}, sys {m['sys']:.1f}), load {m['load_before']:.2f} -> "
          f"{m['load_after']:.2f} on {os.cpu_count()} cores")
    return m["rc"]


if __name__ == "__main__":
    raise SystemExit(cli())
