"""NumPy kernels and expression builders emitted by symbolic/codegen/kernels.py (do not edit; `make generate`)."""
