"""NumPy kernels emitted by symbolic/codegen.py (do not edit; `make generate`)."""
