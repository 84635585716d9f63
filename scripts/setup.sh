#!/usr/bin/env bash
# Installs the Debian 12 packages mjarm needs, skipping those already present, then makes the
# project's virtual environment with the pinned MuJoCo and Python packages (setup_venv.sh).
# Idempotent.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  # `pip install .` builds with Ninja (scikit-build-core takes it from PyPI when it is missing)
  ninja-build
  libeigen3-dev libtinyxml2-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # scene files (YAML, and JSON through the same parser)
  libyaml-cpp-dev
  # render room (part of the default build, tested headless): EGL + desktop GL headers, Mesa's
  # EGL vendor and software rasteriser (no GPU, no display), PNG frames, ffmpeg for MP4 video
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libpng-dev ffmpeg
  # interactive viewer (part of the default build): GLFW windows; its test runs under Xvfb
  libglfw3-dev xvfb xauth
  # plots of a recording (`mjarm plot`, the demo)
  gnuplot-nox
  # the fuzz targets (scripts/fuzz.sh, part of `make test`): clang and its libFuzzer runtime
  clang libclang-rt-14-dev
  # the project's virtual environment (MuJoCo, NumPy, pybind11, pytest from PyPI, pinned) on
  # Debian's /usr/bin/python3, whose headers the Python extension compiles against
  python3-venv python3-dev
)

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

bash scripts/setup_venv.sh
