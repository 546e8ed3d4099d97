#!/usr/bin/env bash
# Installs this build into a temporary prefix, builds examples/cpp against it
# with find_package(obscura), runs the program and checks what it prints.
# Usage: consumer_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
test -f "$work/prefix/include/obscura/obscura.h"
test -f "$work/prefix/lib/cmake/obscura/obscuraConfig.cmake"
test -f "$work/prefix/share/obscura/validation/slab_reference.csv"
cmake -S "$source/examples/cpp" -B "$work/example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/example" >/dev/null
out=$("$work/example/puff_radiance")
echo "$out"
# The plate (330 K, ε 0.9) and the 250 K sky bound what the camera can see.
echo "$out" | grep -Eq '^obscura [0-9.]+: 64x48 px, mean LWIR radiance [0-9.]+ W m-2 sr-1, apparent temperature 2[0-9][0-9]\.[0-9]+-3[0-3][0-9]\.[0-9]+ K$'
