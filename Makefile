# Every target installs what it needs into the one .venv of the checkout first.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
CLI := $(VENV)/bin/chaplygin
STAMP := $(VENV)/.installed

.PHONY: setup verify verify-deep test test-slow typecheck generate bench mutate mutate-derivations clean docs docs-html docs-test

setup: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

## verify: run every proof, print the ledger, write VERIFICATION.md, verification.json and
## docs/claim-graph.svg, and fail on a `fails` row, an error, an `open` row without reason, a
## finding without a kind, or a stale generated/. `make verify SEED=N` draws every seeded point
## from seed N (default: chaplygin_nd.symbolic.exact.points.DEFAULT_SEED); the seed is recorded in both reports.
SEED ?=
verify: setup
	$(CLI) verify --check-generated $(if $(SEED),--seed $(SEED))

## verify-deep: the heavy parts of nine rows, tens of minutes: the first-integral search
## (S6:first-integrals: weight-zero boxes of n = 5 to M-degree 6 and of n = 6, 7; the invariant
## ring of n = 5 to M-degree 8 and of n = 6, 7 to M-degree 6; the symbolic n = 5 proof of the new
## integral), the H_k identities at n = 13, 14 (S6:wedge-integrals) and their ranks (S6:wedge-independence), the torus rows
## (S6:open-reduced-n6, -n7, -n8) on their large drawn ensembles, and the heavy boxes of the
## Hamiltonisation and symmetry-field searches (S7:poisson-n4, -n5, S7:symmetry-fields).
DEEP_ROWS := S6:first-integrals S6:wedge-integrals S6:wedge-independence S6:open-reduced-n6 S6:open-reduced-n7 \
	S6:open-reduced-n8 S7:poisson-n4 S7:poisson-n5 S7:symmetry-fields
verify-deep: setup
	CHAPLYGIN_ND_DEEP=1 $(CLI) prove $(DEEP_ROWS) $(if $(SEED),--seed $(SEED))

## test: the pytest suite (engine, proofs, kernels against mpmath, hard cases) without the checks
## marked `slow`, on every core (pytest-xdist; each worker has its own caches: tests/conftest.py).
## `make test PYTEST_ARGS=-n0` runs it in one process.
## test-slow: the `slow` checks (long exact or high-precision checks, seeded interrupts, the
## cross-checks on the base install, mutants); CI runs both (.ci/run).
PYTEST_ARGS ?= -n auto --dist worksteal
test: setup
	$(PY) -m pytest -q -m 'not slow and not site' $(PYTEST_ARGS)

test-slow: setup
	$(PY) -m pytest -q -m 'slow and not site' $(PYTEST_ARGS)

## typecheck: mypy over the package as Python imports it (.ci/typecheck.py assembles the
## chaplygin_nd namespace outside the tree); the level is [tool.mypy] in pyproject.toml: mypy's
## default (annotated functions checked), the claim scripts and the benchmarks not yet.
typecheck: setup
	$(PY) .ci/typecheck.py

## mutate: mutation testing of every printed formula (one-symbol AST mutants, each run against the
## rows that reach it); writes mutation.json and ledger/reach.json; fails on a surviving mutant.
mutate: setup
	$(CLI) mutate

## mutate-derivations: the same one-token mutants applied to the derivations of symbolic/ (run
## against the rows that reach them) and to runtime/ (run against the tests that call them), two
## workers, cheapest first; writes mutation-derivations.json (every 30 s; --resume goes on).
## `make mutate-derivations MUTATE_ARGS="--sample 150"` draws a seeded sample.
mutate-derivations: setup
	$(CLI) mutate-derivations $(MUTATE_ARGS)

## generate: rewrite generated/ from the derived (proved) expressions.
generate: setup
	$(CLI) generate

## bench: accuracy-versus-time and throughput benchmarks (never part of the tests);
## `make bench BENCH_ARGS=--cold` starts from empty caches, `BENCH_ARGS="--quick"` is a smoke run.
bench: setup
	$(CLI) bench $(BENCH_ARGS)

## docs: the reading site in docs/_build/html (open docs/_build/html/index.html): a page per ledger
## row, generated from verification.json (`make verify` writes it; REPORT=path/to/verification.json
## reads another), built with warnings as errors, its internal links checked, then tested in
## headless Chromium (docs-test).
REPORT ?= verification.json
DOCS_STAMP := $(VENV)/.docs-installed
$(DOCS_STAMP): $(STAMP)
	$(PY) -m pip install --quiet -e '.[test,docs]'
	touch $(DOCS_STAMP)

docs: docs-test

docs-html: $(DOCS_STAMP)
	test -f $(REPORT) || $(CLI) verify
	$(PY) docs/build_pages.py --report $(REPORT)
	$(PY) -m sphinx -b html -W --keep-going -q -c docs docs/_build/src docs/_build/html
	$(PY) docs/check_links.py docs/_build/html

## docs-test: the browser test of the built site (installs Debian's chromium and chromium-driver
## with apt-get when they are missing: needs root, as in CI).
docs-test: docs-html
	command -v chromium >/dev/null && command -v chromedriver >/dev/null || \
	  { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium chromium-driver; }
	$(PY) -m pytest -q -m site tests/test_site_browser.py

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache docs/_build
