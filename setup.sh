#!/usr/bin/env bash
# bluetile set-up: installs the Debian packages that are missing, configures and builds,
# then runs what was asked.
#
#   ./setup.sh demo [DIR]   build, then relax 1000 points (80 iterations) and write the points,
#                           images and a report to DIR (default: out/)
#   ./setup.sh test         build, then run the whole test suite (ctest), then build it with
#                           address + undefined sanitizers (in build-sanitize/) and run it again
#   ./setup.sh build        install and build only
#
# Environment: BLUETILE_BUILD_DIR (default build), BLUETILE_BUILD_TYPE (default Release),
# BLUETILE_SANITIZE=OFF skips the sanitizer pass of `test`.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cd "$here"

# Packages the library, the tool and its tests need (cairo: PDF output, through a plugin
# module; expat and poppler's pdfinfo: the tests read SVG and PDF back). CGAL is only for the
# optional reference benchmark (GPL, never linked into the library).
packages=(
  cmake ninja-build g++ pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libglm-dev libopenimageio-dev libcli11-dev nlohmann-json3-dev libgtest-dev
  libcairo2-dev libexpat1-dev poppler-utils
  libcgal-dev
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

# build DIR CMAKE_ARGS...: configures (once) and builds into DIR.
build() {
  local dir=$1
  shift
  cmake -S . -B "$dir" -G Ninja "$@" >/dev/null
  cmake --build "$dir"
}

run_tests() {
  local dir=$1
  ctest --test-dir "$dir" --output-on-failure -j 2
}

demo() {
  local out=${1:-out}
  mkdir -p "$out"
  local bin="$build_dir/bluetile"
  "$bin" relax --count 1000 --iterations 80 --seed 1 --output "$out/points.txt" \
    --log "$out/relax-log.csv"
  "$bin" analyze --input "$out/points.txt" --output "$out"
  echo "setup: wrote $out/points.txt, $out/relax-log.csv and the analysis in $out/" >&2
  cat "$out/report.txt"
}

build_dir=${BLUETILE_BUILD_DIR:-build}
build_type=${BLUETILE_BUILD_TYPE:-Release}
what=${1:-}
case "$what" in
  demo)
    install_missing
    build "$build_dir" -DCMAKE_BUILD_TYPE="$build_type"
    shift
    demo "$@"
    ;;
  test)
    install_missing
    build "$build_dir" -DCMAKE_BUILD_TYPE="$build_type"
    run_tests "$build_dir"
    # The same tests once more with address + undefined-behaviour sanitizers.
    if [ "${BLUETILE_SANITIZE:-ON}" = ON ]; then
      echo "setup: tests under address + undefined sanitizers" >&2
      build "$build_dir-sanitize" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBLUETILE_SANITIZE=ON -DBLUETILE_BUILD_BENCH=OFF
      run_tests "$build_dir-sanitize"
    fi
    ;;
  build)
    install_missing
    build "$build_dir" -DCMAKE_BUILD_TYPE="$build_type"
    ;;
  *)
    sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
    ;;
esac
