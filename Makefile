# HydroSync: `make demo` installs everything and runs the main job; `make test` runs the tests.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.hydrosync-installed
OUT ?= demo-output

.PHONY: install demo test bench lint gui screenshot screenshots clean

$(STAMP): pyproject.toml scripts/install-system-packages.sh
	bash scripts/install-system-packages.sh
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test]"
	$(BIN)/python -m hydrosync_core.warmup
	touch $(STAMP)

# Qt translation catalogues: resources/i18n/*.ts compiled to .qm (the GUI compiles a
# missing or older one itself, into the temporary folder).
QM := $(patsubst %.ts,%.qm,$(wildcard resources/i18n/*.ts))

%.qm: %.ts $(STAMP)
	$(BIN)/pyside6-lrelease -silent $< -qm $@

install: $(STAMP) $(QM)

demo: $(STAMP)
	$(BIN)/hydrosync demo --out $(OUT)

# The OpenGL views need a real X server: they run first under Xvfb (skipped without xvfb-run),
# then the whole suite runs headless (offscreen Qt, where GL views show their 2-D fallback).
test: $(STAMP)
	if command -v xvfb-run >/dev/null; then \
	  QT_QPA_PLATFORM=xcb xvfb-run -a $(BIN)/python -m pytest -q -m gl; \
	fi
	QT_QPA_PLATFORM=offscreen $(BIN)/python -m pytest -q -n auto --dist loadgroup

bench: $(STAMP)
	$(BIN)/python benchmarks/run_all.py

lint: $(STAMP)
	$(BIN)/ruff check .

# docs/ screenshots from the layout harness's artifact (checked as they are shot).
screenshots: $(STAMP)
	$(BIN)/python scripts/docs_screenshots.py

gui: $(STAMP)
	$(BIN)/hydrosync-gui $(OUT)/demo.h5

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache
