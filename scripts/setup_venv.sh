#!/usr/bin/env bash
# Makes the project's virtual environment (.venv, or $MJARM_VENV) and installs the pinned
# requirements files given as arguments (python/requirements.txt when none). Idempotent: a
# working environment whose installed requirements match the files' stamp is left as it is; a
# missing or broken one (no interpreter, an interpreter that does not start, a package that does
# not import) is made again from scratch.
set -euo pipefail
cd "$(dirname "$0")/.."

venv="${MJARM_VENV:-.venv}"
requirements=("$@")
[ ${#requirements[@]} -gt 0 ] || requirements=(python/requirements.txt)
for file in "${requirements[@]}"; do
  [ -f "$file" ] || { echo "mjarm setup: no requirements file '$file'" >&2; exit 2; }
done

# the stamp: which files, with which contents, were installed into this environment
stamp_of() { sha256sum "$1" | cut -d' ' -f1; }
stamp_file="$venv/.mjarm-installed"

healthy() {
  [ -x "$venv/bin/python" ] || return 1
  "$venv/bin/python" -c "import sys, pip" >/dev/null 2>&1 || return 1
  # the one package everything else stands on, and the same interpreter it was made with
  "$venv/bin/python" -c "import mujoco" >/dev/null 2>&1 || return 1
}

if [ -e "$venv" ] && ! healthy; then
  # a half-made environment (interrupted install, a deleted interpreter) is not repaired in place
  if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c "import pip" >/dev/null 2>&1 &&
     [ ! -f "$stamp_file" ]; then
    :  # made but never installed into: install below
  else
    echo "mjarm setup: the virtual environment $venv is broken; making it again"
    rm -rf "$venv"
  fi
fi
if [ ! -e "$venv" ]; then
  echo "mjarm setup: making the virtual environment $venv"
  /usr/bin/python3 -m venv "$venv"
fi

missing=()
for file in "${requirements[@]}"; do
  line="$file $(stamp_of "$file")"
  grep -qxF "$line" "$stamp_file" 2>/dev/null || missing+=("$file")
done
[ ${#missing[@]} -gt 0 ] || exit 0

args=()
for file in "${missing[@]}"; do args+=(-r "$file"); done
echo "mjarm setup: installing ${missing[*]} into $venv"
# the project's pins constrain every install: a peer never moves mujoco or numpy
"$venv/bin/python" -m pip install --disable-pip-version-check --no-input -q \
  -c python/requirements.txt "${args[@]}"
# check what was asked for is what is there (pip exits 0 on some partial states)
"$venv/bin/python" -m pip check >/dev/null || {
  echo "mjarm setup: the packages in $venv do not agree ($venv/bin/python -m pip check)" >&2
  exit 1
}
"$venv/bin/python" -c "import mujoco" || {
  echo "mjarm setup: mujoco does not import in $venv; remove it and run make setup" >&2
  exit 1
}
for file in "${missing[@]}"; do
  grep -v "^$file " "$stamp_file" 2>/dev/null > "$stamp_file.new" || true
  echo "$file $(stamp_of "$file")" >> "$stamp_file.new"
  mv "$stamp_file.new" "$stamp_file"
done
