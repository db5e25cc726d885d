# machdyn — the two commands a new user needs: `make demo` and `make test`.
# Both install missing Debian packages (scripts/install-deps.sh), configure with CMake + Ninja and build.

BUILD_RELEASE := build/release
BUILD_TEST    := build/test
JOBS          ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: demo test deps deps-browser build-release build-test bench package clean

deps:
	@bash scripts/install-deps.sh

# Chromium for the browser test of the HTML report (large; without it that test is skipped).
deps-browser:
	@MACHDYN_WITH_CHROMIUM=1 bash scripts/install-deps.sh

build-release: deps
	@cmake -S . -B $(BUILD_RELEASE) -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD_RELEASE) -j $(JOBS)

build-test: deps
	@cmake -S . -B $(BUILD_TEST) -G Ninja -DCMAKE_BUILD_TYPE=Release -DMACHDYN_WERROR=ON >/dev/null
	@cmake --build $(BUILD_TEST) -j $(JOBS)

demo: build-release
	@$(BUILD_RELEASE)/apps/machdyn/machdyn demo

test: build-test
	@cd $(BUILD_TEST) && ctest --output-on-failure -j $(JOBS)
	@command -v chromium >/dev/null 2>&1 || echo "note: chromium is not installed, so the browser test of the HTML report was SKIPPED (make deps-browser installs it)"

bench: build-release
	@bash bench/run.sh $(BUILD_RELEASE)

# A Debian package (CPack) with the CLI, the library, the headers, the CMake package and the Python module.
package: build-release
	@cd $(BUILD_RELEASE) && cpack -G DEB
	@ls $(BUILD_RELEASE)/package/*.deb

clean:
	rm -rf build
