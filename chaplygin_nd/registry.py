"""One shape for every extension point of the project: a registry of frozen entries, filled by the
modules that define them (each calls :meth:`Registry.register` at import), looked up by name.
The integrators (:mod:`simulate.integrators.registry`), the scene outputs
(:mod:`simulate.scene.output_registry`) and the evidence rules (:mod:`simulate.analysis.rules`)
are each one :class:`Registry`; nothing elsewhere switches on their names."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Generic, TypeVar

__all__ = ["Registry"]

T = TypeVar("T")


class Registry(Generic[T]):
    """Entries of one ``kind`` keyed by ``key(entry)``; ``modules`` (full module names) register
    theirs when first imported, which :meth:`load` does before any lookup."""

    def __init__(self, kind: str, key: Callable[[T], str], modules: tuple[str, ...] = ()):
        self.kind, self.key, self.modules = kind, key, modules
        self._entries: dict[str, T] = {}

    def register(self, entry: T) -> T:
        """Add ``entry`` (one name once; registering the same entry again is harmless)."""
        name = self.key(entry)
        if name in self._entries and self._entries[name] is not entry:
            raise ValueError(f"{self.kind} {name!r} registered twice")
        self._entries[name] = entry
        return entry

    def load(self) -> None:
        """Import the registering modules (each registers at its first import only)."""
        for module in self.modules:
            importlib.import_module(module)

    def get(self, name: str) -> T:
        """The entry called ``name``; ``ValueError`` naming the known ones otherwise."""
        self.load()
        if name not in self._entries:
            raise ValueError(f"no {self.kind} {name!r}; known: {', '.join(sorted(self._entries))}")
        return self._entries[name]

    def entries(self) -> list[T]:
        """Every entry, in the order of ``modules`` (and of registration within one)."""
        self.load()
        return list(self._entries.values())

    def names(self) -> tuple[str, ...]:
        """Every name, in the order of :meth:`entries`."""
        return tuple(self.key(e) for e in self.entries())
