# Shared by the shell tests (bench_arguments.sh, setup_arguments.sh), sourced: a scratch folder
# $work removed on exit, the counters, fail MESSAGE, and finish (the summary line and the status).
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
cases=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

finish() {
  echo "$cases cases, $failures failures"
  [ "$failures" = 0 ]
}
