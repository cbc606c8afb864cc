"""The exact engines: every symbolic verdict of the ledger is decided here.

``identity`` (a zero test after clearing denominators, reduced modulo $\\|\\gamma\\|^2 - 1$, and
its random half at seeded rational points) runs on SymPy (``sympy_fraction``) and again on FLINT
(``flint_engine``, ``flint_matrix``); ``points`` draws the seeded rational points (on
$S^{n-1}$ by inverse stereographic projection); ``counterexample`` renders a failed identity;
``mpmath_eval`` evaluates derived expressions at high precision for the kernel tests. Nothing
here builds a formula of the paper.
"""
