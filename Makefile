# Every target installs what it needs into its own .venv first.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
CLI := $(VENV)/bin/chaplygin
STAMP := $(VENV)/.installed

.PHONY: setup verify test generate bench mutate mutate-derivations clean

setup: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

## verify: run every proof, print the ledger, write VERIFICATION.md, verification.json and
## docs/claim-graph.svg, and fail on a `fails` row, an error, an `open` row without reason, a
## finding without a kind, or a stale generated/. `make verify SEED=N` draws every seeded point
## from seed N (default: chaplygin_nd.symbolic.points.DEFAULT_SEED); the seed is recorded in both reports.
SEED ?=
verify: setup
	$(CLI) verify --check-generated $(if $(SEED),--seed $(SEED))

## test: the pytest suite (engine, proofs, kernels against mpmath, hard cases).
test: setup
	$(PY) -m pytest -q

## mutate: mutation testing of every printed formula (one-symbol AST mutants, each run against the
## rows that reach it); writes mutation.json and ledger/reach.json; fails on a surviving mutant.
mutate: setup
	$(CLI) mutate

## mutate-derivations: the same one-token mutants applied to the derivations of symbolic/ (run
## against the rows that reach them) and to runtime/ (run against its tests); writes
## mutation-derivations.json. `make mutate-derivations MUTATE_ARGS="--sample 150"` draws a seeded sample.
mutate-derivations: setup
	$(PY) -m chaplygin_nd.ledger.mutate_derivations $(MUTATE_ARGS)

## generate: rewrite generated/ from the derived (proved) expressions.
generate: setup
	$(CLI) generate

## bench: accuracy-versus-time and throughput benchmarks (never part of the tests);
## `make bench BENCH_ARGS=--cold` starts from empty caches, `BENCH_ARGS="--quick"` is a smoke run.
bench: setup
	$(CLI) bench $(BENCH_ARGS)

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache
