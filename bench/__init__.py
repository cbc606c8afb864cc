"""Benchmarks (``make bench`` = ``chaplygin bench``): throughput of the kernels and the
accuracy-versus-time diagrams. Never timed tests: the test suite asserts correctness only."""
