#!/usr/bin/env bash
# `make demo`'s build: the CLI in BUILD (configured by the Makefile), while the packages the demo
# runs but the build does not need (setup.sh demo-run: ffmpeg, gnuplot, Mesa's renderer) install
# beside it — on a bare Debian 12 their apt time is hidden behind the compile. In the background
# only where apt needs no password (root, or sudo without one); otherwise first, in the foreground.
# Usage: build_demo.sh BUILD JOBS
set -euo pipefail
cd "$(dirname "$0")/.."
build=$1
jobs=$2

if [ "$(id -u)" -ne 0 ] && ! sudo -n true 2>/dev/null; then
  bash scripts/setup.sh demo-run
  exec cmake --build "$build" -j "$jobs" --target mjarm_cli
fi

log="$build/setup-run.log"
# a background command ignores Ctrl-C: apt is never cut short mid-install
bash scripts/setup.sh demo-run > "$log" 2>&1 &
installer=$!
set +e
cmake --build "$build" -j "$jobs" --target mjarm_cli
built=$?
wait "$installer"
installed=$?
set -e
if [ "$installed" -ne 0 ]; then
  cat "$log" >&2
  echo "mjarm setup: installing what the demo runs failed (above; $log)" >&2
  exit 1
fi
[ -s "$log" ] && sed -n '1p' "$log"
exit "$built"
