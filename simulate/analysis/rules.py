r"""The rules of the drawn evidence rows, one entry each, fixed before the runs: what each reads of a
measured orbit, what the row's orbits must satisfy, what contradicts a torus statement, and how the
control must separate from the row.

An entry (:class:`Rule`) names its ``part`` (what an ``open`` row's reason names: ``integrals``,
``chaos``, ``frequencies``), its ``observable`` (the field of
:class:`simulate.analysis.drawn_evidence.OrbitResult` it reads, measured by
:mod:`simulate.analysis.drawn_evidence`), its :class:`Criterion` list (a fraction of the orbits at
least or at most a bound), which orbits contradict (``contradicts``, with the word the reason uses)
and its ``control`` test (row and control orbits -> separates). :func:`unmet` and
:func:`separates` run every registered rule in order; ``proofs/drawn_common.py`` words the verdict.
A new rule is one :func:`register` call (in this module, or in a module of :data:`MODULES`); a rule
that needs a new measurement adds its field to ``OrbitResult`` and computes it in
:mod:`simulate.analysis.drawn_evidence`. Validate a rule on systems with known answers
(``chaplygin bench evidence``) before it decides a row.

The three rules (thresholds as fractions of the orbits):

* ``integrals`` — at least ``KEPT_MIN`` = 98 % keep the proved integrals (drift $\le 10^{-6}$ at
  energy scale 1, :mod:`simulate.analysis.kept`);
* ``chaos`` (the MEGNO horizon ladder, :func:`simulate.analysis.chaos.ladder_class`) — at most
  ``CONTRADICTING_MAX`` = 2 % chaotic (contradict) and at least ``MEGNO_REGULAR_MIN`` = 90 %
  regular; the control separates iff at least ``CONTROL_CHAOTIC_MIN`` = 90 % of its orbits are
  chaotic while at most 2 % of the row's are;
* ``frequencies`` (the NAFF count) — at most 2 % ``excess`` (contradict) and at least
  ``PREDICTED_MIN`` = 20 % with exactly the predicted count; the control separates iff its median
  diffusion is at least ``SEPARATION`` = 100 times the row's.

Then, when no rule alone has too many contradicting orbits, at most 2 % may contradict by any rule.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from chaplygin_nd.registry import Registry

__all__ = ["Criterion", "Rule", "register", "rules", "get", "unmet", "separates", "contradicting",
           "fraction", "holds", "MODULES", "CONTRADICTING_MAX", "MEGNO_REGULAR_MIN", "PREDICTED_MIN",
           "CONTROL_CHAOTIC_MIN", "SEPARATION", "KEPT_MIN"]

CONTRADICTING_MAX = 0.02
MEGNO_REGULAR_MIN = 0.90
PREDICTED_MIN = 0.20
CONTROL_CHAOTIC_MIN = 0.90
SEPARATION = 100.0
KEPT_MIN = 0.98

#: Modules that register further rules (this one registers the three above first).
MODULES: tuple[str, ...] = ()


def fraction(results, test) -> float:
    """The fraction of ``results`` for which ``test(r)`` holds."""
    return sum(bool(test(r)) for r in results) / len(results) if results else 0.0


@dataclass(frozen=True)
class Criterion:
    """The orbits for which ``counts(r)`` holds, described as ``what``, must be a fraction at
    least (``at_least``) or at most (``at_most``) ``bound`` of all."""

    what: str
    counts: Callable[[Any], bool]
    bound: float
    at_least: bool


@dataclass(frozen=True)
class Rule:
    """One rule (module docstring): ``contradicts(r)`` an orbit against a torus statement, called
    ``word`` in the reason; ``control(results, control) -> bool`` the separation it asks for."""

    part: str
    observable: str
    criteria: tuple[Criterion, ...]
    contradicts: Callable[[Any], bool] | None = None
    word: str = ""
    control: Callable[[list, list], bool] | None = None


_REGISTRY: Registry[Rule] = Registry("evidence rule", lambda r: r.part, MODULES)
register = _REGISTRY.register
get = _REGISTRY.get
rules = _REGISTRY.entries


def holds(part: str, results) -> bool:
    """Whether ``results`` meet every criterion of the rule of ``part``."""
    n = len(results)
    return bool(n) and all(
        (fraction(results, c.counts) >= c.bound if c.at_least else fraction(results, c.counts) <= c.bound)
        for c in get(part).criteria)


def contradicting(r) -> bool:
    """An orbit that contradicts a torus statement by some rule."""
    return any(rule.contradicts(r) for rule in rules() if rule.contradicts is not None)


def unmet(results) -> list[str]:
    """The criteria of the registered rules that ``results`` fail, each with its numbers
    (``[]`` iff the statement is supported): what an ``open`` row names as its reason."""
    n = len(results)
    if not n:
        return ["no drawn orbits"]
    counts = [(rule.part, sum(bool(c.counts(r)) for r in results), c)
              for rule in rules() for c in rule.criteria]
    against = [rule for rule in rules() if rule.contradicts is not None]
    if all(fraction(results, rule.contradicts) <= CONTRADICTING_MAX for rule in against):
        counts.append((" and ".join(rule.part for rule in against),
                       sum(contradicting(r) for r in results),
                       Criterion(f"are {' or '.join(rule.word for rule in against)} (contradict)",
                                 contradicting, CONTRADICTING_MAX, at_least=False)))
    return [f"{part}: {k} of {n} orbits {c.what}: {100 * k / n:g} %, "
            f"{'fewer than' if c.at_least else 'more than'} the rule's {100 * c.bound:g} %"
            for part, k, c in counts
            if not (k / n >= c.bound if c.at_least else k / n <= c.bound)]


def separates(results, control) -> tuple[bool, ...]:
    """Per rule that has a control test (in order: the chaos indicator, the frequency
    diffusion), whether the control separates from ``results``."""
    return tuple(bool(rule.control(results, control)) for rule in rules()
                 if rule.control is not None)


def _keeps(r) -> bool:
    from chaplygin_nd.simulate.analysis.kept import KEPT

    return bool(r.drift <= KEPT)


def _chaotic(r) -> bool:
    return r.megno_cls == "chaotic"


def _megno_separates(results, control) -> bool:
    return (fraction(control, _chaotic) >= CONTROL_CHAOTIC_MIN
            and fraction(results, _chaotic) <= CONTRADICTING_MAX)


def _diffusion_separates(results, control) -> bool:
    d_row = float(np.median([r.diffusion for r in results]))
    d_ctl = float(np.median([r.diffusion for r in control]))
    return bool(d_ctl >= SEPARATION * max(d_row, 1e-300))


INTEGRALS = register(Rule(
    "integrals", "drift",
    (Criterion("keep the proved integrals", _keeps, KEPT_MIN, at_least=True),)))
CHAOS = register(Rule(
    "chaos", "megno_cls",
    (Criterion("are chaotic by the MEGNO ladder (contradict)", _chaotic, CONTRADICTING_MAX,
               at_least=False),
     Criterion("are regular by the MEGNO ladder", lambda r: r.megno_cls == "regular",
               MEGNO_REGULAR_MIN, at_least=True)),
    contradicts=_chaotic, word="chaotic", control=_megno_separates))
FREQUENCIES = register(Rule(
    "frequencies", "cls",
    (Criterion("have a line no combination |c| <= 12 explains (excess, contradict)",
               lambda r: r.cls == "excess", CONTRADICTING_MAX, at_least=False),
     Criterion("show exactly the predicted count", lambda r: r.cls == "predicted",
               PREDICTED_MIN, at_least=True)),
    contradicts=lambda r: r.cls == "excess", word="excess", control=_diffusion_separates))
