# Every target installs what it needs into its own .venv first.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: setup verify test generate bench clean

setup: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

## verify: run every proof, print the ledger, write VERIFICATION.md and verification.json,
## and fail on a `fails` row, an error, an `open` row without reason, or a stale generated/.
verify: setup
	$(PY) -m proofs --check-generated

## test: the pytest suite (engine, proofs, kernels against mpmath, hard cases).
test: setup
	$(PY) -m pytest -q

## generate: rewrite generated/ from the derived (proved) expressions.
generate: setup
	$(PY) -m symbolic.codegen

## bench: accuracy-versus-time and throughput benchmarks (never part of the tests);
## `make bench BENCH_ARGS=--cold` starts from empty caches, `BENCH_ARGS="--quick"` is a smoke run.
bench: setup
	$(PY) -m bench $(BENCH_ARGS)

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache
