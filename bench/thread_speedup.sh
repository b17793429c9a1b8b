#!/usr/bin/env bash
# Two threads against one for the exact engine's Lloyd relaxation, as a user runs it: wall and
# user time of `bluetile relax --engine exact` under BLUETILE_THREADS=1 and 2, for one or more
# binaries (say a base build and a branch), interleaved in each round so that load from other
# processes falls on all alike. Prints a markdown table of means and the two-against-one ratio.
#
#   bench/thread_speedup.sh ROUNDS BINARY...        e.g. bench/thread_speedup.sh 8 /tmp/base/bluetile build/bluetile
#
# Sizes: 10^4 sites x 200 iterations (rounds as given), 10^5 x 20 (half), 10^6 x 5 (a quarter).
set -euo pipefail
rounds=${1:?rounds}
shift
[ $# -gt 0 ] || { echo "usage: $0 ROUNDS BINARY..." >&2; exit 1; }
for bin in "$@"; do [ -x "$bin" ] || { echo "no $bin" >&2; exit 1; }; done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "| N, iterations, rounds | binary | 1 thread wall / user (s) | 2 threads wall / user (s) | 2 vs 1 |"
echo "|---|---|---:|---:|---:|"
for job in "10000 200 1" "100000 20 2" "1000000 5 4"; do
  read -r n k divide <<<"$job"
  r=$(( (rounds + divide - 1) / divide ))
  : >"$work/times"
  for _ in $(seq "$r"); do
    for threads in 1 2; do
      b=0
      for bin in "$@"; do
        /usr/bin/time -f "$b $threads %e %U" -a -o "$work/times" env BLUETILE_THREADS="$threads" \
          "$bin" relax -n "$n" -k "$k" --engine exact -o "$work/points.txt" >/dev/null
        b=$((b + 1))
      done
    done
  done
  b=0
  for bin in "$@"; do
    awk -v b="$b" -v label="$n, $k, $r" -v name="$bin" '
      $1 == b { w[$2] += $3; u[$2] += $4; c[$2]++ }
      END { printf "| %s | %s | %.3f / %.3f | %.3f / %.3f | %.2fx |\n", label, name,
                   w[1] / c[1], u[1] / c[1], w[2] / c[2], u[2] / c[2], (w[1] / c[1]) / (w[2] / c[2]) }' "$work/times"
    b=$((b + 1))
  done
done
