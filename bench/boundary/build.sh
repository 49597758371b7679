#!/usr/bin/env bash
# Builds bench/boundary/experiment against a built urbanvec library (default: build/, or the folder
# given as $1) and prints the program's path. Usage: bench/boundary/build.sh [build-folder]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
cmake --build "$build" --target urbanvec -j2 >&2
out="$build/bench/boundary_experiment"
mkdir -p "$(dirname "$out")"
g++ -O2 -std=c++17 -pthread -I"$root/src" "$here/experiment.cpp" "$build/lib/liburbanvec.a" -lgeos_c -o "$out"
echo "$out"
