"""The code generator: verified SymPy expressions written into ``generated/`` (``make generate``).

``kernels``: vectorised NumPy kernels with CSE, a banner, the claim ids and a source hash;
``builders``: straight-line expression builders over any arithmetic (heyoka, mpmath, NumPy);
``emit/``: one module per family of kernels, naming which derived expression becomes which
kernel. Nothing here derives a formula.
"""
