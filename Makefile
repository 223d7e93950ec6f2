# MeshIK: the README's two commands (`make demo`, `make test`) and helpers.
# Every target installs what it needs first (scripts/setup.sh) and is quick when current.
SHELL := /bin/bash
ROOT := $(abspath .)
PY := $(ROOT)/.venv/bin/python
BUILD := build
BUILD_ASAN := build-asan
BUILD_PORTABLE := build-portable
BUILD_WHEEL := build-wheel
VERSION = $(shell sed -n 's/^__version__ = "\(.*\)"$$/\1/p' pipeline/meshik/__init__.py)
JOBS ?= $(shell nproc)
CMAKE_ARGS ?=

.PHONY: all setup build test test-cpp test-asan test-portable test-python demo bench plugin gui-check clean dist wheel sdist plugin-zip

all: build

setup:
	@scripts/setup.sh all
	@scripts/fetch_meshlab_source.sh >/dev/null

# Configure once (re-configured by CMake itself when its inputs change), then build incrementally.
$(BUILD)/build.ninja: | setup
	cmake -S . -B $(BUILD) -G Ninja -DPython_EXECUTABLE=$(PY) $(CMAKE_ARGS)

build: setup $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

$(BUILD_ASAN)/build.ninja: | setup
	cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DMESHIK_SANITIZE=address,undefined \
	  -DMESHIK_BUILD_PYTHON=OFF -DMESHIK_BUILD_PLUGIN=OFF -DMESHIK_BUILD_BENCH=OFF

test-cpp: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-asan: setup $(BUILD_ASAN)/build.ninja
	cmake --build $(BUILD_ASAN) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --test-dir $(BUILD_ASAN) --output-on-failure -j $(JOBS)

# The core as a portable binary (MESHIK_NATIVE_ARCH=OFF: SSE2 baseline, batch loops picked at
# load time), the build the plugin README recommends for sharing: its own vector widths differ.
$(BUILD_PORTABLE)/build.ninja: | setup
	cmake -S . -B $(BUILD_PORTABLE) -G Ninja -DMESHIK_NATIVE_ARCH=OFF \
	  -DMESHIK_BUILD_PYTHON=OFF -DMESHIK_BUILD_PLUGIN=OFF -DMESHIK_BUILD_BENCH=OFF

test-portable: setup $(BUILD_PORTABLE)/build.ninja
	cmake --build $(BUILD_PORTABLE) -j $(JOBS)
	ctest --test-dir $(BUILD_PORTABLE) --output-on-failure -j $(JOBS)

# The Blender reader test needs bpy in its own venv (about 1 GB): installed here, not by `make demo`.
# The wheel is built first: tests/python/test_wheel_install.py installs it into a brand-new venv.
test-python: build wheel
	@scripts/setup.sh blender
	MESHIK_WHEEL_REQUIRED=1 $(PY) -m pytest -q tests/python

test: test-cpp test-asan test-portable test-python

demo: build
	$(PY) -m meshik.demo --out demo_output

bench: build
	$(PY) bench/run_bench.py

plugin: setup $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS) --target plugins

# The plugin in a real MeshLab GUI under Xvfb (builds that GUI the first time, ~10 minutes).
# PRECISION=float (MeshLab releases) or double (as pymeshlab).
PRECISION ?= float
gui-check: build
	BUILD=$(abspath $(BUILD)) JOBS=$(JOBS) scripts/gui_check.sh $(PRECISION)

# make dist: in dist/, the wheel repaired by auditwheel (the external shared libraries bundled, a manylinux
# tag), the sdist, and the MeshLab plugins (float and double) as a zip with install instructions.
dist: wheel sdist plugin-zip

# The wheel's CMake build stays in $(BUILD_WHEEL) (incremental, ccache), its core without -march=native.
wheel: setup
	rm -rf dist/raw dist/meshik-$(VERSION)-*.whl
	$(PY) -m pip wheel --no-build-isolation --no-deps -q -w dist/raw -C build-dir=$(BUILD_WHEEL) .
	PATH="$(ROOT)/.venv/bin:$$PATH" $(PY) -m auditwheel repair -w dist dist/raw/meshik-$(VERSION)-*.whl
	rm -rf dist/raw

sdist: setup $(BUILD)/build.ninja
	rm -f dist/meshik-$(VERSION).tar.gz
	$(PY) -m build --sdist --no-isolation -o dist .

plugin-zip: plugin
	$(PY) scripts/plugin_zip.py $(BUILD) dist $(VERSION)

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD_PORTABLE) $(BUILD_WHEEL) dist demo_output
