#!/usr/bin/env bash
# Installs the Debian 12 packages mjarm needs, skipping those already present, then makes the
# project's virtual environment with the pinned MuJoCo and Python packages (setup_venv.sh).
# Idempotent. `setup.sh demo` installs only what building and running the CLI needs (`make demo`,
# Node.js and npm included: the demo writes a replay page); without an argument, everything
# (`make test`: the tests, the Python extension, the fuzzers).
set -euo pipefail

profile="${1:-all}"
case "$profile" in
  demo|all) ;;
  *) echo "usage: scripts/setup.sh [demo]" >&2; exit 2 ;;
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
  # render room (part of the default build, tested headless): EGL + desktop GL headers, Mesa's
  # EGL vendor and software rasteriser (no GPU, no display), PNG frames, ffmpeg for MP4 video
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libpng-dev ffmpeg
  # interactive viewer (part of the default build): GLFW windows
  libglfw3-dev
  # the live web view's HTTP and WebSocket server (`mjarm view --web`): Boost.Beast, headers only
  libboost-dev
  # plots of a recording (`mjarm plot`, the demo)
  gnuplot-nox
  # the project's virtual environment (MuJoCo, NumPy, pybind11, pytest from PyPI, pinned) on
  # Debian's /usr/bin/python3
  python3-venv
)
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
if ! command -v node >/dev/null 2>&1; then
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

if ! command -v npm >/dev/null 2>&1; then
  bash scripts/setup_npm.sh
fi
bash scripts/setup_venv.sh
