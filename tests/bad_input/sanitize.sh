#!/usr/bin/env bash
# tests/bad_input/sanitize.sh [BUILD_DIR]: builds the loaders (engine/core, engine/io, engine/scene)
# with AddressSanitizer and UndefinedBehaviorSanitizer into a build folder of their own (default
# build-sanitize/, beside build/; the first build takes a few minutes on two cores, later ones only
# what changed), writes the bad-input corpus (tests/bad_input/make_corpus.py) into it and reads every
# model, scene and image of the corpus with tests/bad_input/load_check: the same loading as lightpass
# (textures decoded, the checker standing in for a bad one), no GPU. Any sanitizer report (an
# out-of-bounds read, a use after free, a leak, an overflowing integer, a misaligned read) stops it;
# so does an exit status other than 0 or 1 (a crash) or a file that takes over 60 s. Prints
# "sanitizer run clean: N files" when none does. Not part of scripts/test: run it after changing a loader.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build-sanitize}"
cmake -S "$root/tests/bad_input/sanitize" -B "$build" -DCMAKE_BUILD_TYPE=Debug >/dev/null
cmake --build "$build" -j"$(nproc)" 2>&1 | grep -vE '^\[ *[0-9]+%\]' || true
test -x "$build/load_check" || { echo "sanitize.sh: build failed" >&2; exit 1; }
corpus="$build/corpus"
python3 "$root/tests/bad_input/make_corpus.py" "$corpus" >/dev/null
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:exitcode=86:check_initialization_order=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=87"
count=0
while IFS= read -r -d '' file; do
  case "$file" in
    *.gltf|*.glb|*.GLTF|*.GLB|*.obj|*.json|*.png|*.jpg|*.tga|*.bmp|*.hdr|*.exr) ;;
    *) continue ;;
  esac
  [ "$(basename "$file")" = manifest.json ] && continue
  [ -f "$file" ] || continue  # FIFOs and folders: the regular-file check, not the loaders
  set +e
  timeout 60 "$build/load_check" "$file" >"$build/last.out" 2>"$build/last.err"
  status=$?
  set -e
  if [ "$status" -ne 0 ] && [ "$status" -ne 1 ]; then
    echo "sanitize.sh: $file: exit status $status" >&2
    tail -n 40 "$build/last.err" >&2
    exit 1
  fi
  count=$((count + 1))
done < <(find "$corpus" -type f -print0 | sort -z)
echo "sanitizer run clean: $count files"
