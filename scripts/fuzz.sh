#!/usr/bin/env bash
# The fuzz targets (fuzz/; docs/hardening.md, "Fuzzing"): builds build-fuzz with clang (libFuzzer,
# ASan, UBSan), stages each target's seeds and dictionary from the tree (fuzz/corpora.txt), then
# runs the targets:
#   scripts/fuzz.sh check [TARGET...]  a bounded, deterministic run of each (`make test`): seed 1,
#                                      the `runs` of corpora.txt, at most FUZZ_CHECK_SECONDS (7) s
#   scripts/fuzz.sh long [TARGET...]   FUZZ_SECONDS (600) s each, FUZZ_PARALLEL (1) at a time, the
#                                      grown corpora kept in build-fuzz/corpus/TARGET (`make fuzz`)
# A finding fails the run: a crash, a sanitizer report, an exception other than mjarm::Error, an
# input that takes more than FUZZ_TIMEOUT (20) s or more than FUZZ_RSS_MB (2048) MB. Its input
# is kept in build-fuzz/findings/TARGET/ and the command that reproduces it is printed; once
# fixed, the input goes to fuzz/regressions/TARGET/, which the test suite replays (tests/fuzz).
# FUZZ_PROGRAMS=DIR runs the programs DIR already holds instead of building build-fuzz (make test:
# the sanitized test build makes them), with the staged files and findings in FUZZ_BUILD.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-}
[ $# -gt 0 ] && shift
case $mode in
  check | long) ;;
  *) echo "usage: scripts/fuzz.sh check|long [TARGET...]" >&2; exit 2 ;;
esac
build=${FUZZ_BUILD:-build-fuzz}
table=fuzz/corpora.txt
timeout=${FUZZ_TIMEOUT:-20}
rss_mb=${FUZZ_RSS_MB:-2048}

programs=${FUZZ_PROGRAMS:-}
if [ -z "$programs" ]; then
  if ! command -v clang++ >/dev/null; then
    echo "fuzz: clang++ not found (Debian: clang and libclang-rt-14-dev; make setup installs them)" >&2
    exit 1
  fi
  if [ ! -f "$build/CMakeCache.txt" ]; then
    # -O1 -g1: libFuzzer's speed with readable stacks at a third of the -O2 compile time
    # shellcheck disable=SC2086  # FUZZ_CMAKE_FLAGS holds several flags
    cmake -S . -B "$build" -DMJARM_FUZZ=ON -DMJARM_WERROR=ON -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
      -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" ${FUZZ_CMAKE_FLAGS:-}
  fi
  cmake --build "$build" -j "${JOBS:-$(nproc)}"
  programs=$build
fi

# the column of corpora.txt lines of one kind for one target
field() { awk -v kind="$1" -v target="$2" -v col="$3" '$1 == kind && $2 == target { print $col }' "$table"; }

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  mapfile -t targets < <(awk '$1 == "runs" { print $2 }' "$table")
fi
for t in "${targets[@]}"; do
  if [ ! -x "$programs/fuzz_$t" ] || [ -z "$(field runs "$t" 3)" ]; then
    echo "fuzz: no target '$t' (targets: $(awk '$1 == "runs" { printf "%s ", $2 }' "$table"))" >&2
    exit 2
  fi
done

# Seeds: copies of the tree's files (flattened names), so libFuzzer reads exactly these.
# Dictionary: the quoted names in the reader's sources, and the element and attribute names,
# keys and words of the seeds.
stage() {
  local t=$1 seeds=$build/seeds/$1 dict=$build/dict/$1.dict
  rm -rf "$seeds"
  mkdir -p "$seeds" "$build/dict"
  while read -r folder extension; do
    while IFS= read -r -d '' file; do
      cp "$file" "$seeds/$(echo "${file#./}" | tr '/' '_')"
    done < <(find "$folder" -type f -name "*$extension" -print0)
  done < <(awk -v target="$t" '$1 == "seeds" && $2 == target { print $3, $4 }' "$table")
  for regression in fuzz/regressions/"$t"/*; do
    [ -f "$regression" ] && cp "$regression" "$seeds/regression_$(basename "$regression")"
  done
  {
    for source in $(field dict "$t" 3); do
      grep -ohE '"[A-Za-z_][A-Za-z0-9_.:/-]{1,40}"' "$source" || true
    done
    grep -ohE '<[A-Za-z_][A-Za-z0-9_]*' "$seeds"/* | sed 's/.*/"&"/' || true
    grep -ohE '[A-Za-z_][A-Za-z0-9_]*="' "$seeds"/* | sed 's/"$//; s/.*/"&=\\""/' || true
    grep -ohE '^[ -]*[A-Za-z_][A-Za-z0-9_]*:' "$seeds"/* | sed 's/^[ -]*//; s/.*/"&"/' || true
    grep -ohE '"[A-Za-z_][A-Za-z0-9_]*"' "$seeds"/* || true
    grep -ohE '\b[a-z_]{2,24}\b' "$seeds"/* | sed 's/.*/"&"/' || true
  } | sort -u > "$dict"
}

# runs target $1; its output goes to $build/logs/$1.log, a one-line summary to stdout
run() {
  local t=$1 corpus findings log=$build/logs/$1.log
  findings=$build/findings/$t
  local args=(-dict="$build/dict/$t.dict" -timeout="$timeout" -rss_limit_mb="$rss_mb"
              -artifact_prefix="$findings/" -print_final_stats=1)
  if [ "$mode" = check ]; then
    corpus=$build/check/$t
    rm -rf "$corpus"
    args+=(-seed=1 -runs="$(field runs "$t" 3)" -max_total_time="${FUZZ_CHECK_SECONDS:-7}")
  else
    corpus=$build/corpus/$t
    args+=(-max_total_time="${FUZZ_SECONDS:-600}")
  fi
  mkdir -p "$corpus" "$findings" "$build/logs"
  local rc=0
  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/scripts/lsan.supp \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$programs/fuzz_$t" "${args[@]}" "$corpus" "$build/seeds/$t" > "$log" 2>&1 || rc=$?
  local stats
  stats=$(awk '/^stat::number_of_executed_units/ { runs = $2 } /^stat::average_exec_per_sec/ { rate = $2 }
               /^stat::peak_rss_mb/ { rss = $2 }
               / cov: / { for (i = 1; i < NF; ++i) { if ($i == "cov:") cov = $(i + 1); if ($i == "ft:") ft = $(i + 1);
                                                     if ($i == "corp:") corp = $(i + 1) } }
               END { printf "%s runs, %s/s, cov %s, ft %s, corpus %s, peak RSS %s MB", runs, rate, cov, ft, corp, rss }' "$log")
  if [ $rc -eq 0 ]; then
    echo "fuzz $t: $stats, no finding"
    return 0
  fi
  local input
  input=$(grep -oE 'Test unit written to .*' "$log" | tail -1 | sed 's/Test unit written to //') || true
  echo "fuzz $t: FINDING (exit $rc): $stats"
  grep -E 'ERROR|runtime error|terminate called|what\(\)|deadly signal|==[0-9]+==|#[0-9] ' "$log" | head -20 | sed 's/^/  /'
  echo "  log: $log"
  if [ -n "$input" ]; then
    echo "  input: $input"
    echo "  reproduce: ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=\$PWD/scripts/lsan.supp $programs/fuzz_$t $input"
    echo "  once fixed: cp $input fuzz/regressions/$t/ (the test suite replays it)"
  fi
  return 1
}

for t in "${targets[@]}"; do stage "$t"; done
status=0
if [ "$mode" = long ] && [ "${FUZZ_PARALLEL:-1}" -gt 1 ]; then
  # several targets at once; each one's summary is printed when it ends
  pids=()
  for t in "${targets[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$FUZZ_PARALLEL" ]; do wait -n || status=1; done
    run "$t" &
    pids+=($!)
  done
  for pid in "${pids[@]}"; do wait "$pid" || status=1; done
else
  for t in "${targets[@]}"; do run "$t" || status=1; done
fi
exit $status
