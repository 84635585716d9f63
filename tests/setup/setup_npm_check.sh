#!/usr/bin/env bash
# scripts/setup_npm.sh into a scratch folder (MJARM_TOOLS): the pinned npm is fetched, checked and
# runs; a second run is quiet; a download that is not the pinned tarball is refused with nothing
# left behind; a folder whose npm was damaged is fetched again.
# Usage: setup_npm_check.sh SOURCE_DIR WORK_DIR
set -euo pipefail
source_dir=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
pinned=$(sed -n 's/^version=//p' "$source_dir/scripts/setup_npm.sh")

source "$(dirname "$0")/script_checks.sh"
run_setup() { run_script "$source_dir/scripts/setup_npm.sh"; }
runs() { [ "$("$MJARM_TOOLS/bin/npm" --version)" = "$pinned" ]; }
absent() { [ ! -e "$MJARM_TOOLS/npm" ] && [ ! -e "$MJARM_TOOLS/bin/npm" ] &&
  [ -z "$(find "$MJARM_TOOLS" -name '.npm-*' 2>/dev/null)" ]; }

# 1. none yet: fetched, and it runs
export MJARM_TOOLS="$work/tools"
run_setup
expect fetch "says what it fetches" said "fetching npm $pinned from the npm registry"
expect fetch "exit 0" exited 0
expect fetch "runs at the pinned version" runs

# 2. nothing to do: quiet
run_setup
expect idempotent "quiet, exit 0" quiet

# 3. its files damaged (the stamp gone with them): fetched again
rm -rf "$MJARM_TOOLS/npm/bin" "$MJARM_TOOLS/npm/.mjarm-npm-$pinned"
run_setup
expect damaged "fetched again" said "fetching npm $pinned"
expect damaged "runs" runs

# 4. another tarball than the pinned one (another npm version's): refused, nothing installed
export MJARM_TOOLS="$work/other"
MJARM_NPM_URL="https://registry.npmjs.org/npm/-/npm-10.9.8.tgz" run_setup
expect mismatch "exit 1" exited 1
expect mismatch "says it does not match" said "does not match its pinned sha512"
expect mismatch "nothing installed" absent

finish
