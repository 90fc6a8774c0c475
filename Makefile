# The README's two commands: `make run` and `make test`. Each installs what is missing first.
# `make` (= `make build`) only configures and builds.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all build deps run test bench clean

all: build

deps:
	@bash scripts/install-deps.sh

build:
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS)

run: deps
	@$(MAKE) --no-print-directory build
	@$(BUILD_DIR)/movseg demo

test: deps
	@$(MAKE) --no-print-directory build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

bench: deps
	@$(MAKE) --no-print-directory build
	@$(BUILD_DIR)/bench/movseg_bench --benchmark_min_time=0.5 --benchmark_repetitions=5 \
	  --benchmark_report_aggregates_only=true

clean:
	@rm -rf $(BUILD_DIR)
