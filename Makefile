# Road Sign Inventory: the two commands of the README, and a few helpers.
#   make demo   set everything up, run the chain on the bundled sample
#   make test   set everything up, run all tests
#   make lint   ruff (pycodestyle, pyflakes, isort, pep8-naming) and mypy on core/
VENV ?= .venv
PY := $(VENV)/bin/python
# make test's pytest-xdist workers, each given whole test files (0: none, the tests run in-process)
TEST_WORKERS ?= 2
export QT_QPA_PLATFORM := offscreen
export PROJ_DATA := /usr/share/proj

.PHONY: setup test test-core lint demo zip i18n clean

setup:
	bash scripts/setup.sh

test: setup
	$(PY) -m pytest -n $(TEST_WORKERS) --dist loadfile

test-core: setup
	$(PY) -m pytest -n $(TEST_WORKERS) --dist loadfile tests/core

lint: setup
	$(VENV)/bin/ruff check .
	$(VENV)/bin/mypy

demo: setup
	$(PY) scripts/demo.py

zip:
	$(PY) scripts/package.py

# translations (i18n/README.md): pylupdate5 and the core's texts into i18n/*.ts, lrelease to
# the .qm, then list what is left to translate (fails while anything is)
i18n:
	python3 scripts/i18n.py update
	python3 scripts/i18n.py compile
	python3 scripts/i18n.py check

clean:
	rm -rf demo_out build dist
