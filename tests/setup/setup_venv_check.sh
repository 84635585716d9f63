#!/usr/bin/env bash
# Breaks a scratch virtual environment (MJARM_VENV) in each way scripts/setup_venv.sh must
# handle, runs the script, and checks what it said and that the environment works afterwards
# (mujoco imports at the pinned version, one libmujoco) — or, for a folder that is not an
# environment, that it was refused and left alone.
# Usage: setup_venv_check.sh SOURCE_DIR WORK_DIR
set -euo pipefail
source_dir=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
export MJARM_VENV="$work/venv"
pinned=$(sed -n 's/^mujoco==\([^ ;#]*\).*/\1/p' "$source_dir/python/requirements.txt")
[ -n "$pinned" ] || { echo "no mujoco pin in python/requirements.txt" >&2; exit 1; }
# the script is given the pins the cases break (mujoco, numpy), as python/requirements.txt has
# them: what it does with a requirements file does not depend on the file's length, and the rest
# of that file (pytest, gymnasium, the build backend, ...) would only make each install longer
requirements="$work/requirements.txt"
grep -E '^(mujoco|numpy)==' "$source_dir/python/requirements.txt" > "$requirements" || true
[ "$(wc -l < "$requirements")" -eq 2 ] ||
  { echo "no mujoco and numpy pins in python/requirements.txt" >&2; exit 1; }

source "$(dirname "$0")/script_checks.sh"
run_setup() { run_script "$source_dir/scripts/setup_venv.sh" "$requirements"; }
site() { "$MJARM_VENV/bin/python" -c "import sysconfig; print(sysconfig.get_paths()['purelib'])"; }
# mujoco imports at the pinned version, from one library file (the pinned mujoco-core's)
works() {
  "$MJARM_VENV/bin/python" - "$pinned" <<'PYTHON'
import glob, os, sys, mujoco
assert mujoco.__version__ == sys.argv[1], mujoco.__version__
libraries = glob.glob(os.path.join(os.path.dirname(mujoco.__file__), "libmujoco.so*"))
assert [os.path.basename(p) for p in libraries] == [f"libmujoco.so.{sys.argv[1]}"], libraries
PYTHON
}

# 1. no environment: made
run_setup
expect missing "made, exit 0" said "making the virtual environment $MJARM_VENV"
expect missing "works" works

# 2. nothing to do: quiet
run_setup
expect idempotent "quiet, exit 0" quiet

# 3. its interpreter gone (the base Python removed or upgraded): made again
ln -sfn "$work/no-such-python" "$MJARM_VENV/bin/python3"
run_setup
expect interpreter "made again" said "does not start"
expect interpreter "exit 0" exited 0
expect interpreter "works" works

# 4. an install cut short: never stamped, one package without RECORD and its library missing,
#    another with a file missing
sp=$(site)
rm "$MJARM_VENV/.mjarm-installed" "$sp"/mujoco_core-*.dist-info/RECORD "$sp/mujoco/libmujoco.so.$pinned"
rm "$sp/numpy/__init__.py"
run_setup
expect interrupted "unrecorded package named" said "unrecorded mujoco-core $pinned"
expect interrupted "damaged package named" said "damaged numpy"
expect interrupted "exit 0" exited 0
expect interrupted "works" works
run_setup
expect interrupted "quiet once repaired" quiet

# 5. mujoco that does not import: its library's contents changed, every file still there
truncate -s 4096 "$sp/mujoco/libmujoco.so.$pinned"
run_setup
expect no-import "changed files found" said "files changed since their install"
expect no-import "package named" said "damaged mujoco-core $pinned"
expect no-import "exit 0" exited 0
expect no-import "works" works

# 6. another mujoco installed by the user: the pinned one put back. 3.3.7 predates the split
#    into mujoco-core and ships files of the same names: replacing it takes mujoco-core's with it
"$MJARM_VENV/bin/python" -m pip install --disable-pip-version-check -q mujoco==3.3.7
run_setup
expect other-version "version named" said "pin mujoco $pinned 3.3.7 installed"
expect other-version "files lost with it found" said "damaged mujoco-core $pinned"
expect other-version "exit 0" exited 0
expect other-version "works" works
run_setup
expect other-version "quiet once repaired" quiet

# 7. a folder that is not a virtual environment: refused, left as it was, the command given
MJARM_VENV="$work/not-a-venv"
mkdir -p "$MJARM_VENV"
echo keep > "$MJARM_VENV/notes.txt"
run_setup
expect not-a-venv "exit 1" exited 1
expect not-a-venv "says what to run" said "mv $MJARM_VENV $MJARM_VENV.old"
expect not-a-venv "left alone" grep -qx keep "$MJARM_VENV/notes.txt"

finish
