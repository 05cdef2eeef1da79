# renderaudit: the two commands a new user needs are `make` and `make test` (see README.md).
BUILD ?= build
JOBS ?= $(shell nproc)
EXPERIMENT ?= experiments/quick.toml
OUT ?= outputs/quick

.PHONY: all deps build run test bench format clean

# Installs what is missing, builds, runs the default experiment and leaves its results in $(OUT).
all: run

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

run: build
	$(BUILD)/renderaudit run $(EXPERIMENT) --out $(OUT)

# The whole test suite (CTest). CI runs exactly this.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Benchmarks: side-by-side medians, printed as tables and written as JSON under outputs/bench/.
bench: build
	$(BUILD)/readback_bench --primitives 300 --rounds 3 --json outputs/bench/readback.json
	$(BUILD)/analysis_bench --records 2400000 --platforms 2

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD)
