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
"""

import os

# SymPy's ground types, decided before SymPy is first imported: with python-flint installed,
# SymPy >= 1.13 would silently switch to "flint" and its QQ arithmetic and DomainMatrix would
# then run on FLINT — the second engine (symbolic/flint_engine.py) would share code with the
# first. "gmpy" keeps SymPy's engine its own (README: "Two exact engines").
os.environ.setdefault("SYMPY_GROUND_TYPES", "gmpy")

__version__ = "0.2.0"

__all__ = ["__version__"]
