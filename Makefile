# The two quick-start entry points. Each one does all of the set-up itself.
BUILD ?= build
CMAKE_FLAGS ?=

.PHONY: setup build run test bench clean

setup:
	bash scripts/setup.sh

build: setup
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS)
	cmake --build $(BUILD)

run: build
	./$(BUILD)/firmware-host/facectl run

test: build
	ctest --test-dir $(BUILD) --output-on-failure

bench: build
	./$(BUILD)/firmware-host/facectl bench loop

clean:
	rm -rf $(BUILD)
