"""NumPy kernels and expression builders emitted by symbolic/codegen.py (do not edit; `make generate`)."""
