# rollspring: two commands.
#   make demo   set up .venv with what the demo needs (the core and the report extra), analyse
#               and simulate the default system (the paper's hoop and cylinder) and write its
#               report (build/demo/report.html)
#   make test   set up .venv with everything (the test extra: every extra and the test tools)
#               and run the whole test suite
#   rollspring serve   (after either) the interactive page at http://127.0.0.1:8000/
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
# uv installs the pinned packages (it downloads in parallel and compiles no bytecode up front:
# a fresh `make demo` installs in about 7 s where pip took about 30 s); pinned in constraints.txt
PIP    := $(BIN)/uv pip install --quiet --python $(BIN)/python -c constraints.txt
# one stamp per install: the demo's (core + report) and the full one (test: every extra)
DEMO_STAMP := $(VENV)/.installed-demo
STAMP      := $(VENV)/.installed

.PHONY: demo test bench clean system-packages bench-packages

# Debian packages the tests drive: Chromium (report/browser tests, PDF) and a LaTeX engine
# (the derivations' LaTeX documents are compiled). Installed only when missing.
SYSTEM_PACKAGES := chromium texlive-latex-base
system-packages:
	@if command -v chromium >/dev/null && command -v pdflatex >/dev/null; then :; \
	elif command -v apt-get >/dev/null && [ "$$(id -u)" = 0 ]; then \
		echo "installing Debian packages: $(SYSTEM_PACKAGES)"; \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $(SYSTEM_PACKAGES) >/dev/null; \
	else echo "missing: $(SYSTEM_PACKAGES) (install them with your package manager)" >&2; exit 1; fi

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# uv, pinned, into the venv (a rule of its own: a venv made before uv was used gets it too)
$(BIN)/uv: | $(BIN)/python
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -c constraints.txt uv

$(DEMO_STAMP): pyproject.toml constraints.txt | $(BIN)/uv
	$(PIP) -e ".[report]"
	touch $(DEMO_STAMP)

$(STAMP): pyproject.toml constraints.txt | $(BIN)/uv
	$(PIP) -e ".[test]"
	touch $(STAMP) $(DEMO_STAMP)

# the page's front-end libraries (uPlot; axe-core for the tests, not served), pinned in
# package.json / package-lock.json
WEB_STATIC := src/rollspring/web/static
WEB_STAMP  := $(WEB_STATIC)/node_modules/.installed
$(WEB_STAMP): $(WEB_STATIC)/package.json $(WEB_STATIC)/package-lock.json
	npm ci --prefix $(WEB_STATIC) --no-audit --no-fund --loglevel=error
	touch $(WEB_STAMP)

demo: $(DEMO_STAMP)
	$(BIN)/rollspring analyze hoop-cylinder
	$(BIN)/rollspring simulate hoop-cylinder --duration 10 --rtol 1e-10
	$(BIN)/rollspring report hoop-cylinder -o build/demo/report.html

# the hygiene checks (pyproject.toml: [tool.ruff], [tool.mypy], [tool.importlinter]): ruff's
# lint and format check, mypy on the files it configures (strict on model, physics, analysis,
# simulate) and the import-linter contracts (the layers; no SymPy/Matplotlib/pandas/IPython in
# physics and simulate)
.PHONY: lint
lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	$(BIN)/mypy
	$(BIN)/lint-imports

# the hygiene checks, every test, and the documentation site built with warnings as errors
# (its examples run)
test: $(STAMP) lint $(WEB_STAMP) system-packages docs
	HYPOTHESIS_PROFILE=$${HYPOTHESIS_PROFILE:-ci} $(BIN)/python -m pytest

# the web benchmark's load generator (Debian's wrk), installed only when missing
bench-packages:
	@if command -v wrk >/dev/null; then :; \
	elif command -v apt-get >/dev/null && [ "$$(id -u)" = 0 ]; then \
		echo "installing Debian packages: wrk"; \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends wrk >/dev/null; \
	else echo "missing: wrk (install it with your package manager)" >&2; exit 1; fi

# benchmarks (bench/README.md): installs the bench extra (MuJoCo, pymunk), runs every bench/bench_*.py
bench: $(STAMP) $(WEB_STAMP) system-packages bench-packages
	$(PIP) -e ".[test,bench]"
	@for script in bench/bench_*.py; do echo "== $$script"; $(BIN)/python $$script || exit 1; done

# the documentation site (docs/README.md): the docs extra, and MathJax from npm (pinned in
# docs/package-lock.json) so the site renders math without a CDN; warnings are errors
.PHONY: docs
DOCS_STAMP     := $(VENV)/.docs-installed
DOCS_NPM_STAMP := docs/node_modules/.installed
$(DOCS_STAMP): pyproject.toml constraints.txt | $(BIN)/uv
	$(PIP) -e ".[docs]"
	touch $(DOCS_STAMP)
$(DOCS_NPM_STAMP): docs/package.json docs/package-lock.json
	npm ci --prefix docs --no-audit --no-fund --loglevel=error
	touch $(DOCS_NPM_STAMP)
docs: $(DOCS_STAMP) $(DOCS_NPM_STAMP)
	$(BIN)/sphinx-build -W --keep-going -q -b html docs build/docs/html

clean:
	rm -rf $(VENV) .pytest_cache .hypothesis .ruff_cache .mypy_cache build src/*.egg-info \
		$(WEB_STATIC)/node_modules \
		docs/node_modules docs/_generated docs/gallery docs/tutorial
