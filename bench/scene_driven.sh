#!/usr/bin/env bash
# Scene-driven frame graph against every candidate pass forced on (--all-passes): frame time and
# texture memory of each bundled scene, both ways in one run, summarised into a Markdown table.
#   bench/scene_driven.sh [LIGHTPASS] [SIZE] [FRAMES] [WARMUP] [OUTDIR]
# gallery needs ../shared/assets; it is left out (with a note) when they are absent.
set -euo pipefail
lp=${1:-build/app/lightpass}
size=${2:-1920x1080}
frames=${3:-200}
warmup=${4:-30}
out=${5:-bench/results/frame/$(date +%F)_scene-driven-graph}
here=$(cd "$(dirname "$0")" && pwd)
scenes="$here/../scenes"
mkdir -p "$out"
jsons=()
for name in cornell gallery lights-4k ibl-spheres unlit; do
  if [ "$name" = gallery ] && [ ! -d "$here/../../shared/assets/stanford-dragon" ]; then
    echo "gallery: skipped (../shared/assets not found)" >&2
    continue
  fi
  for mode in scene all; do
    flag=()
    [ "$mode" = all ] && flag=(--all-passes)
    "$lp" render --scene "$scenes/$name.json" --size "$size" --frames "$frames" --warmup "$warmup" -q \
          "${flag[@]}" --out "$out/${name}_${mode}.png" --timings-json "$out/${name}_${mode}.json" >/dev/null
    jsons+=("$out/${name}_${mode}.json")
  done
done
python3 "$here/summarize_scene_driven.py" "${jsons[@]}" > "$out/scene_driven.md"
cat "$out/scene_driven.md"
