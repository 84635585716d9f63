# The two commands a newcomer runs: `make demo` and `make test`. Everything else is a helper.
BUILD   ?= build
JOBS    ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all setup build demo test sanitize bench format tidy clean

all: build

setup:
	@bash scripts/setup.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: setup $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# the main job: an end-to-end run of what mjarm does
demo: build
	./$(BUILD)/mjarm demo

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600

# the whole suite once more under AddressSanitizer + UndefinedBehaviorSanitizer
sanitize: setup
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DMJARM_SANITIZE=ON -DCMAKE_CXX_FLAGS=-O1
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/scripts/lsan.supp UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) --timeout 900 -LE install

bench: setup
	cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DMJARM_BUILD_BENCH=ON
	cmake --build build-bench -j $(JOBS)
	@for b in build-bench/bench_*; do echo "== $$b"; $$b --benchmark_min_time=0.2; done

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) build-asan build-bench
