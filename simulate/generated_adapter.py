"""Adapter from the kernels of :mod:`generated` to the matrix interface of :mod:`simulate.kernels`."""

from __future__ import annotations

from simulate.kernels import Kernels

__all__ = ["bind"]


def bind() -> Kernels:
    """The kernels :mod:`generated` provides today, in the matrix interface."""
    return Kernels(name="generated", note="generated/ has no axisymmetric kernels yet")
