#!/usr/bin/env bash
# Fails when a tracked C++ file differs from the project's .clang-format style (names the files).
set -euo pipefail
cd "$1"
formatter="${2:-clang-format}"
mapfile -t files < <(git ls-files '*.cpp' '*.h')
unformatted=()
for file in "${files[@]}"; do
  "$formatter" --dry-run --Werror "$file" >/dev/null 2>&1 || unformatted+=("$file")
done
if [ ${#unformatted[@]} -ne 0 ]; then
  echo "not in .clang-format style (run clang-format -i on them):"
  printf '  %s\n' "${unformatted[@]}"
  exit 1
fi
echo "${#files[@]} C++ files in .clang-format style"
