#!/usr/bin/env bash
# Runs a command with an X display of its own: an Xvfb that picks a free display number and
# reports it (-displayfd), stopped by its PID when the command ends, also on failure or a signal.
# Usage: with_display.sh COMMAND [ARG...]
set -euo pipefail
report=$(mktemp)
xvfb_pid=""
stop() {
  if [[ -n $xvfb_pid ]]; then
    kill "$xvfb_pid" 2>/dev/null || true
    wait "$xvfb_pid" 2>/dev/null || true
  fi
  rm -f "$report"
}
trap stop EXIT
trap 'exit 143' TERM
trap 'exit 130' INT
command -v Xvfb >/dev/null || { echo "with_display.sh: no Xvfb (scripts/setup.sh installs it)" >&2; exit 1; }
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3>"$report" >/dev/null 2>&1 &
xvfb_pid=$!
for _ in $(seq 600); do  # the display number and a newline once it listens: 60 s at most
  [[ $(wc -l <"$report") -ge 1 ]] && break
  kill -0 "$xvfb_pid" 2>/dev/null || { echo "with_display.sh: Xvfb exited" >&2; exit 1; }
  sleep 0.1
done
[[ $(wc -l <"$report") -ge 1 ]] || { echo "with_display.sh: Xvfb reported no display in 60 s" >&2; exit 1; }
DISPLAY=":$(head -n1 "$report")" "$@"
