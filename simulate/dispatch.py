r"""The one place where :mod:`simulate` binds to the verified kernels of :mod:`generated`.

The interface (:class:`~chaplygin_nd.simulate.kernels.Kernels`) is described in
:mod:`chaplygin_nd.simulate.kernels`. :func:`active` returns the kernels in use (by default those of
:mod:`generated`, bound by :mod:`chaplygin_nd.simulate.generated_adapter`); :func:`use` swaps them
(tests compare the generated kernels with an independent route this way).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

from chaplygin_nd.simulate import generated_adapter
from chaplygin_nd.simulate.kernels import OPTIONAL, KernelMissing, Kernels

__all__ = ["Kernels", "KernelMissing", "active", "use", "from_generated", "OPTIONAL"]


def from_generated() -> Kernels:
    """Bind the kernels of :mod:`generated` (see :mod:`simulate.generated_adapter`)."""
    return generated_adapter.bind()


_ACTIVE: list[Kernels] = []


def active() -> Kernels:
    """The kernels in use: the innermost :func:`use`, else those of :mod:`generated`."""
    if not _ACTIVE:
        _ACTIVE.append(from_generated())
    return _ACTIVE[-1]


@contextlib.contextmanager
def use(kernels: Kernels) -> Iterator[Kernels]:
    """Use ``kernels`` inside the ``with`` block (e.g. an independent reference in a test)."""
    _ACTIVE.append(kernels)
    try:
        yield kernels
    finally:
        _ACTIVE.pop()
