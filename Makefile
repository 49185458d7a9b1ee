# subfab: the two commands of the README, and what they need.
#   make run   set up, build the `subfab` command only (Release), decompose a
#              bundled example (data/moai.obj, thesis height 0.225) into
#              out/example and validate the result
#   make test  set up, check that module dependencies point down, build
#              everything, run the whole test suite (ctest), then the reader
#              and repair tests (the bad-input corpus) again under
#              AddressSanitizer + UBSan
SHELL := /bin/bash
BUILD_DIR ?= build
ASAN_DIR ?= build-asan
JOBS ?= $(shell nproc)
EXAMPLE ?= data/moai.obj
EXAMPLE_HEIGHT ?= 0.225
OUT ?= out/example

.PHONY: all setup configure build build-app run test test-fast test-asan check-layering clean

all: build

setup:
	@bash scripts/setup.sh

configure: setup
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

build-app: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target subfab_app

run: build-app
	@./$(BUILD_DIR)/subfab decompose $(EXAMPLE) -o $(OUT) --max-height $(EXAMPLE_HEIGHT)
	@./$(BUILD_DIR)/subfab validate $(EXAMPLE) $(OUT) --quiet

test-fast: build
	@ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

# The sanitizer build: only what `subfab repair` needs (SUBFAB_REPAIR_ONLY:
# core, mesh, checks, 3 geometry sources, repair; test_core, test_mesh,
# test_repair with the whole bad-input corpus), at -O1 -g1 to keep CI's cold
# build short.
test-asan: setup
	@cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
		-DSUBFAB_REPAIR_ONLY=ON -DSUBFAB_SANITIZE=ON >/dev/null
	@cmake --build $(ASAN_DIR) -j $(JOBS)
	@ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		ctest --test-dir $(ASAN_DIR) --output-on-failure -j $(JOBS)

check-layering:
	@python3 scripts/check_layering.py

test: check-layering test-fast test-asan

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR) out
