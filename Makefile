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

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD)
