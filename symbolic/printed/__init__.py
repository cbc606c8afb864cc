"""The paper's formulas as printed, transcribed literally, one module per section (DESIGN rule 1).

Only `proofs/` may import this package; derivations in `symbolic/` never do (tests enforce it).
Each function carries its claim id and the LaTeX source line of the paper in its docstring.
"""
