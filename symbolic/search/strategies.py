"""Which strategy of symbolic/search/box_search.py searches which space: ``invariant`` (the
SO(n-1)-invariant polynomials, symbolic/search/invariant_search.py) or ``weight-zero`` (monomials of
weight zero for a maximal torus, symbolic/search/integral_search.py)."""

from __future__ import annotations

__all__ = ["make_search", "default_space", "SPACES"]

SPACES = ("invariant", "weight-zero")


def default_space(model) -> str:
    """``invariant`` where the model's invariant generators are derived, else ``weight-zero``."""
    from chaplygin_nd.symbolic.search import invariant_rings

    try:
        invariant_rings.ring_for(model.n, model.kind)
    except ValueError:
        return "weight-zero"
    return "invariant"


def make_search(model, space: str | None, include_new: bool = True):
    """The strategy for ``space`` (``invariant``, ``weight-zero``, or None: the invariant ring
    where its generators are derived, else weight zero); ValueError when the invariant ring is
    asked for where it is not derived."""
    from chaplygin_nd.symbolic.search.integral_search import WeightZeroSearch
    from chaplygin_nd.symbolic.search.invariant_search import InvariantRingSearch

    space = space or default_space(model)
    if space == "invariant":
        if default_space(model) != "invariant":
            from chaplygin_nd.symbolic.search import invariant_rings

            invariant_rings.ring_for(model.n, model.kind)     # raises with the reason
        return InvariantRingSearch(model, include_new=include_new)
    return WeightZeroSearch(model, include_new=include_new)
