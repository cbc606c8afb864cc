r"""Verdicts and the claim registry.

A proof module registers one function per ledger row::

    from chaplygin_nd.ledger.registry import Verdict, claim

    @claim("eq:invL3D", uses=("eq:mom3D", "S2.1:detL3D"))
    def inverse_3d() -> Verdict:
        printed = rational_identity(...)          # a symbolic.exact.identity.Check
        return Verdict.decide(printed, method_suffix="", n_values=(3,))

The verdict of a comparison is *computed*, never asserted: :meth:`Verdict.decide` returns
``holds`` when the printed formula agrees with the derivation, ``corrected`` when it does not but
a stated correction is proved, ``fails`` otherwise. A row may consist of named :class:`Part`\ s,
each with its own verdict; the row's verdict is then the worst of its parts.

A row may announce each part as soon as it is final with :func:`decided` (``parts.append(
decided(Part(...)))``): the part must then appear, unchanged, in the row's verdict. Nothing
observes it in a normal run; ``make mutate-derivations`` does (:func:`observing_parts`), and
stops a mutant's run of the row at the first final part that differs from the unmutated row's —
the row's signature has changed whatever the later parts say.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass, field

from chaplygin_nd.symbolic.exact.identity import Check

__all__ = ["Verdict", "Part", "claim", "registry", "VERDICTS", "ClaimSpec", "KINDS",
           "ERRATA_KINDS", "NEEDS_KIND",
           "EVIDENCE_FIELDS", "decided", "observing_parts"]

#: Verdicts, best first. ``error`` is set only by the runner when a proof raises. ``evidence`` is
#: numerical support for a qualitative statement (never counted as ``holds``).
VERDICTS = ("holds", "definition", "corrected", "evidence", "open", "fails", "error")
_RANK = {v: i for i, v in enumerate(VERDICTS)}
#: What an ``evidence`` row must state (DESIGN.md, Verdicts).
EVIDENCE_FIELDS = frozenset({"measured", "initial_conditions", "tolerance", "contradiction",
                             "control", "control_separates"})

#: What a non-holding row found, most serious first (DESIGN.md, "Verdicts"):
#: ``formula`` — a displayed formula is false; ``proof`` — a step of a proof is false, the
#: statement holds; ``scope`` — the statement fails on a parameter value or stratum the paper does
#: not exclude; ``reading`` — the text is ambiguous, false in one reading and true in another.
KINDS = ("formula", "proof", "scope", "reading")
#: Kinds that are errata of the paper; the others are remarks.
ERRATA_KINDS = ("formula", "proof")
#: Verdicts that must say which kind of finding they are.
NEEDS_KIND = ("corrected", "fails")


def _check_kind(kind: str | None) -> None:
    if kind is not None and kind not in KINDS:
        raise ValueError(f"unknown kind {kind!r}; one of {KINDS}")


def _kind_for(verdict: str, kind: str | None) -> str | None:
    """A kind describes a finding: it is kept only on a row that is not a pass."""
    _check_kind(kind)
    return kind if verdict in NEEDS_KIND else None


@dataclass(frozen=True)
class Part:
    """One named sub-claim of a row (e.g. one component of a vector field)."""

    name: str
    verdict: str
    method: str
    counterexample: str | None = None
    counterexample_latex: str | None = None
    printed_latex: str | None = None
    correction_latex: str | None = None
    notes: str = ""
    kind: str | None = None
    #: argued in prose, not computed (counted and listed apart; never a machine-checked pass)
    argued: bool = False
    remark: str = ""

    def __post_init__(self):
        if self.verdict not in VERDICTS:
            raise ValueError(f"unknown verdict {self.verdict!r}")
        _check_kind(self.kind)


def _decide(printed: Check, corrected: Check | None, correction_latex: str | None):
    """(verdict, counterexample text, counterexample latex, correction) from two checks."""
    if printed.ok:
        return "holds", None, None, None
    cx = printed.counterexample
    text = cx.text() if cx else None
    latex = cx.latex() if cx else None
    if corrected is not None and corrected.ok and correction_latex:
        return "corrected", text, latex, correction_latex
    if corrected is not None and not corrected.ok:
        extra = corrected.counterexample.text() if corrected.counterexample else "no counterexample"
        text = f"{text}; the proposed correction fails too: {extra}"
    return "fails", text, latex, None


@dataclass(frozen=True)
class Verdict:
    """The outcome of one ledger row. Build it with the class methods, not directly."""

    verdict: str
    method: str
    n_values: tuple[int, ...] = ()
    counterexample: str | None = None
    counterexample_latex: str | None = None
    printed_latex: str | None = None
    correction_latex: str | None = None
    notes: str = ""
    parts: tuple[Part, ...] = ()
    #: ``formula``/``proof``/``scope``/``reading`` for a ``corrected``/``fails`` row (see KINDS)
    kind: str | None = None
    #: what the paper leaves implicit, stated for the reader (e.g. a constant factor its proof
    #: names); shown in the remarks of the report, never changes the verdict
    remark: str = ""
    #: argued in prose, not computed (counted and listed apart; never a machine-checked pass)
    argued: bool = False
    evidence: dict | None = None  # for ``evidence`` rows: see :meth:`Verdict.numerical`
    #: machine-readable results of a row beyond the paper (e.g. the degree table of
    #: S6:first-integrals), written to verification.json as they are
    data: dict | None = None

    def __post_init__(self):
        if self.verdict not in VERDICTS:
            raise ValueError(f"unknown verdict {self.verdict!r}")
        _check_kind(self.kind)
        fixed = self.correction_latex or any(p.verdict == "corrected" and p.correction_latex
                                             for p in self.parts)
        if self.verdict == "corrected" and not (self.counterexample and fixed):
            raise ValueError("a corrected row needs a counterexample and a corrected formula")
        if self.verdict == "evidence" and not (self.evidence and EVIDENCE_FIELDS <= set(self.evidence)):
            raise ValueError(f"an evidence row needs the fields {sorted(EVIDENCE_FIELDS)}")

    # -- constructors ------------------------------------------------------------------------
    @classmethod
    def decide(cls, printed: Check, *, n_values: Sequence[int] = (), method: str = "",
               corrected: Check | None = None, correction_latex: str | None = None,
               printed_latex: str | None = None, notes: str = "", kind: str | None = None,
               remark: str = "", argued: bool = False) -> Verdict:
        """Compare the printed formula (``printed``: the check of printed == derived) and, if it
        fails, a proposed correction (``corrected``: the check of corrected == derived).
        ``kind`` (one of :data:`KINDS`) says what a failure of ``printed`` means; it is kept only
        when the verdict is ``corrected`` or ``fails``. ``argued``: the check rests on a step
        argued in prose, not computed (said in the method)."""
        verdict, cx, cx_latex, fix = _decide(printed, corrected, correction_latex)
        how = method or printed.method
        if verdict == "corrected" and corrected is not None:
            how = f"{how}; correction: {corrected.method}"
        return cls(verdict, how, tuple(n_values), cx, cx_latex,
                   printed_latex if verdict != "holds" else None, fix, notes,
                   kind=_kind_for(verdict, kind), remark=remark, argued=argued)

    @classmethod
    def all_of(cls, checks: Iterable[tuple[str, Check]], *, n_values: Sequence[int] = (),
               method: str = "", notes: str = "", kind: str | None = None,
               argued: bool = False) -> Verdict:
        """``holds`` iff every named check holds; otherwise ``fails`` (of ``kind``) with the first
        counterexample. The method lists each check's method unless ``method`` is given. No
        checks: ``ValueError`` (an empty conjunction proves nothing)."""
        checks = list(checks)
        if not checks:
            raise ValueError("all_of needs at least one check")
        methods = "; ".join(f"{name}: {c.method}" for name, c in checks)
        for name, c in checks:
            if not c.ok:
                cx = c.counterexample
                return cls("fails", method or methods, tuple(n_values),
                           f"{name}: {cx.text()}" if cx else name,
                           cx.latex() if cx else None, None, None, notes, kind=kind,
                           argued=argued)
        return cls("holds", method or methods, tuple(n_values), notes=notes, argued=argued)

    @classmethod
    def definition(cls, method: str, *, n_values: Sequence[int] = (), notes: str = "",
                   consistency: Iterable[tuple[str, Check]] = ()) -> Verdict:
        """A definition. Optional ``consistency`` checks (e.g. the nD definition restricts to the 3D
        one); if one fails the row is ``fails``, with its counterexample."""
        checks = list(consistency)
        if not all(c.ok for _, c in checks):
            return cls.all_of(checks, n_values=n_values, notes=notes)
        if checks:
            method = method + "; " + "; ".join(f"{name}: {c.method}" for name, c in checks)
        return cls("definition", method, tuple(n_values), notes=notes)

    @classmethod
    def numerical(cls, supported: bool, *, measured: str, initial_conditions: int,
                  tolerance: str, contradiction: str, control: str, control_separates: bool,
                  method: str, n_values: Sequence[int] = (), notes: str = "",
                  data: dict | None = None, unmet: Sequence[str] = ()) -> Verdict:
        """Numerical evidence for a qualitative statement. ``evidence`` only when the measurement
        supports the statement *and* the control (a system where the statement should fail)
        shows the method can tell the difference; otherwise ``open`` with the numbers as reason.
        Never ``holds``: a measurement is not a proof. The row records what was measured, on how
        many initial conditions, with which tolerance, what would have contradicted the
        statement, and the control. ``unmet``: the parts of the rule that failed, named first in
        an ``open`` row's reason."""
        record = {"measured": measured, "initial_conditions": initial_conditions,
                  "tolerance": tolerance, "contradiction": contradiction, "control": control,
                  "control_separates": control_separates, **(data or {})}
        if supported and control_separates:
            return cls("evidence", method, tuple(n_values), notes=notes, evidence=record)
        why = ("the control does not separate from the regular orbits" if not control_separates
               else "the measurement does not support the statement"
               + (f" ({'; '.join(unmet)})" if unmet else ""))
        return cls("open", method, tuple(n_values),
                   notes=f"{why}: {measured}; {notes}".strip("; "), evidence=record)

    @classmethod
    def by_argument(cls, argument: str, *, n_values: Sequence[int] = (), notes: str = "") -> Verdict:
        """A step argued in prose (a mathematical fact we state), not computed: ``holds`` with
        ``argued=True``; the method says "argued, not machine-checked". Reports count such parts
        apart; use it only for what no computation here decides."""
        if not argument.strip():
            raise ValueError("an argued step must state its argument")
        return cls("holds", f"argued, not machine-checked: {argument}", tuple(n_values),
                   notes=notes, argued=True)

    @classmethod
    def open(cls, reason: str) -> Verdict:
        """Not decided yet; ``reason`` says why and names the work that will decide it."""
        if not reason.strip():
            raise ValueError("an open row must say why and what will decide it")
        return cls("open", "not yet checked", notes=reason)

    @classmethod
    def of_parts(cls, parts: Sequence[Part], *, n_values: Sequence[int] = (), method: str = "",
                 notes: str = "", kind: str | None = None, remark: str = "") -> Verdict:
        """A row made of named parts; its verdict is the worst part's (``definition`` ~ ``holds``).
        Its kind is ``kind`` or, by default, the most serious kind of the parts that carry the
        row's verdict. The printed and corrected formulas stay on the parts (one display each)."""
        if not parts:
            raise ValueError("of_parts needs at least one part")
        worst = max(parts, key=lambda p: _RANK["holds" if p.verdict == "definition" else p.verdict])
        verdict = "holds" if worst.verdict == "definition" else worst.verdict
        method = method or "; ".join(sorted({p.method for p in parts}))
        remark = remark or " ".join(p.remark for p in parts if p.remark)
        if verdict in NEEDS_KIND:
            bad = [p for p in parts if p.verdict == verdict]
            cx = "; ".join(f"{p.name}: {p.counterexample}" for p in bad)
            kinds = [p.kind for p in bad if p.kind]
            kind = kind or min(kinds, key=KINDS.index, default=None)
            return cls(verdict, method, tuple(n_values), cx, None, None, None, notes, tuple(parts),
                       kind=_kind_for(verdict, kind), remark=remark)
        if verdict == "open":
            notes = notes or "; ".join(f"{p.name}: {p.notes}" for p in parts if p.verdict == "open")
        return cls(verdict, method, tuple(n_values), notes=notes, parts=tuple(parts), remark=remark)

    def as_part(self, name: str) -> Part:
        """This verdict as a named part of a larger row (its remark becomes the row's remark)."""
        return Part(name, self.verdict, self.method, self.counterexample,
                    self.counterexample_latex, self.printed_latex, self.correction_latex,
                    self.notes, self.kind, self.argued, self.remark)

    @property
    def argued_parts(self) -> tuple[str, ...]:
        """Names of what this row argues in prose instead of computing (the row itself if so)."""
        names = tuple(p.name for p in self.parts if p.argued)
        return names + (("(the whole row)",) if self.argued and not names else ())

    def to_dict(self) -> dict:
        d = asdict(self)
        d["n_values"] = list(self.n_values)
        d["parts"] = [asdict(p) for p in self.parts]
        return d


@dataclass(frozen=True)
class ClaimSpec:
    """A registered proof: the row id, the function that decides it, the ids it uses."""

    id: str
    run: Callable[[], Verdict]
    uses: tuple[str, ...] = field(default=())
    module: str = ""
    adds: tuple[str, str] | None = None  # (section, claim) of a row this project adds


_REGISTRY: dict[str, ClaimSpec] = {}


def claim(claim_id: str, *, uses: Sequence[str] = (), adds: tuple[str, str] | None = None) -> Callable:
    """Register the decorated zero-argument function as the proof of ledger row ``claim_id``.

    ``adds=(section, claim)`` makes it a row this project adds to the ledger (e.g. a stable
    rewrite of a formula for a kernel, or a labelled equation CLAIMS.md has no row for); without it
    ``claim_id`` must be a row of CLAIMS.md. A row is declared in one of the two places, never
    both (:func:`ledger.catalog.all_rows` refuses it)."""

    def register(fn: Callable[[], Verdict]) -> Callable[[], Verdict]:
        if claim_id in _REGISTRY:
            raise ValueError(f"ledger row {claim_id!r} registered twice "
                             f"({_REGISTRY[claim_id].module} and {fn.__module__})")
        _REGISTRY[claim_id] = ClaimSpec(claim_id, fn, tuple(uses), fn.__module__, adds)
        return fn

    return register


#: The observers of :func:`decided` (a stack; empty in a normal run).
_OBSERVERS: list[Callable[[Part], None]] = []


def decided(part: Part) -> Part:
    """Announce that ``part`` is final (it will be in the row's verdict as it is); returns it."""
    for observe in _OBSERVERS:
        observe(part)
    return part


class observing_parts:  # noqa: N801 - used as a context manager, like contextlib's
    """``with observing_parts(callback):`` calls ``callback(part)`` at each :func:`decided` part of
    the rows run inside it (the callback may raise to stop the row there); ``.seen`` lists them."""

    def __init__(self, callback: Callable[[Part], None]):
        self.callback = callback
        self.seen: list[Part] = []

    def _observe(self, part: Part) -> None:
        self.seen.append(part)
        self.callback(part)

    def __enter__(self) -> observing_parts:
        _OBSERVERS.append(self._observe)
        return self

    def __exit__(self, *exc) -> None:
        _OBSERVERS.remove(self._observe)


def registry() -> dict[str, ClaimSpec]:
    """The registered proofs (import :mod:`ledger.catalog` ``discover()`` first)."""
    return dict(_REGISTRY)
