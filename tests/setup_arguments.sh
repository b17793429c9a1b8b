#!/usr/bin/env bash
# setup.sh's command line and switches, with nothing installed or built: stubs first on PATH stand
# in for cmake and ctest (they log their arguments), dpkg-query (every package installed), and
# apt-get and sudo (reaching them fails the test); a fake build folder holds a `bluetile` and fuzz
# targets that log their arguments.
#   - help, -h, --help: the usage on stdout, nothing on stderr, exit status 0;
#   - an unknown command, no command, extra arguments, an option given as demo's DIR, a switch
#     spelt neither on nor off: "setup.sh: ..." naming it, then the usage, on stderr, nothing on
#     stdout, exit status 2, and nothing run;
#   - a relative DIR and BLUETILE_BUILD_DIR are taken from the caller's folder;
#   - BLUETILE_SANITIZE and BLUETILE_PYTHON take on/1/yes/true and off/0/no/false;
#   - BLUETILE_BUILD_TYPE takes CMake's four build types in any case, BLUETILE_FUZZ_SECONDS 1 to
#     86400; other values are refused as above.
#
#   setup_arguments.sh SETUP_SH
set -u
setup=$1
source "$(dirname "$0")/script_cases.sh"

mkdir -p "$work/stubs" "$work/caller"
for tool in cmake ctest; do
  printf '#!/bin/sh\necho "%s $*" >>"%s/calls"\n' "$tool" "$work" >"$work/stubs/$tool"
done
printf '#!/bin/sh\nprintf "install ok installed"\n' >"$work/stubs/dpkg-query"
for tool in apt-get sudo; do
  printf '#!/bin/sh\necho "%s $*" >>"%s/calls"\nexit 1\n' "$tool" "$work" >"$work/stubs/$tool"
done
chmod +x "$work"/stubs/*

# A build folder (relative to the caller's folder) whose programs log their arguments; the fuzz
# targets print the statistic setup.sh reports.
fake_build() {
  local dir=$work/caller/$1
  mkdir -p "$dir" "$dir-fuzz"
  printf '#!/bin/sh\necho "bluetile $*" >>"%s/calls"\n' "$work" >"$dir/bluetile"
  for reader in point_file tile_set tile_set_semantics point_table density_map; do
    printf '#!/bin/sh\necho "fuzz %s" >>"%s/calls"\necho "stat::number_of_executed_units: 1" >&2\n' \
      "$reader" "$work" >"$dir-fuzz/bluetile_fuzz_$reader"
  done
  chmod +x "$dir/bluetile" "$dir"-fuzz/*
}

# run STATUS ARG...: runs setup.sh from the caller's folder (with the environment in `env_vars`)
# and checks its exit status; leaves stdout, stderr and the logged calls in $work.
env_vars=()
run() {
  local want=$1
  shift
  cases=$((cases + 1))
  shown="${env_vars[*]} setup.sh $*"
  rm -f "$work/calls"
  touch "$work/calls"
  local status=0
  (cd "$work/caller" && env PATH="$work/stubs:$PATH" "${env_vars[@]}" timeout 60 bash "$setup" "$@") \
    >"$work/out" 2>"$work/err" </dev/null || status=$?
  if [ "$status" != "$want" ]; then
    fail "$shown: exit status $status, expected $want; stderr: $(head -c 600 "$work/err")"
    return 1
  fi
}

# refused MESSAGE ARG...: exit status 2, MESSAGE on stderr's first line, the usage after it,
# nothing on stdout, nothing run.
refused() {
  local message=$1
  shift
  run 2 "$@" || return
  local first
  first=$(head -1 "$work/err")
  [ "$first" = "setup.sh: $message" ] || fail "$shown: stderr starts '$first', expected 'setup.sh: $message'"
  grep -q -- "./setup.sh demo \[DIR\]" "$work/err" || fail "$shown: no usage on stderr"
  [ ! -s "$work/out" ] || fail "$shown: output on stdout: $(head -c 300 "$work/out")"
  [ ! -s "$work/calls" ] || fail "$shown: ran $(head -c 300 "$work/calls")"
}

for help in help -h --help; do
  if run 0 "$help"; then
    grep -q -- "./setup.sh demo \[DIR\]" "$work/out" || fail "$shown: no usage on stdout"
    [ ! -s "$work/err" ] || fail "$shown: help wrote to stderr: $(head -c 300 "$work/err")"
    [ ! -s "$work/calls" ] || fail "$shown: ran $(head -c 300 "$work/calls")"
  fi
done

refused "unknown command 'bogus'" bogus
refused "unknown command '--bogus'" --bogus
refused "no command given"
refused "build takes no arguments, got 'extra-arg'" build extra-arg
refused "test takes no arguments, got 'a' 'b'" test a b
refused "help takes no arguments, got 'demo'" help demo
refused "demo takes one folder at most, got 'mydemo' 'extra'" demo mydemo extra
refused "demo: '--help' looks like an option, not a folder (write ./--help for a folder of that name)" demo --help
refused "demo: '-o' looks like an option, not a folder (write ./-o for a folder of that name)" demo -o
refused "demo: the folder name is empty" demo ""
[ ! -e "$work/caller/--help" ] || fail "demo --help made a folder '--help'"

for variable in BLUETILE_SANITIZE BLUETILE_PYTHON; do
  for value in maybe 2 ONN; do
    env_vars=("$variable=$value")
    refused "$variable='$value': expected ON, on, 1, yes or true, or OFF, off, 0, no or false" test
  done
done

# The build type and the fuzzing time were passed on unchecked (a typo built without optimisation;
# libFuzzer runs for ever on 0 and on what is not a number).
for value in abc Releas "" " " "Release " Debug,Release; do
  [ -n "$value" ] || continue  # empty: the default
  env_vars=("BLUETILE_BUILD_TYPE=$value")
  for command in build test demo; do
    refused "BLUETILE_BUILD_TYPE='$value': expected Release, Debug, RelWithDebInfo or MinSizeRel" "$command"
  done
done
for value in abc 0 -1 1.5 10s 86401 999999 " 5" 0x10; do
  env_vars=("BLUETILE_FUZZ_SECONDS=$value")
  refused "BLUETILE_FUZZ_SECONDS='$value': expected a whole number of seconds from 1 to 86400" test
done

# A relative DIR and build folder are the caller's.
fake_build mybuild
env_vars=(BLUETILE_BUILD_DIR=mybuild)
if run 0 demo mydemo; then
  grep -q -- "^cmake -S \. -B $work/caller/mybuild " "$work/calls" ||
    fail "$shown: not configured in the caller's mybuild/: $(cat "$work/calls")"
  grep -q -- "^bluetile relax .* --output $work/caller/mydemo/points.txt" "$work/calls" ||
    fail "$shown: points not written to the caller's mydemo/: $(cat "$work/calls")"
  [ -d "$work/caller/mydemo" ] || fail "$shown: the caller's mydemo/ was not made"
fi

# The switches' spellings: on runs the sanitizer pass and its fuzzing, off skips it; the Python
# pass is only ever switched off here (it would run pip).
for value in ON on 1 yes true True; do
  env_vars=(BLUETILE_BUILD_DIR=mybuild BLUETILE_SANITIZE="$value" BLUETILE_PYTHON=OFF BLUETILE_FUZZ_SECONDS=1)
  if run 0 test; then
    grep -q -- "-B $work/caller/mybuild-sanitize .*-DBLUETILE_SANITIZE=ON" "$work/calls" ||
      fail "$shown: no sanitizer build: $(cat "$work/calls")"
    grep -q "^fuzz density_map" "$work/calls" || fail "$shown: no fuzzing: $(cat "$work/calls")"
  fi
done
# The build types in any case, spelt for CMake; the fuzzing time as given (leading zeros read as
# decimal).
for value in release Release RELEASE debug RelWithDebInfo minsizerel; do
  env_vars=(BLUETILE_BUILD_DIR=mybuild BLUETILE_BUILD_TYPE="$value")
  if run 0 build; then
    case ${value,,} in
      release) want=Release ;; debug) want=Debug ;; relwithdebinfo) want=RelWithDebInfo ;; minsizerel) want=MinSizeRel ;;
    esac
    grep -q -- "-B $work/caller/mybuild .*-DCMAKE_BUILD_TYPE=$want\b" "$work/calls" ||
      fail "$shown: not built as $want: $(cat "$work/calls")"
  fi
done
for value in 1 08 86400; do
  env_vars=(BLUETILE_BUILD_DIR=mybuild BLUETILE_SANITIZE=ON BLUETILE_PYTHON=OFF BLUETILE_FUZZ_SECONDS="$value")
  if run 0 test; then
    grep -q "fuzzing the file readers (libFuzzer, $((10#$value)) s each)" "$work/err" ||
      fail "$shown: fuzzed for other than $((10#$value)) s: $(cat "$work/err")"
  fi
done
for sanitize in OFF off 0 no false; do
  for python in OFF off 0 no false FALSE; do
    env_vars=(BLUETILE_BUILD_DIR=mybuild BLUETILE_SANITIZE="$sanitize" BLUETILE_PYTHON="$python")
    if run 0 test; then
      grep -q -- "-B $work/caller/mybuild " "$work/calls" || fail "$shown: no build: $(cat "$work/calls")"
      grep -q -- "sanitize\|^fuzz" "$work/calls" && fail "$shown: ran the sanitizer pass: $(cat "$work/calls")"
      grep -q "Python" "$work/err" && fail "$shown: ran the Python pass: $(cat "$work/err")"
    fi
  done
done

finish
