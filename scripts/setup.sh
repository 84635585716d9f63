#!/usr/bin/env bash
# Installs the Debian 12 packages mjarm needs, skipping those already present, then makes the
# project's virtual environment with the pinned MuJoCo and Python packages (setup_venv.sh).
# Idempotent. `setup.sh demo` installs only what building and running the CLI needs (Node.js and
# npm included: the demo writes a replay page); `demo-build` the part of it the build needs, with
# the environment, and `demo-run` the rest, the programs the demo runs (`make demo` installs those
# while it builds); without an argument, everything (`make test`: the tests, the Python extension,
# the fuzzers).
set -euo pipefail

profile="${1:-all}"
case "$profile" in
  demo|demo-build|demo-run|all) ;;
  *) echo "usage: scripts/setup.sh [demo|demo-build|demo-run]" >&2; exit 2 ;;
esac

# the library and the CLI
packages=(
  build-essential cmake pkg-config
  # `make demo` builds with Ninja, and `pip install .` too (scikit-build-core takes it from PyPI
  # when it is missing)
  ninja-build
  libeigen3-dev libtinyxml2-dev libcli11-dev nlohmann-json3-dev
  # scene and sweep files (YAML, and JSON through the same parser)
  libyaml-cpp-dev
  # sampling-based joint-space planning (mjarm::OmplPlanner, `mjarm plan --planner ompl:…`)
  libompl-dev
  # a sweep's results (mjarm sweep): SQLite
  libsqlite3-dev
  # render room (part of the default build, tested headless): EGL + desktop GL headers, PNG frames
  libegl-dev libgl-dev libopengl-dev libpng-dev
  # interactive viewer (part of the default build): GLFW windows
  libglfw3-dev
  # the live web view's HTTP and WebSocket server (`mjarm view --web`): Boost.Beast, headers only
  libboost-dev
  # the project's virtual environment (MuJoCo, NumPy, pybind11, pytest from PyPI, pinned) on
  # Debian's /usr/bin/python3
  python3-venv
)
# what the CLI runs but its build does not need (ffmpeg and gnuplot alone bring 157 of the 321
# packages a bare Debian 12 lacks for the demo): Mesa's EGL vendor and software rasteriser (no
# GPU, no display), ffmpeg for MP4 video, gnuplot for the plots of a recording
run_packages=(libegl-mesa0 libgl1-mesa-dri ffmpeg gnuplot-nox)
case "$profile" in
  demo-build) ;;
  demo-run) packages=("${run_packages[@]}") ;;
  *) packages+=("${run_packages[@]}") ;;
esac
if [ "$profile" = all ]; then
  packages+=(
    libgtest-dev libgmock-dev libbenchmark-dev
    # the viewer's tests run under Xvfb
    xvfb xauth
    # the sanitized test build and the fuzz targets (scripts/fuzz.sh, part of `make test`): clang
    # and its sanitizer and libFuzzer runtimes
    clang libclang-rt-14-dev
    # the code's format (`make format`, `git clang-format` before a commit: .clang-format)
    clang-format
    # make test's wheel check reuses the sanitized build's objects through the compiler cache
    ccache
    # the Python extension compiles against Debian's python3 headers
    python3-dev
    # a Slurm cluster of one node for the tests of the Slurm path (scripts/slurm_local.sh)
    slurm-wlm munge
    # the replay page's test (tests/web): headless Chromium, driven through its DevTools protocol
    chromium
  )
fi
# the replay page is bundled from npm at build time (web/, MJARM_WEB; the demo writes one):
# Debian's Node.js where no node is on PATH (a node from elsewhere is kept, never installed over),
# and npm, where none is on PATH, from the npm registry (setup_npm.sh, below: Debian's npm package
# would bring about 350 packages with it)
if [ "$profile" != demo-run ] && ! command -v node >/dev/null 2>&1; then
  packages+=(nodejs)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "mjarm setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "mjarm setup: run as root or install sudo" >&2; exit 1; }
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

[ "$profile" = demo-run ] && exit 0
if ! command -v npm >/dev/null 2>&1; then
  bash scripts/setup_npm.sh
fi
bash scripts/setup_venv.sh
