r"""The paper's statement of a ledger row, cut from the .tex and turned into HTML for MathJax.

Where a row's passage is: the environment that holds ``\label{ID}`` (for an equation, with the
paragraph around it); else the lines that ``symbolic/printed`` records for the row (its modules'
``SOURCE`` tables and the ``ID (lines a-b)`` of their docstrings, read by the run into the row's
``sources.paper_lines``), each widened to its paragraph;
else nothing (a row this project added, or a claim of the prose without a line of its own).

The conversion keeps every formula as LaTeX (``\(..\)``, ``\[..\]``) for MathJax and turns the
little text markup the paper uses into HTML; it never rewrites a formula.
"""

from __future__ import annotations

import html
import re
from dataclasses import dataclass

#: Display environments kept as maths; theorem-like ones shown with a bold heading.
MATH_ENVS = ("equation", "equation*", "align", "align*", "gather", "gather*", "multline",
             "multline*", "eqnarray", "eqnarray*")
THEOREM_ENVS = ("theorem", "proposition", "corollary", "lemma", "remark", "definition", "proof",
                "remarks*")
#: The paper's own macros (its preamble), for MathJax.
MACROS = {"R": r"\mathbb{R}", "I": r"\mathbb{I}", "J": r"\mathbb{J}", "so": r"\mathfrak{so}",
          "SO": r"\mathrm{SO}", "SE": r"\mathrm{SE}", "Ss": r"\mathrm{S}",
          "restr": [r"\,\vert_{#1}", 1], "defn": [r"\textbf{#1}", 1]}
_MAX_LINES = 40


@dataclass(frozen=True)
class Passage:
    """Lines ``first``..``last`` (1-based, inclusive) of the .tex and how they were found."""

    first: int
    last: int
    how: str


def _begin_end(lines: list[str], k: int) -> tuple[int, int, str] | None:
    """The innermost environment (of MATH_ENVS or THEOREM_ENVS) around line index ``k``."""
    depth: dict[str, int] = {}
    for i in range(k, -1, -1):
        for m in reversed(list(re.finditer(r"\\(begin|end)\{([a-z*]+)\}", lines[i]))):
            kind, env = m.groups()
            if env not in MATH_ENVS + THEOREM_ENVS:
                continue
            if kind == "end":
                depth[env] = depth.get(env, 0) + 1
            elif depth.get(env, 0):
                depth[env] -= 1
            else:
                for j in range(k, len(lines)):
                    if f"\\end{{{env}}}" in lines[j]:
                        return i, j, env
                return None
    return None


def _paragraph(lines: list[str], first: int, last: int) -> tuple[int, int]:
    """Widen ``first..last`` (indices) to the blank lines around it, at most _MAX_LINES."""
    while first > 0 and lines[first - 1].strip() and last - first < _MAX_LINES // 2:
        first -= 1
    while last + 1 < len(lines) and lines[last + 1].strip() and last - first < _MAX_LINES:
        last += 1
    return first, last


def passages(tex_lines: list[str], claim_id: str, printed: dict[str, set[int]]) -> list[Passage]:
    """Where the paper states ``claim_id`` (see the module docstring); ``[]`` when nowhere."""
    label = f"\\label{{{claim_id}}}"
    for k, line in enumerate(tex_lines):
        if label in line:
            found = _begin_end(tex_lines, k)
            if found is None:
                first, last = _paragraph(tex_lines, k, k)
                return [Passage(first + 1, last + 1, f"the paragraph of \\label{{{claim_id}}}")]
            first, last, env = found
            if env in MATH_ENVS:
                first, last = _paragraph(tex_lines, first, last)
                how = f"the {env} environment of \\label{{{claim_id}}} with its paragraph"
            else:
                how = f"the {env} environment of \\label{{{claim_id}}}"
            return [Passage(first + 1, last + 1, how)]
    out: list[Passage] = []
    for line in sorted(printed.get(claim_id, ())):
        k = line - 1
        if not 0 <= k < len(tex_lines) or (out and out[-1].first <= line <= out[-1].last):
            continue
        env = _begin_end(tex_lines, k)
        a, b = (env[0], env[1]) if env and env[2] in MATH_ENVS else (k, k)
        a, b = _paragraph(tex_lines, a, b)
        if out and a + 1 <= out[-1].last + 1:
            out[-1] = Passage(out[-1].first, max(out[-1].last, b + 1), out[-1].how)
        else:
            out.append(Passage(a + 1, b + 1, "lines transcribed in symbolic/printed"))
    return out


_MATH = re.compile(r"\$\$(.+?)\$\$|\$(.+?)\$|\\\[(.+?)\\\]|\\\((.+?)\\\)|"
                   r"\\begin\{(" + "|".join(re.escape(e) for e in MATH_ENVS) + r")\}(.+?)\\end\{\5\}",
                   re.S)


def _clean_math(body: str, link) -> str:
    body = re.sub(r"\\label\{[^}]*\}|\\nonumber|\\notag", "", body)
    body = re.sub(r"\\eq?ref\{([^}]*)\}", lambda m: r"\text{(" + m.group(1) + ")}", body)
    return html.escape(body, quote=False)


def _text(t: str, link) -> str:
    t = html.escape(t, quote=False)
    t = re.sub(r"\\label\{[^}]*\}", "", t)
    t = re.sub(r"\\eqref\{([^}]*)\}", lambda m: "(" + link(m.group(1)) + ")", t)
    t = re.sub(r"\\ref\{([^}]*)\}", lambda m: link(m.group(1)), t)
    t = re.sub(r"\\cite(?:\[[^]]*\])?\{([^}]*)\}", r"[\1]", t)
    t = re.sub(r"\\(?:emph|textit|defn)\{([^}]*)\}", r"<em>\1</em>", t)
    t = re.sub(r"\\textbf\{([^}]*)\}", r"<strong>\1</strong>", t)
    for env in THEOREM_ENVS:
        name = env.rstrip("*").capitalize()
        t = re.sub(r"\\begin\{" + re.escape(env) + r"\}(\[[^]]*\])?",
                   lambda m, name=name: f"<strong>{name}{' ' + m.group(1) if m.group(1) else ''}."
                                        "</strong> ", t)
        t = t.replace(f"\\end{{{env}}}", " ∎" if env == "proof" else "")
    t = re.sub(r"\\(?:begin|end)\{(?:enumerate|itemize)\}", "", t)
    t = re.sub(r"\\item\s*(\[[^]]*\])?", lambda m: "<br>• " + (m.group(1) or "")[1:-1] + " ", t)
    t = re.sub(r"\\(?:noindent|medskip|smallskip|bigskip|newline|qquad|quad)\b", " ", t)
    t = t.replace("~", "\u00a0").replace("``", "“").replace("''", "”").replace("\\\\", "<br>")
    return re.sub(r"\n\s*\n", "</p><p>", t)


def to_html(source: str, link=lambda cid: html.escape(cid)) -> str:
    """LaTeX passage -> HTML: formulas as ``\\(..\\)``/``\\[..\\]`` for MathJax, text markup as
    HTML; ``link(label)`` is the HTML shown for a ``\\ref``/``\\eqref`` (a link to a row's page)."""
    source = re.sub(r"(?<!\\)%.*", "", source)  # comments
    parts, pos = [], 0
    for m in _MATH.finditer(source):
        parts.append(_text(source[pos:m.start()], link))
        display, inline, bracket, paren, env, env_body = m.groups()
        if inline is not None or paren is not None:
            parts.append(r"\(" + _clean_math(inline if inline is not None else paren, link) + r"\)")
        else:
            body = display or bracket or env_body
            if env and env.startswith(("align", "eqnarray")):
                body = r"\begin{aligned}" + body + r"\end{aligned}"
            elif env and env.startswith("gather"):
                body = r"\begin{gathered}" + body + r"\end{gathered}"
            elif env and env.startswith("multline"):
                body = r"\begin{split}" + body + r"\end{split}"
            parts.append(r"\[" + _clean_math(body, link) + r"\]")
        pos = m.end()
    parts.append(_text(source[pos:], link))
    return "<p>" + "".join(parts) + "</p>"
