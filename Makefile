# Set-up commands: each creates or reuses .venv and installs what it needs.
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed

.PHONY: run test lint bench docs clean

$(PY):
	python3 -m venv $(VENV)

$(STAMP): pyproject.toml | $(PY)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -e ".[dev]"
	touch $(STAMP)

run: $(STAMP)
	MPLBACKEND=Agg $(PY) -m rotorsim run models/default.toml

test: $(STAMP)
	MPLBACKEND=Agg $(PY) -m ruff check rotorsim tests benchmarks examples
	$(PY) -m mypy
	# two workers (pytest-xdist), each test module kept on one worker so that its
	# module-scoped fixtures are built once; one BLAS thread per worker
	OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MPLBACKEND=Agg $(PY) -m pytest -q -n 2 --dist loadscope

lint: $(STAMP)
	$(PY) -m ruff check rotorsim tests benchmarks examples
	$(PY) -m mypy

docs: $(STAMP)
	$(PY) -m mkdocs build --strict

bench: $(STAMP)
	$(PY) benchmarks/run_all.py

clean:
	rm -rf $(VENV) results
