# The two quick-start entry points. Each one does all of the set-up itself.
BUILD ?= build
CMAKE_FLAGS ?=
# The benchmarks' build: profile-guided as well (cmake/pgo.cmake), without tests.
BENCH_BUILD ?= build-bench

.PHONY: setup configure build run test bench clean

setup:
	bash scripts/setup.sh

configure: setup
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD)

# Builds only the program, not the tests: the quickest way to a running head.
run: configure
	cmake --build $(BUILD) --target facectl
	./$(BUILD)/firmware-host/facectl run

# Two tests at a time on this 2-core machine, as the sanitizer suite runs
# (scripts/sanitize.sh): the real-time loop's tests hold their deadlines
# beside another test even instrumented. The QEMU guest test runs alone
# (RUN_SERIAL, tests/CMakeLists.txt): its emulated CAN drives keep 100 ms
# heartbeats and watchdogs that a loaded host makes it miss.
TEST_JOBS ?= $(shell nproc)
test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(TEST_JOBS)

bench: setup
	cmake -S . -B $(BENCH_BUILD) -G Ninja -DFACECTL_PGO=ON -DFACECTL_BUILD_TESTS=OFF $(CMAKE_FLAGS)
	cmake --build $(BENCH_BUILD)
	./$(BENCH_BUILD)/firmware-host/facectl bench simulate
	./$(BENCH_BUILD)/firmware-host/facectl bench loop

clean:
	rm -rf $(BUILD) $(BENCH_BUILD)
