#!/usr/bin/env bash
# The benchmark programs' arguments (bench/bench_args.h): --help prints a usage and exits 0; an
# unknown option, a bad value or a missing input file is one line "<program>: ..." on standard
# error with exit status 2 (1 for the file), never a crash; a few short valid runs exit 0.
#
#   bench_arguments.sh BIN_DIR PROGRAM...   (the programs this build made; bench/CMakeLists.txt)
set -u
bin_dir=$1
shift
source "$(dirname "$0")/script_cases.sh"

# expect STATUS PROGRAM ARG...: runs the program and checks its status and what it printed.
expect() {
  local want=$1 program=$2
  shift 2
  cases=$((cases + 1))
  local status=0
  timeout 60 "$bin_dir/$program" "$@" >"$work/out" 2>"$work/err" </dev/null || status=$?
  local shown="$program $*"
  if [ "$status" != "$want" ]; then
    fail "$shown: exit status $status, expected $want; stderr: $(head -c 600 "$work/err")"
    return
  fi
  local err_lines
  err_lines=$(wc -l <"$work/err")
  case $want in
    0)
      if [ "${1-}" = "--help" ] || [ "${2-}" = "--help" ]; then
        grep -q "Usage:" "$work/out" || fail "$shown: no 'Usage:' in the help"
        [ "$err_lines" = 0 ] || fail "$shown: help wrote to stderr: $(head -c 300 "$work/err")"
      fi
      ;;
    *)
      [ "$err_lines" = 1 ] || fail "$shown: $err_lines lines on stderr, expected one: $(head -c 600 "$work/err")"
      grep -q "^$program: " "$work/err" || fail "$shown: stderr does not start with '$program: ': $(head -c 300 "$work/err")"
      if [ "$want" = 2 ] && [ -s "$work/out" ]; then
        fail "$shown: a bad argument, yet output on stdout: $(head -c 300 "$work/out")"
      fi
      ;;
  esac
}

# expect_message STATUS TEXT PROGRAM ARG...: as expect, and stderr holds TEXT.
expect_message() {
  local want=$1 text=$2
  shift 2
  expect "$want" "$@"
  grep -qF -- "$text" "$work/err" || fail "$*: stderr lacks '$text': $(head -c 300 "$work/err")"
}

for program in "$@"; do
  if [ ! -x "$bin_dir/$program" ]; then
    fail "$program: not built in $bin_dir"
    continue
  fi
  expect 0 "$program" --help
  expect_message 2 "unknown option '--no-such-option'" "$program" --no-such-option
  case $program in
    bluetile_bench)
      expect_message 2 "--sizes 'abc': not a number" "$program" --sizes abc
      expect_message 2 "--engines 'bogus': unknown name; expected one of exact, cgal-periodic, cgal-band, raster" \
        "$program" --engines bogus
      expect 2 "$program" --repeats 0
      expect 2 "$program" --threads -3
      expect 2 "$program" --seed nan
      expect 2 "$program" --starts random,sideways
      expect 2 "$program" --sizes
      ;;
    bluetile_progressive_bench)
      expect 0 "$program" sets --help
      expect_message 2 "mode 'abc': unknown mode" "$program" abc
      expect 2 "$program" frobnicate 4
      expect 2 "$program" 0
      expect 2 "$program" -5
      expect 2 "$program" 100 0
      expect 2 "$program" prefixes 10 0
      expect 2 "$program" prefixes 256 1 nan
      expect 2 "$program" prefixes 256 1 -1
      expect 2 "$program" sets 2 0
      expect_message 2 "N '100': expected a multiple of 16" "$program" anchors 100 1
      expect 2 "$program" sets 2 8 9
      expect 0 "$program" sets 2 8
      ;;
    bluetile_plot_order_bench)
      expect_message 2 "N 'abc': not a number" "$program" abc
      expect 2 "$program" -- -1
      expect 2 "$program" 0
      expect 0 "$program" 100
      ;;
    bluetile_wang_bench)
      expect_message 2 "mode 'bogus': unknown name; expected one of quality, time, levels" "$program" bogus
      expect 2 "$program" quality --seeds 0
      expect 2 "$program" time --repeats 0
      expect 2 "$program" --set wang9
      expect 2 "$program" --ratio 1
      expect_message 2 "--plot 'x.svg': only in levels mode" "$program" quality --plot x.svg
      ;;
    bluetile_tiler_bench)
      expect 2 "$program" --throughput --repeats 0
      expect 2 "$program" --ramp --counts 0 --seeds 1 --repeats 1
      expect 2 "$program" --range 0
      expect_message 2 "--range-image 'x.png': needs --range" "$program" --range-image x.png
      expect_message 1 "/nonexistent.tiles" "$program" --tiles /nonexistent.tiles --throughput --repeats 1
      ;;
    bluetile_density_integration_bench)
      expect 2 "$program" --counts 0 --repeats 1
      expect 2 "$program" --repeats 0
      ;;
    bluetile_stipple_bench)
      expect 2 "$program" --counts 100 --iterations 2 --repeats 0 --engines exact
      expect 2 "$program" --engines exact,bogus
      expect_message 1 "/nonexistent.png" "$program" --image /nonexistent.png --counts 100 --iterations 2 --repeats 1 \
        --engines exact
      ;;
    bluetile_raster_profile)
      expect_message 2 "--jobs 'bogus': unknown name; expected one of paper, n1e4" "$program" --jobs bogus
      expect 2 "$program" --repeats 0
      expect 2 "$program" --repeats -1
      expect 2 "$program" --split-kernels group
      ;;
    bluetile_degenerate_bench)
      expect 2 "$program" --engine exact --sizes 200 --repeats 0 --kinds line
      expect_message 2 "--kinds 'bogus': unknown name; expected one of uniform, line" "$program" --kinds bogus
      expect 2 "$program" --sizes 0
      expect 2 "$program" --threads -3
      expect_message 2 "only with --engine raster" "$program" --engine exact --max-cone-overlap 0
      ;;
    bluetile_periodogram_bench)
      expect 2 "$program" -n 0
      expect 2 "$program" --threads 0
      expect 2 "$program" --direct-max abc
      expect 0 "$program" -n 100 --threads 1
      ;;
    bluetile_topology_bench)
      expect 2 "$program" --sizes 100 --repeats 0 --engines kept
      expect 2 "$program" --engines bogus
      expect 2 "$program" --profile bogus
      expect 2 "$program" --sizes 0
      ;;
    *)
      fail "$program: no cases in $0 (add some)"
      ;;
  esac
done

finish
