#!/usr/bin/env bash
# The local backend's speed-up: one sweep file run with 1 and with JOBS workers (same shard size,
# fresh folders), wall time of each, the ratio, and a check that both gave the same trials table.
#   bench/sweep_speedup.sh [MJARM] [FILE] [JOBS] [SHARD_SIZE]
# defaults: build-demo/mjarm (make demo: Release), examples/sweeps/shelf_pick.yaml, 2, 10.
set -euo pipefail
mjarm="${1:-build-demo/mjarm}"
file="${2:-examples/sweeps/shelf_pick.yaml}"
jobs="${3:-2}"
shard="${4:-10}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

run() {  # run N: wall seconds of a sweep with N workers
  local start end
  start=$(date +%s.%N)
  "$mjarm" sweep run "$file" --out "$work/jobs$1" --jobs "$1" --shard-size "$shard" --json \
    > "$work/jobs$1.json"
  end=$(date +%s.%N)
  python3 -c "print($end - $start)"
}

one=$(run 1)
many=$(run "$jobs")
"$mjarm" sweep export "$work/jobs1" --csv > "$work/one.csv"
"$mjarm" sweep export "$work/jobs$jobs" --csv > "$work/many.csv"
trials=$(python3 -c "import json; print(json.load(open('$work/jobs1.json'))['plan']['trials'])")
same=yes
cmp -s "$work/one.csv" "$work/many.csv" || same=no
printf 'sweep %s: %s trials, shards of %s\n' "$file" "$trials" "$shard"
printf '1 worker:  %.2f s\n%s workers: %.2f s\nspeed-up:  %.2fx\nsame trials table: %s\n' \
  "$one" "$jobs" "$many" "$(python3 -c "print($one / $many)")" "$same"
[ "$same" = yes ]
