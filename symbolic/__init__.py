"""The algebra and the derivations: the only place that builds formulas (SymPy, FLINT).

Grouped by idea; the layers run one way (a module imports only from layers above it, never
from one below; ``tests/test_symbolic_layers.py`` reads every import, deferred ones included):

``printed/``
    The paper's formulas as printed, transcribed literally, one module per section. Only
    ``proofs/`` imports it; no derivation does.
``algebra``, ``mass_operator``
    $\\mathfrak{so}(n)$ as the paper uses it; the matrix of $L_\\gamma$ in any arithmetic.
``exact/``
    The two exact engines and what feeds them: zero tests (SymPy and FLINT), seeded rational
    points, the FLINT matrix type, counterexamples, mpmath evaluation of derived expressions.
The modules directly here
    The definitions and the paper's derivations: the model (eq:M-O, eq:motion-general) and its
    FLINT evaluation, the axisymmetric sphere ($L_\\gamma$, $\\Delta$), the inverse
    $L_\\gamma^{-1}$, vertical momentum ($\\zeta$, $\\chi$), the invariant measure, the
    $O(n^2)$ field, the 4D block form, the physical ball, the 3D sphere.
``reduction/``
    Invariant theory and the reduced fields on $P/SO(n-1)$: $n = 4$ (SO(3)) and $n = 5$ (SO(4));
    the next $n$ is a pair of modules here.
``search/``
    Exact searches over $\\mathbb{Q}$ by an exact sandwich modulo primes: first integrals (and
    the strategies that join them), the sampled field, the known solutions, reconstruction, the
    command line.
``family/``
    The integrals found beyond the paper: the wedge-power family $H_k$ and the sixth integral
    of $n = 5$.
``codegen/``
    The code generator: NumPy kernels and expression builders written into ``generated/``, and
    the emitters that say which derived expression becomes which kernel.
"""
