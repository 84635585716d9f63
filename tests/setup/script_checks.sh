# The checks a set-up script's test makes (sourced by tests/setup/*_check.sh): run the script,
# keep what it said and its exit status, and count each expectation, printing the script's words
# under a failed one.
passed=0
failed=0
output=""
status=0
script=""
run_script() {  # run_script SCRIPT ARG...
  script=$(basename "$1")
  set +e
  output=$(bash "$@" 2>&1)
  status=$?
  set -e
}
expect() {  # expect CASE WHAT COMMAND...
  local case=$1 what=$2
  shift 2
  if "$@"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED [$case] $what"
    echo "  $script exited $status and said:"
    sed 's/^/    /' <<<"$output"
  fi
}
said() { grep -qF -- "$1" <<<"$output"; }
exited() { [ "$status" -eq "$1" ]; }
quiet() { [ "$status" -eq 0 ] && [ -z "$output" ]; }
finish() {
  echo "$passed passed, $failed failed"
  [ "$failed" -eq 0 ]
}
