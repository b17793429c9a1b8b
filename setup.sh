#!/usr/bin/env bash
# bluetile set-up: installs the Debian packages that are missing, configures and builds,
# then runs what was asked.
#
#   ./setup.sh demo [DIR]   build, then relax 1000 points (80 iterations) and write the points,
#                           images and a report to DIR (default: out/ in the repository; a
#                           relative DIR is taken from the folder you run the script in)
#   ./setup.sh test         build, then run the whole test suite (ctest); build the Python module
#                           with pip into a virtual environment (build/python-venv) and run its
#                           tests (pytest); then build the suite with address + undefined
#                           sanitizers (in build-sanitize/) and run it again, and fuzz every file
#                           reader briefly with libFuzzer (clang, in build-fuzz/). The Python pass
#                           needs network access: pip fetches scikit-build-core and nanobind.
#   ./setup.sh build        install and build only
#   ./setup.sh help         this text (also -h, --help)
#
# Environment: BLUETILE_BUILD_DIR (default build in the repository; a relative one is taken from
# the folder you run the script in), BLUETILE_BUILD_TYPE (default Release), BLUETILE_SANITIZE=OFF
# skips the sanitizer pass of `test` (fuzzing included), BLUETILE_PYTHON=OFF its Python pass (both
# take ON/on/1/yes/true or OFF/off/0/no/false), BLUETILE_FUZZ_SECONDS (default 10, a whole number
# from 1 to 86400) sets each fuzz target's run. BLUETILE_BUILD_TYPE is one of Release, Debug,
# RelWithDebInfo and MinSizeRel (any case).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
self=$here/$(basename "${BASH_SOURCE[0]}")

# The comment block above, without its '# '.
usage() {
  sed -n '2,/^[^#]/p' "$self" | sed '$d' | sed 's/^# \{0,1\}//'
}

# usage_error MESSAGE: the message and the usage on stderr, exit status 2.
usage_error() {
  echo "setup.sh: $1" >&2
  usage >&2
  exit 2
}

# on_off NAME DEFAULT: ON or OFF for the environment variable NAME (DEFAULT when unset or empty),
# into the variable of that name in lower case; any other spelling is refused.
on_off() {
  local name=$1 value=${!1:-$2}
  case ${value,,} in
    on | 1 | yes | true) printf -v "${name,,}" ON ;;
    off | 0 | no | false) printf -v "${name,,}" OFF ;;
    *) usage_error "$name='$value': expected ON, on, 1, yes or true, or OFF, off, 0, no or false" ;;
  esac
}

# Everything asked for is checked here, before anything is installed or built. Paths given
# relative are taken from the caller's folder; the defaults live in the repository.
caller=$PWD
absolute() {
  case $1 in
    /*) printf '%s\n' "$1" ;;
    *) printf '%s\n' "$caller/$1" ;;
  esac
}
# The arguments, each in quotes, for messages.
quoted() {
  local a list=()
  for a in "$@"; do list+=("'$a'"); done
  echo "${list[*]}"
}
what=${1:-}
if [ $# -gt 0 ]; then shift; fi
case "$what" in
  demo)
    [ $# -le 1 ] || usage_error "demo takes one folder at most, got $(quoted "$@")"
    out=out
    if [ $# -eq 1 ]; then
      case $1 in
        "") usage_error "demo: the folder name is empty" ;;
        -*) usage_error "demo: '$1' looks like an option, not a folder (write ./$1 for a folder of that name)" ;;
      esac
      out=$(absolute "$1")
    fi
    ;;
  test | build)
    [ $# -eq 0 ] || usage_error "$what takes no arguments, got $(quoted "$@")"
    ;;
  help | -h | --help)
    [ $# -eq 0 ] || usage_error "$what takes no arguments, got $(quoted "$@")"
    usage
    exit 0
    ;;
  "") usage_error "no command given" ;;
  *) usage_error "unknown command '$what'" ;;
esac
if [ "$what" = test ]; then
  on_off BLUETILE_SANITIZE ON
  on_off BLUETILE_PYTHON ON
  # libFuzzer reads 0 as no limit and ignores what is not a number: both would fuzz for ever.
  fuzz_seconds=${BLUETILE_FUZZ_SECONDS:-10}
  [[ $fuzz_seconds =~ ^[0-9]{1,5}$ ]] && [ $((10#$fuzz_seconds)) -ge 1 ] && [ $((10#$fuzz_seconds)) -le 86400 ] ||
    usage_error "BLUETILE_FUZZ_SECONDS='$fuzz_seconds': expected a whole number of seconds from 1 to 86400"
  fuzz_seconds=$((10#$fuzz_seconds))
fi
build_dir=build
[ -z "${BLUETILE_BUILD_DIR:-}" ] || build_dir=$(absolute "$BLUETILE_BUILD_DIR")
# CMake takes any build type without a word and builds it with no optimisation flags.
build_type=${BLUETILE_BUILD_TYPE:-Release}
case ${build_type,,} in
  release) build_type=Release ;;
  debug) build_type=Debug ;;
  relwithdebinfo) build_type=RelWithDebInfo ;;
  minsizerel) build_type=MinSizeRel ;;
  *) usage_error "BLUETILE_BUILD_TYPE='$build_type': expected Release, Debug, RelWithDebInfo or MinSizeRel" ;;
esac
cd "$here"

# Packages the library, the tool and its tests need (cairo: PDF output, through a plugin
# module; expat and poppler's pdfinfo: the tests read SVG and PDF back; clang and its runtime
# libraries: libFuzzer for the fuzz targets). CGAL is only for the
# optional reference benchmark (GPL, never linked into the library).
packages=(
  cmake ninja-build g++ pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libglm-dev libopenimageio-dev libcli11-dev nlohmann-json3-dev libgtest-dev
  libcairo2-dev libexpat1-dev poppler-utils
  libcgal-dev
  clang libclang-rt-dev
  python3-venv python3-dev python3-numpy python3-pytest python3-dask
)

install_missing() {
  local missing=()
  for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "setup: installing ${missing[*]}" >&2
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  # A stale package list makes installs fail; refresh it once when anything is missing.
  "${sudo[@]}" apt-get update -qq
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# build DIR CMAKE_ARGS... [--target T]: configures (once) and builds into DIR (only T if given).
build() {
  local dir=$1
  shift
  local args=() target=()
  while [ $# -gt 0 ]; do
    if [ "$1" = --target ]; then target=(--target "$2"); shift 2; else args+=("$1"); shift; fi
  done
  cmake -S . -B "$dir" -G Ninja "${args[@]}" >/dev/null
  cmake --build "$dir" "${target[@]}"
}

run_tests() {
  local dir=$1
  ctest --test-dir "$dir" --output-on-failure -j 2
}

# The Python module the README's way (pip install . in a virtual environment), then its tests.
# Debian's Python with its numpy and pytest (a venv that sees the system packages); the build
# backend and the binding library come from the package index, as Debian 12 has neither.
python_tests() {
  local venv="$build_dir/python-venv"
  [ -x "$venv/bin/python" ] || /usr/bin/python3 -m venv --system-site-packages "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check "scikit-build-core>=0.10" "nanobind>=2.4"
  # No build isolation: the build folder (build/python-*) and its objects are kept between runs.
  "$venv/bin/pip" install -q --disable-pip-version-check --no-build-isolation "$here"
  BLUETILE_BINARY="$(cd "$build_dir" && pwd)/bluetile" "$venv/bin/python" -m pytest -q -p no:cacheprovider "$here/python/tests"
}

# Each libFuzzer target for a few seconds, under address + undefined sanitizers, from the seed
# corpus in fuzz/corpus/ (new inputs go to a scratch folder, not into the repository; an input
# that fails is kept in build-fuzz/ as crash-*). A fixed seed makes the run repeatable.
fuzz_readers() {
  local dir="$build_dir-fuzz"
  # Images on (density_map: OpenImageIO through the plugin module, not instrumented); no raster.
  build "$dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBLUETILE_FUZZ=ON \
    -DBLUETILE_IMAGES=ON -DBLUETILE_RASTER=OFF -DBLUETILE_BUILD_TOOL=OFF -DBLUETILE_BUILD_TESTS=OFF \
    -DBLUETILE_BUILD_BENCH=OFF -DBLUETILE_INSTALL=OFF --target bluetile_fuzzers
  local scratch
  scratch=$(mktemp -d)
  for reader in point_file tile_set tile_set_semantics point_table density_map; do
    mkdir -p "$scratch/$reader"
    local malloc_limit=1024 leaks=
    if [ "$reader" = density_map ]; then
      # OpenEXR allocates what a damaged header claims (2 GB for an attribute) before it finds the
      # file short; those pages are never touched (the RSS limit still holds). One leak inside
      # OpenImageIO is suppressed (fuzz/density_map.supp says which).
      malloc_limit=8192
      leaks="suppressions=$here/fuzz/density_map.supp"
    fi
    LSAN_OPTIONS="$leaks" "$dir/bluetile_fuzz_$reader" -max_total_time="$fuzz_seconds" -rss_limit_mb=2048 \
      -malloc_limit_mb="$malloc_limit" -timeout=10 -seed=1 -print_final_stats=1 -artifact_prefix="$dir/" \
      "$scratch/$reader" "fuzz/corpus/$reader" \
      2>"$scratch/$reader.log" || { tail -50 "$scratch/$reader.log" >&2; rm -rf "$scratch"; exit 1; }
    grep -h "stat::number_of_executed_units" "$scratch/$reader.log" | sed "s/^/setup: fuzz $reader: /" >&2
  done
  rm -rf "$scratch"
}

# demo DIR
demo() {
  local out=$1
  mkdir -p -- "$out"
  local bin="$build_dir/bluetile"
  "$bin" relax --count 1000 --iterations 80 --seed 1 --output "$out/points.txt" \
    --log "$out/relax-log.csv"
  # analyze prints the report (also written to report.txt) on stdout.
  "$bin" analyze --input "$out/points.txt" --output "$out"
  echo "setup: wrote $out/points.txt, $out/relax-log.csv and the analysis in $out/" >&2
}

case "$what" in
  demo)
    install_missing
    # Only the tool: the tests and benchmarks are built by `test` and `build`.
    build "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" --target bluetile
    demo "$out"
    ;;
  test)
    install_missing
    build "$build_dir" -DCMAKE_BUILD_TYPE="$build_type"
    run_tests "$build_dir"
    if [ "$bluetile_python" = ON ]; then
      echo "setup: the Python module (pip install . into $build_dir/python-venv) and its tests" >&2
      python_tests
    fi
    # The same tests once more with address + undefined-behaviour sanitizers.
    if [ "$bluetile_sanitize" = ON ]; then
      echo "setup: tests under address + undefined sanitizers" >&2
      # -O1 -g1 (line tables: reports keep their file and line): compiling with both sanitizers
      # at RelWithDebInfo's -O2 -g took 2.1-2.4x as long, the largest part of this pass on 2 cores.
      build "$build_dir-sanitize" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
        -DBLUETILE_SANITIZE=ON -DBLUETILE_BUILD_BENCH=OFF
      run_tests "$build_dir-sanitize"
      echo "setup: fuzzing the file readers (libFuzzer, $fuzz_seconds s each)" >&2
      fuzz_readers
    fi
    ;;
  build)
    install_missing
    build "$build_dir" -DCMAKE_BUILD_TYPE="$build_type"
    ;;
esac
