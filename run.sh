#!/usr/bin/env bash
# fibrecheck on a fresh Debian machine:
#   ./run.sh        install what is missing, build into build/, solve the default scenes, summarise
#   ./run.sh test   the same set-up, then the test suite (ctest)
set -euo pipefail
cd "$(dirname "$0")"

mode="${1:-main}"
case "$mode" in
  main|test) ;;
  *) echo "usage: ./run.sh [test]" >&2; exit 2 ;;
esac

# Debian packages the project builds and runs with.
packages=(build-essential cmake libeigen3-dev nlohmann-json3-dev libcli11-dev libgtest-dev
          libbenchmark-dev gnuplot-nox libdeal.ii-dev gmsh libgmsh-dev openmpi-bin)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [ "$(id -u)" -ne 0 ]; then
    echo "Missing Debian packages: ${missing[*]}" >&2
    echo "Install them with:" >&2
    echo "  sudo apt-get update && sudo apt-get install -y --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
  echo "Installing missing Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$jobs"

if [ "$mode" = test ]; then
  cd build
  exec ctest --output-on-failure -j "$jobs"
fi

# The main job: every scene through the iterative solver (with a summary table), then through the
# finite-element reference.
mkdir -p build/results
status=0
./build/fibrecheck solve scenes/*.json --out-dir build/results || status=$?
if [ "$status" -ne 0 ] && [ "$status" -ne 3 ]; then exit "$status"; fi
if ./build/fibrecheck fem --help >/dev/null 2>&1; then
  for scene in scenes/*.json; do
    name=$(basename "$scene" .json)
    echo
    fem_status=0
    ./build/fibrecheck fem "$scene" --out "build/results/$name.fem.json" 2>/dev/null \
      | grep -v '^[|+]' | grep -v '^$' || fem_status=$?
    if [ "$fem_status" -ne 0 ] && [ "$fem_status" -ne 3 ]; then exit "$fem_status"; fi
  done
fi
echo
echo "Results (JSON, schema in README.md) are in build/results/."
exit "$status"
