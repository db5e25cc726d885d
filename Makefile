# machdyn — the two commands a new user needs: `make demo` and `make test`.
# Both install missing Debian packages (scripts/install-deps.sh), configure with CMake + Ninja and build.

BUILD_RELEASE := build/release
BUILD_TEST    := build/test
BUILD_ASAN    := build/asan
# The sanitizer build: clang (libFuzzer needs it), -O1 for speed, ASan + UBSan halting on the first report.
ASAN_CXX      ?= $(shell command -v clang++-14 || command -v clang++)
FUZZ_SECONDS  ?= 300
# Precompiled headers in the sanitizer tree (cmake/Precompiled.cmake): clang compiled its batches 4-11 %
# faster with them (the library's 5 %), for 5 s of CPU per header. They cost the compiler cache its hits
# in another checkout of the same sources (the header's absolute paths): ASAN_PCH=OFF for a CI whose
# clone moves and whose cache is warm.
ASAN_PCH      ?= ON
# LeakSanitizer: OpenMPI's own allocations are not ours (the MPI sweep test starts ranks).
SAN_ENV       := ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=0 \
                 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
                 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/fuzz/lsan.supp:print_suppressions=0
# ccache, when installed, keeps rebuilds of the same sources cheap (paths relative to this tree).
CCACHE        := $(if $(shell command -v ccache 2>/dev/null),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR := $(CURDIR)
export CCACHE_NOHASHDIR := 1
JOBS          ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: demo test test-asan fuzz verify deps deps-browser build-release build-test build-asan bench package clean

deps:
	@bash scripts/install-deps.sh

# Chromium (the browser test of the HTML report) is installed by default; MACHDYN_WITH_CHROMIUM=0 opts out.
deps-browser:
	@MACHDYN_WITH_CHROMIUM=1 bash scripts/install-deps.sh

build-release: deps
	@cmake -S . -B $(BUILD_RELEASE) -G Ninja -DCMAKE_BUILD_TYPE=Release -DMACHDYN_TESTS=ON -DMACHDYN_BENCH=ON \
	  -DMACHDYN_PYTHON=ON $(CCACHE) >/dev/null
	@cmake --build $(BUILD_RELEASE) -j $(JOBS)

# The two trees of `make test` compile the library in batches as well (MACHDYN_UNITY_LIBRARY,
# cmake/Unity.cmake); the release tree above, which the benchmarks measure, compiles it file by file.
build-test: deps
	@cmake -S . -B $(BUILD_TEST) -G Ninja -DCMAKE_BUILD_TYPE=Release -DMACHDYN_WERROR=ON -DMACHDYN_BENCH=OFF \
	  -DMACHDYN_UNITY_LIBRARY=ON $(CCACHE) >/dev/null
	@cmake --build $(BUILD_TEST) -j $(JOBS)

# The test suite and the fuzzers under AddressSanitizer + UBSan (clang, -O1, line tables only).
build-asan: deps
	@cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=Asan -DCMAKE_CXX_COMPILER=$(ASAN_CXX) \
	  -DCMAKE_CXX_FLAGS_ASAN="-O1 -gline-tables-only" -DMACHDYN_FUZZ=ON -DMACHDYN_MPI=OFF \
	  -DMACHDYN_PYTHON=OFF -DMACHDYN_PACKAGE_TESTS=OFF -DMACHDYN_BENCH=OFF -DMACHDYN_UNITY_LIBRARY=ON \
	  -DMACHDYN_PCH=$(ASAN_PCH) $(CCACHE) >/dev/null
	@cmake --build $(BUILD_ASAN) -j $(JOBS) --target machdyn_tests machdyn_cli machdyn_campaign \
	  fuzz_model_file fuzz_units fuzz_expression fuzz_gear_spec fuzz_signal_csv fuzz_set_vary

# The demo installs and builds only the library and the CLI it runs (not the tests, benchmarks or
# Python module, nor their packages); `make bench` or `make package` turns them on in the same tree.
demo:
	@bash scripts/install-deps.sh demo
	@cmake -S . -B $(BUILD_RELEASE) -G Ninja -DCMAKE_BUILD_TYPE=Release -DMACHDYN_TESTS=OFF -DMACHDYN_BENCH=OFF \
	  -DMACHDYN_PYTHON=OFF $(CCACHE) >/dev/null
	@cmake --build $(BUILD_RELEASE) -j $(JOBS) --target machdyn_cli
	@$(BUILD_RELEASE)/apps/machdyn/machdyn demo

# The whole suite (release build), then the same suite and each fuzzer for 20 s under ASan + UBSan.
# The release suite runs while the sanitizer tree builds (its output to build/test/suite.log, printed
# when it ends): the suite's tail and the build's links and test discovery each leave a core idle,
# which the other fills. Any part failing fails `make test`, after the parts that could still run.
test: build-test
	@echo "make test: the release suite runs in the background while the sanitizer tree builds ($(BUILD_TEST)/suite.log)"
	@(cd $(BUILD_TEST) && ctest --output-on-failure -j $(JOBS) > suite.log 2>&1) & suite_pid=$$!; \
	  $(MAKE) --no-print-directory build-asan; asan_build=$$?; \
	  wait $$suite_pid; suite=$$?; \
	  echo "---- the release suite ($(BUILD_TEST)/suite.log) ----"; cat $(BUILD_TEST)/suite.log; \
	  command -v chromium >/dev/null 2>&1 || echo "note: chromium is not installed (MACHDYN_WITH_CHROMIUM=0?), so the browser test of the HTML report was SKIPPED (make deps-browser installs it)"; \
	  if [ $$asan_build -ne 0 ]; then echo "make test: the sanitizer tree did not build"; exit 1; fi; \
	  $(MAKE) --no-print-directory test-asan; asan=$$?; \
	  if [ $$suite -ne 0 ]; then echo "make test: the release suite FAILED ($(BUILD_TEST)/suite.log)"; exit 1; fi; \
	  exit $$asan

# Not the browser tests (ReportBrowser.*: Chromium draws the release tree's report and they check its
# figures); the sanitizer run writes the same reports through the report and CLI tests.
test-asan: build-asan
	@cd $(BUILD_ASAN) && $(SAN_ENV) ctest --output-on-failure -j $(JOBS) -E '^ReportBrowser\.'

# Each fuzzer for FUZZ_SECONDS (300 s by default); findings are written to build/asan as crash-*.
fuzz: build-asan
	@cd $(BUILD_ASAN) && cmake -DMACHDYN_FUZZ_SECONDS=$(FUZZ_SECONDS) . >/dev/null && \
	  $(SAN_ENV) ctest --output-on-failure -L fuzz -j $(JOBS); rc=$$?; \
	  cmake -DMACHDYN_FUZZ_SECONDS=20 . >/dev/null; exit $$rc

# The random-model campaign against the brute-force reference simulator (issue 27, tests/reference,
# docs/hybrid.md): MODELS random models (1000) from seed SEED (fresh: the clock) on dopri5 and bdf, in
# JOBS shards; each failing run is shrunk to a minimal model file under build/verify/ (its first lines
# say what differs). `make test` runs the fixed-seed campaign (ctest ReferenceCampaign.*).
MODELS ?= 1000
SEED   ?= $(shell date +%s)
verify: build-test
	@mkdir -p build/verify
	@echo "reference campaign: $(MODELS) models, seed $(SEED), $(JOBS) shards; failures in build/verify/"
	@rc=0; pids=""; for i in $$(seq 0 $$(($(JOBS) - 1))); do \
	  $(BUILD_TEST)/tests/machdyn_campaign --models $(MODELS) --seed $(SEED) --out build/verify \
	    --shard $$i/$(JOBS) > build/verify/shard$$i.log 2>&1 & pids="$$pids $$!"; \
	done; for p in $$pids; do wait $$p || rc=1; done; cat build/verify/shard*.log; exit $$rc

bench: build-release
	@bash bench/run.sh $(BUILD_RELEASE)

# A Debian package (CPack) with the CLI, the library, the headers, the CMake package and the Python module.
package: build-release
	@cd $(BUILD_RELEASE) && cpack -G DEB
	@ls $(BUILD_RELEASE)/package/*.deb

clean:
	rm -rf build
