r"""The integrators, one entry each: the one place the scene product (planner, cost model, run,
cross-check) looks an integrator up by the name a scene gives in ``accuracy.method``.

An entry (:class:`Integrator`) says what its settings are (a class of
:mod:`simulate.integrators.settings`), how the target becomes settings (``calibrate``) and how
accurate those settings are (``error``), how to run it (``run``), what the plan line says
(``describe``), whether it can integrate the reduced 7D field, whether it is usable here, and
the order in which ``accuracy.method = "auto"`` and ``--cross-check`` try it, whether a scene may
name it, and its calibration (the measured error model of
:class:`simulate.integrators.settings.Calibration`; the tables of that module are read from here).
Each integrator module of this folder registers itself at import (:func:`register`); :data:`MODULES`
lists them. A new integrator is one module that calls :func:`register`, and its name in
:data:`MODULES`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from chaplygin_nd.simulate.integrators.base import Solution

from chaplygin_nd.registry import Registry

__all__ = ["Integrator", "register", "get", "names", "named", "entries", "MODULES"]

#: The integrator modules, each registering one or more entries at import.
MODULES = ("dop853", "heyoka_taylor", "lie", "taylor")


@dataclass(frozen=True)
class Integrator:
    """One integrator, as the scene product sees it.

    ``run(field, y0, t, settings, progress=..., compact=...) -> Solution``;
    ``calibrate(target, span, step, dps, precision) -> settings``; ``error(settings, span)``: the
    calibrated relative error (no safety factor). ``auto`` / ``reference``: rank among the
    methods ``accuracy.method = "auto"`` / the cross-check reference try, lowest first (``None``:
    never). ``costed``: the cost model (:mod:`simulate.scene.cost`) predicts its run time.
    ``scene``: a scene may name it in ``accuracy.method``. ``cost(pilot, tol) -> [Candidate]``:
    its predicted runs (required when ``costed``; :class:`simulate.integrators.base.Pilot`). ``calibration``: ``((key, Calibration),
    ...)``, one per precision it calibrates (the key is its name, or e.g. ``real128``)."""

    name: str
    settings: type  # a class of simulate.integrators.settings (which imports this module)
    run: Callable[..., Solution]
    calibrate: Callable[..., Any]
    error: Callable[[Any, float], float]
    describe: Callable[[Any], str]
    reduced: bool = True
    available: Callable[[], bool] = lambda: True
    auto: int | None = None
    reference: int | None = None
    costed: bool = False
    cost: Callable[..., list] | None = None
    scene: bool = True
    calibration: tuple[tuple[str, Any], ...] = ()


_REGISTRY: Registry[Integrator] = Registry(
    "integrator", lambda e: e.name,
    tuple(f"chaplygin_nd.simulate.integrators.{module}" for module in MODULES))
register = _REGISTRY.register
get = _REGISTRY.get
entries = _REGISTRY.entries


def names(order: str | None = None) -> list[str]:
    """Every registered name; with ``order = "auto"`` or ``"reference"`` those that take part,
    in their rank order."""
    if order is None:
        return sorted(_REGISTRY.names())
    ranked = [(getattr(e, order), e.name) for e in entries() if getattr(e, order) is not None]
    return [name for _, name in sorted(ranked)]


def named() -> list[str]:
    """The names a scene may give in ``accuracy.method`` (besides ``auto``), sorted."""
    return sorted(e.name for e in entries() if e.scene)
