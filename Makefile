# Road Sign Inventory: the two commands of the README, and a few helpers.
#   make demo   set everything up, run the chain on the bundled sample
#   make test   set everything up, run all tests
VENV ?= .venv
PY := $(VENV)/bin/python
export QT_QPA_PLATFORM := offscreen
export PROJ_DATA := /usr/share/proj

.PHONY: setup test test-core demo zip i18n clean

setup:
	bash scripts/setup.sh

test: setup
	$(PY) -m pytest

test-core: setup
	$(PY) -m pytest tests/core

demo: setup
	$(PY) scripts/demo.py

zip:
	$(PY) scripts/package.py

# translations: merge new strings into i18n/*.ts, build the .qm, list what is untranslated
i18n:
	python3 scripts/i18n.py update
	python3 scripts/i18n.py compile
	python3 scripts/i18n.py check

clean:
	rm -rf demo_out build dist
