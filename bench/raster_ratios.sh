#!/usr/bin/env bash
# The raster engine against the exact engine on the jobs docs/RASTER.md measures, as a user runs them:
# `bluetile relax` wall time and peak resident memory, raster (default: area coverage) and
# `--engine exact` interleaved in one run (round r runs every job once), so that load from
# other processes falls on both alike. Prints a markdown table of medians and ratios.
#
#   bench/raster_ratios.sh [BUILD_DIR] [REPEATS]      (defaults: build, 3)
#
# Per-iteration figures for N = 10^4 and 10^5 are (T(k = 11) - T(k = 1)) / 10: start-up,
# input and output cancel out.
set -euo pipefail
build=${1:-build}
repeats=${2:-3}
bin=$build/bluetile
[ -x "$bin" ] || { echo "no $bin: build first" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# name | arguments
jobs=(
  "n1000_k80|-n 1000 -k 80 --seed 1"
  "n1000_k80_point|-n 1000 -k 80 --seed 1 --coverage point"
  "n1e4_k1|-n 10000 -k 1 --seed 1"
  "n1e4_k11|-n 10000 -k 11 --seed 1"
  "n1e5_k1|-n 100000 -k 1 --seed 1"
  "n1e5_k11|-n 100000 -k 11 --seed 1"
  "sets256|-n 64 --sets 256 -k 50 --seed 1"
  "sets4096|-n 64 --sets 4096 -k 50 --seed 1"
)

run() {  # engine, job index, round -> appends "seconds kib" to a results file
  local engine=$1 name=${jobs[$2]%%|*} args=${jobs[$2]#*|}
  local extra=""
  [ "$engine" = exact ] && extra="--engine exact"
  [ "$engine" = exact ] && [[ "$args" == *"--coverage point"* ]] && args=${args%--coverage point}
  /usr/bin/time -f "%e %M" -o "$work/t" "$bin" relax $args $extra -o "$work/out.txt" >/dev/null 2>"$work/err" ||
    { cat "$work/err" >&2; exit 1; }
  cat "$work/t" >>"$work/$name.$engine"
}

for ((r = 0; r < repeats; ++r)); do
  for i in "${!jobs[@]}"; do
    if (((r + i) % 2)); then run exact "$i"; run raster "$i"; else run raster "$i"; run exact "$i"; fi
  done
done

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
col() { awk -v c="$2" '{print $c}' "$work/$1"; }

echo "| job | raster s | exact s | ratio | raster MiB | exact MiB | memory ratio |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for i in "${!jobs[@]}"; do
  name=${jobs[$i]%%|*}
  rs=$(col "$name.raster" 1 | median) es=$(col "$name.exact" 1 | median)
  rm=$(col "$name.raster" 2 | median) em=$(col "$name.exact" 2 | median)
  awk -v n="$name" -v rs="$rs" -v es="$es" -v rm="$rm" -v em="$em" \
    'BEGIN {printf "| %s | %.2f | %.2f | %.1fx | %.0f | %.0f | %.1fx |\n", n, rs, es, rs / es, rm / 1024, em / 1024, rm / em}'
done
for n in 1e4 1e5; do
  r1=$(col "n${n}_k1.raster" 1 | median) r11=$(col "n${n}_k11.raster" 1 | median)
  e1=$(col "n${n}_k1.exact" 1 | median) e11=$(col "n${n}_k11.exact" 1 | median)
  awk -v n="$n" -v r1="$r1" -v r11="$r11" -v e1="$e1" -v e11="$e11" \
    'BEGIN {printf "| N = %s, per iteration | %.3f | %.3f | %.1fx | | | |\n", n, (r11 - r1) / 10, (e11 - e1) / 10, (r11 - r1) / (e11 - e1)}'
done
