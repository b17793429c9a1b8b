#!/usr/bin/env bash
# The golden-output test: runs every subcommand of the tool on fixed tiny inputs with fixed seeds
# and compares the SHA-256 of every output file with tests/golden/expected.sha256, once per thread
# count (BLUETILE_THREADS=1 and 2): a refactor must leave every byte as it was.
#
#   run_golden.sh BLUETILE_BINARY WORK_DIR
#
# BLUETILE_GOLDEN_UPDATE=1 rewrites expected.sha256 from the one-thread run (after checking that
# the two-thread run gives the same bytes). Not hashed: the cairo PDF summary (it embeds its
# creation date) and `devices` (its list is the machine's), which only has to run.
set -euo pipefail

tool=$(realpath "$1")
mkdir -p "$2"
work=$(cd "$2" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
expected=$here/expected.sha256
# Outputs name their inputs: the image is copied into each run's folder and named relatively,
# so the bytes do not depend on where the repository is.
image=ramp.pgm

# run NAME ARGS...: the tool, its standard output kept as NAME.stdout when NAME is not "-".
run() {
  local name=$1
  shift
  local out=discarded.stdout
  [ "$name" != - ] && out=$name.stdout
  if ! "$tool" "$@" >"$out" 2>>stderr.log; then
    echo "golden: failed: bluetile $*" >&2
    tail -n 20 stderr.log >&2
    exit 1
  fi
}

outputs() {
  local dir=$1
  rm -rf "$dir"
  mkdir -p "$dir"
  cd "$dir"
  cp "$here/ramp.pgm" "$image"

  # dart: every point format, a batch of sets, one file per set.
  run - dart -n 64 -s 3 -o dart.txt
  run - dart -n 64 -s 3 -o dart.npy
  run - dart -n 64 -s 3 -o dart.bpt
  run - dart -n 64 -s 3 -o dart.h --name golden_points
  run - dart -n 64 -s 3 -o dart32.npy --float32
  run - dart -n 32 -s 4 --sets 3 --shrink 0.9 --start 0.8 --max-failures 50 -o dart_sets.txt
  run - dart -n 32 -s 4 --sets 2 -o dart_set{}.bpt --format binary

  # relax: exact engine from random starts and from a file, sets, fixed sites, a log, a density
  # map (bounded and periodic); then the raster engine (lavapipe in CI), with its ID image.
  run - relax -n 64 -k 8 -s 5 --engine exact -o relax.txt --log relax_log.csv
  run - relax -n 64 -k 8 -s 5 --engine exact -o relax.npy --float32
  run - relax -n 64 -k 8 -s 5 --engine exact -o relax.h
  run - relax -i dart.txt -k 4 --fixed 8 --engine exact -o relax_from_dart.bpt
  run - relax -i dart_sets.txt -k 3 --engine exact -o relax_from_sets.txt
  run - relax -n 24 -k 3 -s 6 --sets 3 --engine exact -o relax_set{}.npy
  run - relax -n 24 -k 3 -s 6 --sets 2 --tolerance 1e-9 --engine exact -o relax_sets.txt
  # The exact engine's kept Delaunay triangulation (periodic scenes of 256 sites and more).
  run - relax -n 600 -k 6 -s 9 --engine exact -o relax_kept.txt --log relax_kept_log.csv
  run - relax -n 48 -k 4 -s 7 --density-map "$image" -o relax_density.txt
  run - relax -n 48 -k 4 -s 7 --density-map "$image" --invert --gamma 2 --transfer linear --weight-exponent 1 \
    --bounded -o relax_density_bounded.txt
  run - relax -n 64 -k 3 -s 8 --bounded --engine exact -o relax_bounded.txt
  run - relax -n 64 -k 3 -s 9 --engine raster --resolution 64 -o relax_raster.txt --log relax_raster_log.csv \
    --id-image relax_raster_id.png
  run - relax -n 64 -k 3 -s 9 --engine raster --resolution 96 --coverage point --cone fan -o relax_raster_point.txt

  # progressive: from scratch (both placements, a ratio) and on top of a file.
  run - progressive -n 16 -l 3 -k 4 -s 2 --engine exact -o progressive.txt
  run - progressive -n 16 -l 3 -k 4 -s 2 --placement random --ratio 1.5 --engine exact -o progressive_random.txt
  run - progressive -n 8 -l 2 -k 2 -s 2 --sets 2 --engine exact -o progressive_sets.npy
  run - progressive -i relax.txt -a 32 -k 3 --engine exact -o progressive_from_relax.bpt
  run - progressive -n 1 -a 1 -l 64 -k 4 -s 2 --rank-order voids --engine exact -o progressive_voids.txt
  # the fill order: its grid's search (a tree of block summaries) gives the points of a full scan
  run - progressive -n 32 -l 4 -s 2 --rank-order fill -o progressive_fill.txt

  # centroids: both engines.
  run - centroids -i relax.txt --engine exact -o centroids.txt
  run - centroids -i relax_sets.txt --engine exact -o centroids_sets.npy
  run - centroids -i relax.txt --engine raster --resolution 64 -o centroids_raster.txt

  # analyze: one set (with the SVG summary), levels, a comparison and an average. The PDF summary
  # only has to be written (cairo stamps its date into it).
  run analyze analyze -i relax.txt -o analyze_one --summary analyze_one/summary.svg --cells --from dart.txt \
    --image-size 128 --threads 1
  run analyze_levels analyze -i progressive.txt -o analyze_levels --by-level --axis integer --image-size 96
  run analyze_ranks analyze -i progressive_voids.txt -o analyze_ranks --by-rank 1/4 3/8 1/2 1/1 --image-size 96
  run analyze_compare analyze -i relax.txt -i dart.txt -o analyze_compare --compare --label relaxed --label dart \
    --rdf-range 3 --rdf-bins 40 --size 32 --bin-width 2 --image-size 64 --no-centroids --title golden
  run analyze_average analyze -i relax_sets.txt -o analyze_average --average --no-psa-measures --image-size 64
  run - analyze -i dart.txt -o analyze_pdf --summary analyze_pdf/summary.pdf --image-size 64
  rm -f analyze_pdf/summary.pdf

  # wang: the three tile sets, levels, each strategy; wang-check of one; tile from it and from
  # the built-in set, in every output kind.
  run wang8 wang --set wang8 -n 8 -k 3 --warm 2 -s 3 -o wang8.tiles --check
  run - wang --set wang16 -n 13 -k 2 --warm 1 -l 2 --ratio 2 -s 3 --strategy rounds --rank-order voids -o wang16.tiles
  run - wang --set wang8 -n 8 -k 3 --warm 2 -l 3 --ratio 2 -s 3 -o wang8_fill.tiles
  run - wang --set corner16 -n 13 -k 2 --warm 1 --margin 0.05 -s 3 -o corner16.tiles
  run - wang --set wang8 -n 6 -k 2 --warm 1 --strategy instances --period 4 --lattice-steps 2 --seam-steps 2 \
    -s 4 -o wang8_instances.tiles
  run wang_check wang-check wang8.tiles --period 3 -s 2 --untiled --untiled-iterations 3 --image-size 64 \
    -o wang_check
  run - tile --tiles wang8.tiles --region 0 0 3 2 -s 5 -o tile.txt -o tile.svg -o tile.png -o tile.bin \
    --columns x,y,i,j,tile,level,rank --image-size 64
  run - tile --region -1 -1 2 2 -s 6 --tile-size 0.5 --density 20 --normalize -o tile_default.txt
  run - tile --region 0 0 2 1 -s 7 --density-map "$image" --count 300 --dots-follow-density --dot-radius 0.01 \
    -o tile_density.txt -o tile_density.svg -o tile_density.png --image-size 64
  run - tile --region 0 0 2 1 -s 7 --density-map "$image" --invert --max-density 200 -o tile_density_inverted.txt
  run - tile --region 0 0 2 1 -s 7 --density-map "$image" --fit stretch --count 300 -o tile_density_stretch.txt
  run - tile --region 0 0 2 1 -s 7 --density-map "$image" --fit cover --count 300 -o tile_density_cover.txt

  # stipple: the point file, SVG, PNG and log, bounded and periodic.
  run - stipple --image "$image" -n 40 -k 4 -s 2 -o stipple.txt --svg stipple.svg --png stipple.png \
    --png-width 64 --log stipple_log.csv
  run - stipple --image "$image" -n 40 -k 4 -s 2 --periodic --no-invert --tolerance 1e-12 -o stipple_periodic.txt
  run - stipple --image "$image" -n 40 -k 4 -s 2 -o stipple.npy
  run - stipple --image "$image" -n 40 -k 4 -s 2 --svg stipple_only.svg

  # devices: the machine's own list; it only has to run.
  run - devices

  rm -f stderr.log discarded.stdout "$image"
  find . -type f | LC_ALL=C sort | sed 's|^\./||' | xargs -d '\n' sha256sum
}

BLUETILE_THREADS=1 outputs "$work/threads1" >"$work/threads1.sha256"
BLUETILE_THREADS=2 outputs "$work/threads2" >"$work/threads2.sha256"
if ! diff "$work/threads1.sha256" "$work/threads2.sha256" >&2; then
  echo "golden: the outputs differ between 1 and 2 threads (above: < 1 thread, > 2 threads)" >&2
  # Where, for a text output: the first lines that differ (a log of a flaky run says it all).
  # (join pairs the files both runs wrote; one only one run wrote is in the list above.)
  LC_ALL=C join -j 2 "$work/threads1.sha256" "$work/threads2.sha256" | awk '$2 != $3 {print $1}' |
    while read -r file; do
      case $file in
        *.txt | *.csv | *.json | *.stdout | *.svg | *.tiles)
          echo "golden: $file, 1 thread (<) against 2 (>):" >&2
          { diff "$work/threads1/$file" "$work/threads2/$file" || true; } | head -n 12 >&2 ;;
      esac
    done
  exit 1
fi
if [ "${BLUETILE_GOLDEN_UPDATE:-0}" = 1 ]; then
  cp "$work/threads1.sha256" "$expected"
  echo "golden: wrote $expected ($(wc -l <"$expected") files)"
  exit 0
fi
if ! diff "$expected" "$work/threads1.sha256" >&2; then
  echo "golden: outputs differ from $expected (above: < expected, > now; outputs in $work/threads1)." >&2
  echo "golden: if the change is intended, rerun with BLUETILE_GOLDEN_UPDATE=1 and say why in the commit" >&2
  exit 1
fi
echo "golden: $(wc -l <"$expected") files as expected, with 1 and 2 threads"
