# Two commands on a fresh machine: `make run` and `make test`.
# Each creates .venv if it is missing and installs the package with pinned dependencies.
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
CORES  ?= 2
STAMP  := $(VENV)/.moorlife-installed

.PHONY: run quick test test-cluster bench report lint config-reference clean-results

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(STAMP): pyproject.toml constraints.txt | $(BIN)/python
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -c constraints.txt -e ".[test]"
	touch $@

## run: the default study at the paper's scale (271,728 h, 1,000 + 225 states, MS1-MS6),
## ending with the HTML report (report.html); with SNAKEMAKE_OUTPUT_CACHE set, the BEM comes
## from (or goes to) that between-workflow cache (--cache, validation/hydro.md section 6)
CACHE_FLAG := $(if $(SNAKEMAKE_OUTPUT_CACHE),--cache)
run: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) $(CACHE_FLAG)
	$(BIN)/snakemake --cores $(CORES) --report report.html

## quick: the same DAG on config/quick.yaml (a few years, tens of states, short records)
quick: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) --configfile config/quick.yaml
	$(BIN)/snakemake --cores $(CORES) --report report-quick.html --configfile config/quick.yaml

## test: the lint, then the whole test suite (unit, peer and workflow tests), on $(CORES) pytest-xdist
## workers, one test file per worker at a time, longest first; the tiny study is built once
## (tests/conftest.py)
test: lint
	$(BIN)/python -m pytest -q -n $(CORES) --dist loadfile --no-loadscope-reorder

## test-cluster: the tiny workflow by both SLURM routes (the profile; a dask-jobqueue cluster),
## compared bit for bit with a local run; starts a one-node SLURM cluster if none answers
## (.ci/slurm.sh, root, Debian) and installs the cluster extra
test-cluster: $(STAMP)
	$(BIN)/python -m pip install --quiet -c constraints.txt -e ".[test,cluster]"
	bash .ci/test_cluster.sh $(BIN)

## bench: peer-library benchmarks (installs the bench extra)
bench: $(STAMP)
	$(BIN)/python -m pip install --quiet -c constraints.txt -e ".[test,bench]"
	for f in benchmarks/bench_*.py; do echo "== $$f"; $(BIN)/python $$f || exit 1; done

## report: the HTML report of the last run
report: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) --report report.html

## lint: ruff (lint and format) on the Python, snakefmt on the Snakefile and rules, snakemake --lint
lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	$(BIN)/snakefmt --check Snakefile workflow/rules
	$(BIN)/snakemake --lint

## config-reference: regenerate the key table of config/README.md from the schema
config-reference: $(STAMP)
	$(BIN)/python -m moorlife.io.reference config/README.md workflow/schemas/config.schema.yaml
