#!/usr/bin/env bash
# Installs the built arcplan into a temporary prefix, then configures, builds and runs
# examples/consumer against it with find_package(arcplan): the way users import the library.
set -euo pipefail
build_dir="$1"
source_dir="$2"
consumer_flags="${3:-}"  # compiler and linker flags of the consumer (the sanitizers of a sanitized build)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" >/dev/null
cmake -S "$source_dir/examples/consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS="$consumer_flags" -DCMAKE_EXE_LINKER_FLAGS="$consumer_flags" >/dev/null
cmake --build "$work/build" -j 2 >/dev/null
# The installed data (URDF, meshes, scenes) must be found from the install tree, not the sources.
mv "$work/prefix" "$work/moved_prefix"
export LD_LIBRARY_PATH="$work/moved_prefix/lib:${LD_LIBRARY_PATH:-}"
output="$("$work/build/plan_thesis_arc")"
echo "$output"
# Thesis case (d): the analytic arc length 0.8825 m, about 3.73 s at 0.25 m/s.
grep -Eq "tcp path length 0\.882[0-9]* m, execution time 3\.7[0-9]* s" <<<"$output"
