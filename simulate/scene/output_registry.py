r"""The scene outputs, one entry each: the one place the scene product (scene validation, planner,
collection, files and figures) looks an output up by the name a scene gives in ``outputs.want``.

An entry (:class:`Output`) says how its arrays are collected from a trajectory (``collect``), how
each of them is written and drawn (``figures``, ``csv``), what it needs from the planner (whether a
reduced $SO(3)$-invariant model or the horizontal closed form for any $n$ can produce it, whether
it needs the reconstruction, whether it reads $\Omega$ along the samples) and what a scene must
satisfy to ask for it (``only_n``, ``spectral``, ``vertical``). Each output module registers its
outputs at import (:func:`register`); :data:`MODULES` lists them, in the order the scene's error
messages list the names. A new output is one :func:`register` call in a module of :data:`MODULES`;
nothing elsewhere switches on output names.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from chaplygin_nd.registry import Registry

__all__ = ["Output", "register", "get", "names", "where", "owner", "drawing", "MODULES"]

#: The modules that register outputs, in the order their names are listed.
MODULES = ("outputs", "tori")


@dataclass(frozen=True)
class Output:
    r"""One output, as the scene product sees it.

    ``collect(scene, data) -> {key: array}``: its arrays from the trajectory's ``data`` (``None``:
    it writes its own files, e.g. :mod:`simulate.scene.tori`). ``figures``: how each array it
    writes is drawn, ``{key: draw(plt, key, t, arr) or None}`` where a key ending in ``.`` stands
    for every key with that prefix and ``None`` draws nothing (default: its name, drawn as a time
    series). ``csv(path, t, arr, name)``: how it is written as a table (``None``: one row per
    sample and member). ``reduced`` / ``horizontal``: the reduced 7D model / the horizontal closed
    form for any $n$ can produce it; ``reconstruct``: it needs $g$ and the contact path;
    ``omega``: it reads $\Omega$ along the samples. ``reduced_kernels``: the kernels the reduced
    model needs for it; ``full_reason``: why it needs the full system even for $n = 4$ (the plan
    line says it), empty when it does not. ``only_n``: the one $n$ it exists for;
    ``spectral``: it needs uniformly spaced samples; ``vertical``: it is defined for vertical
    momentum only."""

    name: str
    collect: Callable[[Any, dict], dict[str, Any]] | None
    figures: Mapping[str, Callable[..., Any] | None] = field(
        default_factory=lambda: MappingProxyType({}))
    csv: Callable[..., None] | None = None
    reduced: bool = False
    horizontal: bool = False
    reconstruct: bool = False
    omega: bool = False
    reduced_kernels: tuple[str, ...] = ()
    full_reason: str = ""
    only_n: int | None = None
    spectral: bool = False
    vertical: bool = False


_REGISTRY: Registry[Output] = Registry(
    "output", lambda e: e.name, tuple(f"chaplygin_nd.simulate.scene.{m}" for m in MODULES))
register = _REGISTRY.register
get = _REGISTRY.get
names = _REGISTRY.names


def where(flag: str) -> frozenset[str]:
    """The names of the outputs whose ``flag`` (``reduced``, ``horizontal``, ``reconstruct``,
    ``spectral``, ...) is set."""
    return frozenset(e.name for e in _REGISTRY.entries() if getattr(e, flag))


def drawing(key: str, default: Callable[..., Any]) -> Callable[..., Any] | None:
    """How the array ``key`` is drawn: what its output registered in ``figures``, else
    ``default``; ``None`` for an array that has no figure (e.g. ``integrals.<name>``)."""
    found = owner(key)
    return default if found is None else found[0].figures.get(found[1], default)


def owner(key: str) -> tuple[Output, str] | None:
    """The output that writes the array ``key`` (its name, or a prefix of its ``figures``) and the
    key of ``figures`` that matched (``key`` itself when the entry names no figure for it)."""
    entries = _REGISTRY.entries()
    for entry in entries:
        if entry.name == key:
            return entry, key
    for entry in entries:
        for pattern in entry.figures:
            if pattern == key or (pattern.endswith(".") and key.startswith(pattern)):
                return entry, pattern
    return None
