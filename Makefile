# machdyn — the two commands a new user needs: `make demo` and `make test`.
# Both install missing Debian packages (scripts/install-deps.sh), configure with CMake + Ninja and build.

BUILD_RELEASE := build/release
BUILD_TEST    := build/test
JOBS          ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: demo test deps build-release build-test bench clean

deps:
	@bash scripts/install-deps.sh

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

bench: build-release
	@bash bench/run.sh $(BUILD_RELEASE)

clean:
	rm -rf build
