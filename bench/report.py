"""What every benchmark writes: rows (JSON, a list of dicts), Markdown tables, target lines that say
MET or NOT MET, the machine they ran on, and figures — each file written atomically."""

from __future__ import annotations

import json
import math
import os
import platform
import time
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

from chaplygin_nd import writing


def write_atomic(path: Path, data: str | bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder and ``os.replace``: a
    reader never sees half a file, and an interrupted run leaves the old file intact."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    writing.write_atomic(path, data)  # the project's one atomic writer (mode as a plain open())


def _plain(value):
    """JSON-safe values: NumPy scalars to Python numbers, non-finite floats to None."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def write_rows(path: Path, rows: Iterable[dict]) -> None:
    """``rows`` as a JSON list (one object per row, keys in insertion order), atomically."""
    write_atomic(path, json.dumps([_plain(r) for r in rows], indent=1) + "\n")


def save_figure(fig, path: Path, dpi: int = 110) -> None:
    """Save a matplotlib figure as PNG atomically (rendered in memory first)."""
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    write_atomic(path, buf.getvalue())


def target(label: str, met: bool, detail: str) -> str:
    """One target line: ``- label: MET — detail`` or ``NOT MET``. Something not measured is NOT MET
    (the detail says why), never silently absent."""
    return f"- {label}: {'MET' if met else 'NOT MET'} — {detail}"


def best_time(fn: Callable[[], object], repeat: int = 3, budget: float = 0.3) -> float:
    """Minimum wall time of ``fn()`` over at least ``repeat`` calls, more (up to 50) while the total
    stays under ``budget`` seconds: short calls get enough samples to be stable under load."""
    times: list[float] = []
    total = 0.0
    while len(times) < repeat or (total < budget and len(times) < 50):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
        total += times[-1]
    return min(times)


def machine() -> list[str]:
    """Markdown lines: CPU, cores, load at start (the machine is shared), library versions."""
    import matplotlib
    import mpmath
    import scipy

    load = os.getloadavg() if hasattr(os, "getloadavg") else (float("nan"),)
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        import heyoka

        hy = f"heyoka {heyoka.__version__}"
    except ImportError:
        hy = "heyoka not importable (its rows are omitted)"
    return [f"- machine: {cpu}, {os.cpu_count()} logical CPUs, {platform.system()} "
            f"{platform.release()}; load average at start {load[0]:.2f} (shared machine: "
            "times under load are noisier and slower)",
            f"- Python {platform.python_version()}, NumPy {np.__version__}, SciPy {scipy.__version__}, "
            f"mpmath {mpmath.__version__} (backend {mpmath.libmp.BACKEND}), "
            f"matplotlib {matplotlib.__version__}, {hy}"]


def heyoka_available() -> tuple[bool, str]:
    """(True, "") when heyoka and our heyoka integrator import, else (False, the reason)."""
    try:
        import heyoka  # noqa: F401
        from chaplygin_nd.simulate.integrators import heyoka_taylor  # noqa: F401
    except ImportError as exc:
        return False, f"heyoka not importable ({exc}); its rows are omitted"
    return True, ""
