# The README's two commands: `make run` and `make test`. Each installs what is missing first.
# `make` (= `make build`) only configures and builds.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# `make test` also runs the sanitizer build and the fuzz smoke runs (docs/reliability.md).
ASAN_DIR ?= build-asan
FUZZ_DIR ?= build-fuzz
TSAN_DIR ?= build-tsan
FUZZ_SECONDS ?= 15
# `make deb` builds the Debian package in a build configured for /usr.
DEB_DIR ?= build-deb
# -O1: sanitized code stays fast and its stack traces readable. No -DNDEBUG: asserts are on.
# Unity builds: the library and the tools compiled as a few large files, which takes about half
# the time; `make test` builds them four times (the test programs opt out: tests/CMakeLists.txt).
comma := ,
SANITIZE_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
  -DMOVSEG_SANITIZE=address,undefined -DMOVSEG_BUILD_BENCH=OFF -DCMAKE_UNITY_BUILD=ON

.PHONY: all build deps run test test-sanitize test-fuzz test-tsan deb test-deb bench long-run clean

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
	@$(MAKE) --no-print-directory test-deb
	@$(MAKE) --no-print-directory test-fuzz
	@$(MAKE) --no-print-directory test-sanitize
	@$(MAKE) --no-print-directory test-tsan

# The Debian package (CPack): library, headers, CMake package, pkg-config, CLI, Python module,
# GStreamer element; dependencies from dpkg-shlibdeps. Written to $(DEB_DIR)/movseg_*.deb. A unity
# build, as the sanitized ones: half the compile time (docs/reliability.md).
deb: deps
	@cmake -S . -B $(DEB_DIR) -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr -DCMAKE_UNITY_BUILD=ON \
	  -DMOVSEG_BUILD_TESTS=OFF -DMOVSEG_BUILD_BENCH=OFF >/dev/null
	@cmake --build $(DEB_DIR) -j $(JOBS)
	@cd $(DEB_DIR) && rm -f movseg_*.deb && cpack -G DEB >/dev/null && ls movseg_*.deb

# The package unpacked into a scratch root (dpkg -x): its CLI, Python module and element run.
test-deb: deb
	@bash tests/install/deb_test.sh $(DEB_DIR)/movseg_*.deb

# The whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer; the first
# report aborts its test.
test-sanitize: deps
	@echo "test-sanitize: ASan + UBSan build in $(ASAN_DIR)"
	@cmake -S . -B $(ASAN_DIR) $(SANITIZE_FLAGS) >/dev/null
	@cmake --build $(ASAN_DIR) -j $(JOBS)
	@cd $(ASAN_DIR) && ASAN_OPTIONS=halt_on_error=1:detect_leaks=1 \
	  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ctest --output-on-failure -j $(JOBS)

# ThreadSanitizer on the tests that run threads of movseg's own: Segmenters on concurrent threads,
# StreamSegmenters on two threads, a decoder stopped from another thread, and the CLI's runs
# in-process (one stream on two threads, several inputs at once). OpenCV runs on the calling
# threads there (tests/test_support.cc): TSan cannot see the hand-offs of its thread pool (TBB,
# not instrumented) and takes them for races. Only those tests run: the rest of the suite starts
# no thread of movseg's, and the sanitizer build above covers it. tests/tsan.supp: a lock-order
# inversion inside GDAL, an OpenCV codec dependency (docs/reliability.md).
TSAN_TESTS = Determinism.TwoSegmenters*:VideoDecoder.AStopFlag*:EveryMethod/Stream.*_2threads:SegmentRuns.*:BackgroundSubtractor.ThreadsSharing*
test-tsan: deps
	@echo "test-tsan: ThreadSanitizer build in $(TSAN_DIR)"
	@cmake -S . -B $(TSAN_DIR) $(subst address$(comma)undefined,thread,$(SANITIZE_FLAGS)) >/dev/null
	@cmake --build $(TSAN_DIR) -j $(JOBS) --target movseg_thread_tests
	@cd $(TSAN_DIR) && set -f && for pattern in $(subst :, ,$(TSAN_TESTS)); do \
	  tests/movseg_thread_tests --gtest_filter="$$pattern" --gtest_list_tests | grep -q '^  ' || \
	  { echo "test-tsan: no test matches $$pattern"; exit 1; }; done
	@cd $(TSAN_DIR) && TSAN_OPTIONS=halt_on_error=1:suppressions=$(CURDIR)/tests/tsan.supp \
	  tests/movseg_thread_tests --gtest_filter='$(TSAN_TESTS)'

# libFuzzer (clang) on fuzz/'s targets, FUZZ_SECONDS each from the committed corpus.
test-fuzz: deps
	@echo "test-fuzz: libFuzzer + ASan + UBSan build in $(FUZZ_DIR)"
	@cmake -S . -B $(FUZZ_DIR) -DCMAKE_CXX_COMPILER=clang++ $(SANITIZE_FLAGS) -DMOVSEG_FUZZ=ON \
	  -DMOVSEG_BUILD_TESTS=OFF >/dev/null
	@cmake --build $(FUZZ_DIR) -j $(JOBS) --target segmenter_fuzz readers_fuzz video_fuzz
	@bash fuzz/run.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

# Micro-benchmarks (synthetic and DAVIS clips, MOG2 beside), the Python call's overhead, then a
# whole `segment` run against a Python cv2 MOG2 run (skipped without the DAVIS data).
bench: deps
	@$(MAKE) --no-print-directory build
	@$(BUILD_DIR)/bench/movseg_bench --benchmark_min_time=0.5 --benchmark_repetitions=5 \
	  --benchmark_report_aggregates_only=true
	@PYTHONPATH=$(BUILD_DIR)/python /usr/bin/python3 bench/python_overhead.py
	@/usr/bin/python3 bench/whole_run.py --movseg $(BUILD_DIR)/movseg --skip-without-data

# 20,000 frames through one Segmenter; fails when resident memory grows by more than 4 MiB. Then
# README's table of the independent generator's 48 clips, generated and benched (two minutes:
# kept out of `make test`, whose DAVIS tests already take much of its 40-minute budget).
long-run: deps
	@$(MAKE) --no-print-directory build
	@$(BUILD_DIR)/bench/movseg_long_run
	@MOVSEG_LONG_TESTS=1 $(BUILD_DIR)/tests/movseg_tests --gtest_filter='DenseIndependent.*'

clean:
	@rm -rf $(BUILD_DIR) $(ASAN_DIR) $(FUZZ_DIR) $(TSAN_DIR) $(DEB_DIR)
