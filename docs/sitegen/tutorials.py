"""A small build-time executor for the tutorial pages (no Jupyter kernel needed).

A tutorial is MyST Markdown; every fenced block opened with ```` ```python exec ```` runs, in
order, in one namespace per page; what it prints follows it as a text block and every matplotlib
figure it leaves open is saved as a PNG and shown after it. A block that raises stops the build
(the error names the page and the block): a tutorial that does not run is not published.
"""

from __future__ import annotations

import contextlib
import io
import re
import traceback
from pathlib import Path

_BLOCK = re.compile(r"^```python exec\n(.*?)^```\n", re.S | re.M)


class TutorialError(RuntimeError):
    pass


def execute(source: str, name: str, out_dir: Path) -> str:
    """The page ``source`` with every exec block run and followed by its output and figures."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import pyplot as plt

    namespace: dict = {"__name__": f"tutorial_{name}"}
    parts, pos, figures = [], 0, 0
    for k, m in enumerate(_BLOCK.finditer(source), 1):
        parts.append(source[pos:m.start()])
        block = m.group(1)
        parts.append("```python\n" + block + "```\n")
        buffer = io.StringIO()
        try:
            with contextlib.redirect_stdout(buffer):
                exec(compile(block, f"<{name} block {k}>", "exec"), namespace)
        except Exception as exc:
            raise TutorialError(f"tutorial {name}, block {k}: {exc}\n"
                                + traceback.format_exc(limit=4)) from exc
        if buffer.getvalue().strip():
            parts.append("\n```text\n" + buffer.getvalue().rstrip() + "\n```\n")
        for number in plt.get_fignums():
            figures += 1
            png = f"{name}-{figures}.png"
            plt.figure(number).savefig(out_dir / png, dpi=110, bbox_inches="tight",
                                       metadata={"Software": None})
            parts.append(f"\n![figure {figures} of this tutorial]({png})\n")
        plt.close("all")
        pos = m.end()
    parts.append(source[pos:])
    return "".join(parts)


def execute_all(src: Path, out: Path) -> None:
    """Execute every ``*.md`` of ``src`` into ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    for page in sorted(src.glob("*.md")):
        text = execute(page.read_text(encoding="utf-8"), page.stem, out)
        (out / page.name).write_text(text, encoding="utf-8")
