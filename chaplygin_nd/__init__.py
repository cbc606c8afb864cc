r"""chaplygin-nd: a machine-checked companion to *Integrability of the n-dimensional axially
symmetric Chaplygin sphere* (L. C. García-Naranjo).

Subpackages, one idea each (the repository keeps them as top-level folders; installed, they live
under this namespace):

* :mod:`chaplygin_nd.symbolic` — the definitions and the derivations (SymPy);
* :mod:`chaplygin_nd.proofs` — one claim script per group of the paper's claims;
* :mod:`chaplygin_nd.ledger` — the machinery that runs the claims and reports the verdicts;
* :mod:`chaplygin_nd.generated` — NumPy kernels emitted from the proved formulas (never edited);
* :mod:`chaplygin_nd.runtime` — the hand-written assembly of those kernels for any ``n``;
* :mod:`chaplygin_nd.simulate` — scenes, the model planner and the integrators (no SymPy);
* :mod:`chaplygin_nd.bench` — accuracy-versus-time and throughput benchmarks.

The command line is ``chaplygin`` (``python -m chaplygin_nd``): see :mod:`chaplygin_nd.cli`.
For notebooks, :mod:`chaplygin_nd.api` is re-exported here: ``chaplygin_nd.decide``,
``chaplygin_nd.simulate``, ``chaplygin_nd.angular_velocity``, ``L_gamma``, ``vector_field``,
``energy``, ``zeta``. They are imported on first use, so ``import chaplygin_nd`` loads neither
SymPy nor NumPy. ``chaplygin_nd.simulate`` is the function :func:`chaplygin_nd.api.simulate`
(``help`` shows it) whose attributes are the subpackage's (``chaplygin_nd.simulate.scene``).
"""

import importlib as _importlib
import os as _os
import sys as _sys
import types as _types

# SymPy's ground types, decided before SymPy is first imported: with python-flint installed,
# SymPy >= 1.13 would silently switch to "flint" and its QQ arithmetic and DomainMatrix would
# then run on FLINT — the second engine (symbolic/exact/flint_engine.py) would share code with the
# first. "gmpy" keeps SymPy's engine its own (README: "Two exact engines").
_os.environ.setdefault("SYMPY_GROUND_TYPES", "gmpy")

__version__ = "0.2.0"

_API = ("decide", "simulate", "Simulation", "angular_velocity", "L_gamma", "vector_field",
        "energy", "zeta", "first_integrals")
__all__ = ["__version__", *_API]


def _callable_subpackage(module: _types.ModuleType) -> _types.FunctionType:
    """:func:`chaplygin_nd.api.simulate` as a new function object whose attribute namespace is the
    subpackage's: ``help(cn.simulate)`` shows the function (its signature and docstring),
    ``cn.simulate("steady4d")`` runs a scene, and ``cn.simulate.scene.spec`` is still the
    submodule (the import system binds submodules into that shared namespace)."""
    from chaplygin_nd.api import simulate

    f = _types.FunctionType(simulate.__code__, simulate.__globals__, simulate.__name__,
                            simulate.__defaults__, simulate.__closure__)
    f.__kwdefaults__ = simulate.__kwdefaults__
    f.__doc__ = simulate.__doc__
    f.__qualname__, f.__module__ = simulate.__qualname__, simulate.__module__
    f.__annotations__ = simulate.__annotations__
    f.__dict__ = module.__dict__  # type: ignore[misc]  # the subpackage's namespace
    return f


class _Package(_types.ModuleType):
    """This package's class: when the import system binds the subpackage ``simulate`` here, the
    attribute becomes the notebook function :func:`chaplygin_nd.api.simulate` sharing the
    subpackage's namespace, so ``chaplygin_nd.simulate(scene)`` and
    ``chaplygin_nd.simulate.scene`` both work whichever was imported first."""

    def __setattr__(self, name, value):
        if name == "simulate" and isinstance(value, _types.ModuleType):
            value = _callable_subpackage(value)
        super().__setattr__(name, value)


_sys.modules[__name__].__class__ = _Package


def __getattr__(name):
    """The notebook API (:mod:`chaplygin_nd.api`), imported on first use."""
    if name == "simulate":
        _importlib.import_module("chaplygin_nd.simulate")  # binds the function (see _Package)
        return globals()["simulate"]
    if name in _API:
        return getattr(_importlib.import_module("chaplygin_nd.api"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    """The public names: the API, the version, the subpackages imported so far, the module's
    dunders; not the private helpers (``_importlib``, ``_Package``, ...)."""
    return sorted({k for k in globals() if not k.startswith("_") or k.endswith("__")} | set(_API))
