# The two commands a newcomer runs: `make demo` and `make test`. Everything else is a helper.
BUILD   ?= build
JOBS    ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all setup build demo test check-gcc fuzz release-test bench bench-peers format tidy clean

all: build

setup:
	@bash scripts/setup.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: setup $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# the main job: an end-to-end run of what mjarm does. It needs only the CLI: the packages for it
# (setup.sh demo-build: with Node.js and npm; the programs the demo runs, setup.sh demo-run,
# install while it builds: scripts/build_demo.sh), and a Release build of the library and the CLI alone, one
# unit per room, with the replay page (MJARM_WEB=ON: npm ci of web/package-lock.json into the
# build folder once, then esbuild), so the demo writes out/demo.html beside out/demo.mp4. A build
# folder configured before without the page is switched on once.
DEMO_BUILD ?= build-demo
$(DEMO_BUILD)/CMakeCache.txt:
	cmake -S . -B $(DEMO_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DMJARM_UNITY_BUILD=ON \
	  -DMJARM_BUILD_TESTS=OFF -DMJARM_BUILD_EXAMPLES=OFF -DMJARM_PYTHON=OFF -DMJARM_WEB=ON \
	  $(CMAKE_FLAGS)

demo:
	@bash scripts/setup.sh demo-build
	@$(MAKE) --no-print-directory $(DEMO_BUILD)/CMakeCache.txt
	@grep -q '^MJARM_WEB:STRING=ON$$' $(DEMO_BUILD)/CMakeCache.txt || cmake $(DEMO_BUILD) -DMJARM_WEB=ON
	bash scripts/build_demo.sh $(DEMO_BUILD) $(JOBS)
	./$(DEMO_BUILD)/mjarm demo

# Every test, once, in one build that is both strict (-Werror) and sanitized: ASan + UBSan, clang
# (its build takes three quarters of GCC's CPU time; GCC's build is `make check-gcc`, which CI
# runs after this), Ninja, the library at -O1, the
# code that drives it (CLI, tests, examples) at -O0, one translation unit per room
# (docs/architecture.md, "Build"). Four UBSan checks that ASan or Eigen already make are left out
# (CMakeLists.txt): with them the optimized library compiled in twice the time and the suite ran
# a third slower.
# ASan keeps 64 MB of freed memory in quarantine instead of 256: a use after free is still caught
# behind the last 64 MB freed, and the suite's processes touch fewer fresh pages (a fifteenth less
# system time, a third less memory for a CLI run).
# LeakSanitizer ignores what Mesa, EGL, GLFW and X11 keep for the life of the process
# (scripts/lsan.supp).
TEST_BUILD ?= build-test
# ccache, so the wheel check (tests/wheel) compiles nothing the sanitized tree compiled: its build
# folder sits beside $(TEST_BUILD), and paths below the source tree count relative to it
COMPILER_CACHE = $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR = $(CURDIR)
export CCACHE_NOHASHDIR = true
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:quarantine_size_mb=64 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/scripts/lsan.supp \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

$(TEST_BUILD)/CMakeCache.txt:
	cmake -S . -B $(TEST_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DMJARM_SANITIZE=ON \
	  -DMJARM_WERROR=ON -DCMAKE_CXX_COMPILER=clang++ -DMJARM_UNITY_BUILD=ON \
	  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" $(COMPILER_CACHE) $(CMAKE_FLAGS)

# one CTest job more than cores: a few tests mostly wait (the one-node Slurm cluster, the checks of a
# stuck ffmpeg), and the extra job keeps both cores busy meanwhile (the suite 249.8 s → 241.1 s)
TEST_JOBS ?= $(shell echo $$(( $(JOBS) + 1 )))
test: setup $(TEST_BUILD)/CMakeCache.txt
	cmake --build $(TEST_BUILD) -j $(JOBS)
	cd $(TEST_BUILD) && $(SANITIZER_ENV) ctest --output-on-failure -j $(TEST_JOBS) --timeout 900

# GCC's build of what users build with it (`pip install .`, `make demo`): the library, the CLI and
# the bindings, strict (-Werror), in the wheel check that make test runs with clang
# (tests/wheel/wheel_check.py, kept in build-gcc). CI runs it after make test, so every change
# meets both compilers.
GCC_BUILD ?= build-gcc
check-gcc: setup
	CMAKE_BUILD_PARALLEL_LEVEL=$(JOBS) python3 tests/wheel/wheel_check.py . $(GCC_BUILD) --compiler g++

# The fuzz targets (fuzz/, docs/hardening.md "Fuzzing"): libFuzzer on each file reader. `make test`
# runs each for a bounded, deterministic number of inputs on the programs its build makes; this
# builds them by clang in build-fuzz and runs each for FUZZ_SECONDS, growing the corpora in
# build-fuzz/corpus. FUZZ=name runs one target, FUZZ_PARALLEL=2 two at a time.
FUZZ_SECONDS ?= 600
FUZZ ?=
fuzz: setup
	JOBS=$(JOBS) FUZZ_SECONDS=$(FUZZ_SECONDS) bash scripts/fuzz.sh long $(FUZZ)

# everything in Release (the library, the CLI, the tests and the examples)
release-test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600

bench: setup
	cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DMJARM_BUILD_BENCH=ON
	cmake --build build-bench -j $(JOBS)
	@for b in build-bench/bench_*; do echo "== $$b"; $$b --benchmark_min_time=0.2; done

# peers side by side (docs/benchmarks.md, "Peers side by side"): installs the pinned peers from
# PyPI into the venv (python/requirements-peers.txt), builds the extension and the C++ timing of
# Pinocchio in Release, runs one program per peer
PEERS_BUILD ?= build-peers
PEERS_PYTHON = PYTHONPATH=$(PEERS_BUILD)/python .venv/bin/python
bench-peers: setup
	@bash scripts/setup_venv.sh python/requirements.txt python/requirements-peers.txt
	cmake -S . -B $(PEERS_BUILD) -DCMAKE_BUILD_TYPE=Release -DMJARM_BUILD_PEERS_BENCH=ON \
	  -DMJARM_BUILD_TESTS=OFF -DMJARM_BUILD_EXAMPLES=OFF $(CMAKE_FLAGS)
	cmake --build $(PEERS_BUILD) -j $(JOBS) --target mjarm_python bench_peers_pinocchio mjarm_cli
	$(PEERS_PYTHON) bench/peers/pinocchio_side_by_side.py --bench $(PEERS_BUILD)/bench_peers_pinocchio
	$(PEERS_PYTHON) bench/peers/ruckig_side_by_side.py
	$(PEERS_PYTHON) bench/peers/mink_side_by_side.py
	$(PEERS_PYTHON) bench/peers/toppra_side_by_side.py --mjarm $(PEERS_BUILD)/mjarm

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) $(TEST_BUILD) $(TEST_BUILD)-wheel build-bench $(PEERS_BUILD) build-fuzz $(GCC_BUILD)
