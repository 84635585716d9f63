#!/usr/bin/env bash
# Makes the project's virtual environment (.venv, or $MJARM_VENV) and installs the pinned
# requirements files given as arguments (python/requirements.txt when none). Idempotent and quiet
# when there is nothing to do. The environment is checked on every run; what is wrong is said and
# repaired:
#   missing                                    made
#   an interpreter that does not start (its    made again: nothing in it can run
#   base Python removed or upgraded), no pip
#   a pinned package missing or at another     the pins installed (a mujoco the user installed
#   version                                    is replaced by the pinned one)
#   an install cut short (files missing, a     the package reinstalled at its version
#   package without its RECORD)
#   mujoco that does not import                the files of every package checked against their
#                                              RECORD hashes and the changed ones reinstalled;
#                                              if it still does not import, the error and what
#                                              to run
# A folder that is not a virtual environment is never removed: the script says what to run.
set -euo pipefail
cd "$(dirname "$0")/.."

venv="${MJARM_VENV:-.venv}"
requirements=("$@")
[ ${#requirements[@]} -gt 0 ] || requirements=(python/requirements.txt)
for file in "${requirements[@]}"; do
  [ -f "$file" ] || { echo "mjarm setup: no requirements file '$file'" >&2; exit 2; }
done

say() { echo "mjarm setup: $*"; }
fail() { echo "mjarm setup: $*" >&2; exit 1; }

# the stamp: which files, with which contents, were installed into this environment
stamp_of() { sha256sum "$1" | cut -d' ' -f1; }
stamp_file="$venv/.mjarm-installed"

# Checks the environment with its own interpreter; prints one line per problem:
#   pin NAME VERSION WHY         a pinned package missing or at another version
#   damaged NAME VERSION WHY     an installed package with files missing (and with --hashes,
#                                changed) against its RECORD; compiled .pyc files are not checked
#   unrecorded NAME VERSION DIR  an installed package without RECORD (an install cut short), which
#                                pip can neither check nor uninstall
#   import WHY                   mujoco does not import
probe() {
  "$venv/bin/python" - "$@" <<'PYTHON'
import base64
import hashlib
import importlib.metadata as md
import re
import signal
import subprocess
import sys

hashes = sys.argv[1] == "--hashes"
pins = {}
for path in sys.argv[1 + hashes:]:
    for line in open(path, encoding="utf-8"):
        m = re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)(\[[^\]]*\])?\s*==\s*([^\s;#]+)", line)
        if m:
            pins[m.group(1)] = m.group(3)
for name, version in pins.items():
    try:
        installed = md.version(name)
    except md.PackageNotFoundError:
        print(f"pin {name} {version} not installed")
        continue
    if installed != version:
        print(f"pin {name} {version} {installed} installed")


def changed(dist, f):
    if not hashes or f.hash is None:
        return False
    digest = hashlib.new(f.hash.mode, dist.locate_file(f).read_bytes()).digest()
    return base64.urlsafe_b64encode(digest).rstrip(b"=").decode() != f.hash.value


for dist in md.distributions():
    name, version = dist.metadata["Name"], dist.version
    if dist.files is None:
        print(f"unrecorded {name} {version} {getattr(dist, '_path', '?')}")
        continue
    files = [f for f in dist.files if f.suffix != ".pyc"]
    missing = [f for f in files if not dist.locate_file(f).exists()]
    bad = missing or [f for f in files if changed(dist, f)]
    if bad:
        print(f"damaged {name} {version} {len(bad)} files {'missing' if missing else 'changed'},"
              f" {bad[0]} first")
# in a process of its own: a damaged library can crash the import (SIGBUS, SIGSEGV)
imported = subprocess.run([sys.executable, "-c", "import mujoco"], capture_output=True, text=True)
if imported.returncode != 0:
    lines = imported.stderr.strip().splitlines()
    why = lines[-1] if lines else ""
    if imported.returncode < 0:
        why = f"killed by {signal.Signals(-imported.returncode).name} {why}".rstrip()
    print(f"import {why}")
PYTHON
}

# the interpreter starts, is the version the environment was made with, and has pip
interpreter_works() {
  [ -x "$venv/bin/python" ] || return 1
  "$venv/bin/python" - "$venv/pyvenv.cfg" >/dev/null 2>&1 <<'PYTHON' || return 1
import re, sys, pip  # noqa: F401
made = re.search(r"^version\s*=\s*(\d+)\.(\d+)", open(sys.argv[1]).read(), re.M)
sys.exit(0 if made and tuple(map(int, made.groups())) == sys.version_info[:2] else 1)
PYTHON
}

if [ -e "$venv" ] || [ -L "$venv" ]; then
  [ -f "$venv/pyvenv.cfg" ] ||
    fail "$venv exists but is not a virtual environment (no pyvenv.cfg): move it away" \
         "(mv $venv $venv.old) or set MJARM_VENV to another folder, then run this again"
  if ! interpreter_works; then
    say "the interpreter of $venv does not start, is not the Python it was made with, or has" \
        "no pip: making $venv again"
    rm -rf "$venv"
  fi
fi
made=0
if [ ! -e "$venv" ]; then
  made=1
  say "making the virtual environment $venv"
  /usr/bin/python3 -m venv "$venv" ||
    fail "cannot make $venv with /usr/bin/python3 (scripts/setup.sh installs python3-venv)"
fi

stamped=1
for file in "${requirements[@]}"; do
  grep -qxF "$file $(stamp_of "$file")" "$stamp_file" 2>/dev/null || stamped=0
done
problems="$(probe "${requirements[@]}")"
[ $stamped -eq 1 ] && [ -z "$problems" ] && exit 0

pip_install() {
  # the project's pins constrain every install: a peer never moves mujoco or numpy. No bytecode
  # compiled at install (half of pip's time): Python compiles a module when it is first imported.
  "$venv/bin/python" -m pip install --disable-pip-version-check --no-input -q --no-compile \
    -c python/requirements.txt "$@" ||
    fail "pip failed (above). Without network, run this again once PyPI is reachable; otherwise" \
         "make the environment from scratch: rm -rf $venv && bash scripts/setup_venv.sh ${requirements[*]}"
}
# reinstalls the packages a probe found damaged or unrecorded, at their installed versions
repair() {
  local kind name version rest reinstall=()
  while read -r kind name version rest; do
    case "$kind" in
      damaged) reinstall+=("$name==$version") ;;
      unrecorded)
        # pip cannot uninstall it: its metadata goes, the reinstall writes over its files
        case "$rest" in "$venv"/*|"$(cd "$venv" && pwd)"/*) rm -rf "$rest" ;; *) continue ;; esac
        reinstall+=("$name==$version") ;;
    esac
  done <<<"$1"
  if [ ${#reinstall[@]} -gt 0 ]; then
    say "reinstalling ${reinstall[*]}"
    pip_install --force-reinstall --no-deps "${reinstall[@]}"
  fi
}
report() { sed 's/^/  /' <<<"$1"; }

if [ -n "$problems" ] && [ $made -eq 0 ]; then
  say "$venv needs repair:"
  report "$problems"
fi
repair "$problems"
args=()
for file in "${requirements[@]}"; do args+=(-r "$file"); done
say "installing ${requirements[*]} into $venv"
pip_install "${args[@]}"
# what was asked for must be what is there: pip exits 0 on some partial states, and a package
# the install replaced may have taken files of another with it (an older mujoco shipping the
# headers mujoco-core ships now)
problems="$(probe "${requirements[@]}")"
if grep -q '^damaged \|^unrecorded ' <<<"$problems"; then
  say "files of other packages went with the replaced ones:"
  report "$(grep '^damaged \|^unrecorded ' <<<"$problems")"
  repair "$problems"
  problems="$(probe "${requirements[@]}")"
fi
if grep -q '^import ' <<<"$problems" && ! grep -qv '^import ' <<<"$problems"; then
  # every file present and every version right, yet no import: look for changed files
  problems="$(probe --hashes "${requirements[@]}")"
  if grep -q '^damaged ' <<<"$problems"; then
    say "mujoco does not import; files changed since their install:"
    report "$(grep '^damaged ' <<<"$problems")"
    repair "$problems"
    problems="$(probe "${requirements[@]}")"
  fi
fi
if [ -n "$problems" ]; then
  echo "mjarm setup: $venv is still not right:" >&2
  report "$problems" >&2
  fail "if a system library is named, run scripts/setup.sh (Debian's packages); otherwise make" \
       "the environment from scratch: rm -rf $venv && bash scripts/setup_venv.sh ${requirements[*]}"
fi
"$venv/bin/python" -m pip check >/dev/null ||
  fail "the packages in $venv do not agree ($venv/bin/python -m pip check)"
for file in "${requirements[@]}"; do
  grep -v "^$file " "$stamp_file" 2>/dev/null > "$stamp_file.new" || true
  echo "$file $(stamp_of "$file")" >> "$stamp_file.new"
  mv "$stamp_file.new" "$stamp_file"
done
