#!/usr/bin/env bash
# Configures the source tree (configure only, nothing is built) in a throwaway folder as a machine
# without CUDA would (CUDACXX=/nonexistent: cmake/Cuda.cmake then finds no compiler), and checks that
# CMake says so on stderr (what scripts/build shows) and that CTest lists the CUDA tests as skipped
# with the reason.
#   cuda_absent_configure.sh CMAKE CTEST SOURCE_DIR
set -euo pipefail
cmake_cmd=$1 ctest_cmd=$2 src=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
CUDACXX=/nonexistent "$cmake_cmd" -S "$src" -B "$dir" >"$dir/configure.out" 2>"$dir/configure.err"
if ! grep -q "lightpass: no CUDA toolkit found" "$dir/configure.err"; then
  echo "configure without CUDA printed no notice on stderr:"; cat "$dir/configure.err"; exit 1
fi
out=$(cd "$dir" && "$ctest_cmd" -R '^cuda_tests' -V 2>&1)
if ! grep -qE "CUDA toolkit not found at configure time: [1-9][0-9]* CUDA tests" <<<"$out" ||
   ! grep -qE "cuda_tests_skipped_no_cuda_toolkit .*Skipped" <<<"$out"; then
  echo "ctest without CUDA does not show the CUDA tests as skipped with the reason:"; echo "$out"; exit 1
fi
echo "without CUDA: $(head -n 1 "$dir/configure.err"); $(grep -oE "CUDA toolkit not found[^\"]*skipped$" <<<"$out" | tail -n 1)"
