#!/usr/bin/env bash
# lightpass against Google Filament (through filly) on the same scenes, one table: issue #19's.
#   bench/peers/run.sh LIGHTPASS OUTDIR          (bench/gpu_suite.sh LIGHTPASS OUTDIR peers runs it)
# From the repository root, on the GPU machine. LIGHTPASS is the bundle's `run` (or the executable).
# Per scene (gallery: 1 sun; cornell: 1 sun + its 3 point lights):
#   1. bench/peers/scene_to_glb.py -> WORK/NAME.{glb,peer.json,lightpass.json}
#   2. lightpass bench on NAME.lightpass.json at 1920x1080 and 3840x2160: one sun cascade, IBL, no
#      bloom/AA/AO/dithering, ACES  -> OUTDIR/peers_lightpass_NAME.json
#   3. bench/peers/filament.py at both sizes                -> OUTDIR/peers_filament_NAME_WxH.json
#   4. bench/peers/summarize_peers.py                      -> OUTDIR/peers.md
# Filament needs Python >= 3.12 and the wheels folder (bench/peers/README.md): PEERS_PYTHON (default:
# the first python3.1x >= 3.12 on PATH, else the one carried in peers-wheels/python), PEERS_WHEELS
# (default: peers-wheels beside or above LIGHTPASS). Without them lightpass is still timed and the
# table leaves Filament's columns empty.
# PEERS_FRAMES (200), PEERS_WARMUP (30), PEERS_SIZES ("1920x1080 3840x2160") shorten a trial run.
# WORK (PEERS_WORK, default $TMPDIR/lightpass-peers-work) keeps the converted scenes (the gallery GLB
# is 7 MB) and one image per renderer and scene at the first size, out of the results folder.
set -uo pipefail
lp=$1 out=$2
frames=${PEERS_FRAMES:-200} warmup=${PEERS_WARMUP:-30} sizes=${PEERS_SIZES:-1920x1080 3840x2160}
work=${PEERS_WORK:-${TMPDIR:-/tmp}/lightpass-peers-work}
mkdir -p "$out" "$work"
lp_dir=$(cd "$(dirname "$lp")" && pwd)

# ---- Python >= 3.12 with filly and numpy, from the carried wheels (unpacked: no venv or pip needed)
wheels=${PEERS_WHEELS:-}
if [ -z "$wheels" ]; then
  for c in "$lp_dir/peers-wheels" "$lp_dir/../peers-wheels"; do
    if ls "$c"/filly-*.whl >/dev/null 2>&1; then wheels=$(cd "$c" && pwd); break; fi
  done
fi
py=${PEERS_PYTHON:-}
if [ -z "$py" ]; then
  for c in python3.12 python3.13 python3.14 python3; do
    if command -v "$c" >/dev/null 2>&1 && "$c" -c 'import sys; sys.exit(sys.version_info < (3, 12))' 2>/dev/null; then
      py=$(command -v "$c"); break
    fi
  done
fi
if [ -z "$py" ] && [ -n "$wheels" ] && [ -x "$wheels/python/bin/python3.12" ]; then
  # The CPython 3.12 that make_wheels.sh --python carried: its libpython and libraries beside it.
  py=$wheels/python/bin/python3.12
  export LD_LIBRARY_PATH="$wheels/python/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
filament_ok=1
if [ -z "$py" ]; then
  echo "peers: Filament needs Python >= 3.12 (the filly wheel is cp312-abi3) and none is on PATH" \
       "(python3 is $(python3 --version 2>&1)) nor carried in peers-wheels/python (make_wheels.sh --python PREFIX);" \
       "set PEERS_PYTHON=/path/to/python3.12. Timing lightpass only." >&2
  filament_ok=0
elif [ -z "$wheels" ] || ! ls "$wheels"/filly-*.whl >/dev/null 2>&1; then
  echo "peers: no filly wheel: expected peers-wheels/ beside $lp (bench/peers/make_wheels.sh makes it) or" \
       "PEERS_WHEELS=DIR. Timing lightpass only." >&2
  filament_ok=0
fi
if [ "$filament_ok" = 1 ]; then
  site=${PEERS_SITE:-${TMPDIR:-/tmp}/lightpass-peers-site}
  stamp=$(cd "$wheels" && ls *.whl | sort | tr '\n' ' ')
  if [ "$(cat "$site/.wheels" 2>/dev/null)" != "$stamp" ]; then
    rm -rf "$site" && mkdir -p "$site"
    for w in "$wheels"/*.whl; do "$py" -m zipfile -e "$w" "$site" || { echo "peers: cannot unpack $w" >&2; filament_ok=0; }; done
    echo "$stamp" > "$site/.wheels"
  fi
  export PYTHONPATH="$site${PYTHONPATH:+:$PYTHONPATH}"
  libs="$wheels/lib"
  # glvnd's libGL.so.1 from the bundle only where the machine has none (its own matches its libEGL).
  "$py" -c 'import ctypes; ctypes.CDLL("libGL.so.1")' 2>/dev/null || libs="$libs:$wheels/lib-glvnd"
  export LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  if ! "$py" -c 'import filly, numpy' 2> "$work/import_error.txt"; then
    echo "peers: $py cannot import filly: $(tail -1 "$work/import_error.txt"). Timing lightpass only." >&2
    filament_ok=0
  fi
fi
conv_py=python3
[ "$filament_ok" = 1 ] && conv_py=$py  # its numpy comes from the wheels
"$conv_py" -c 'import numpy' 2>/dev/null || { echo "peers: $conv_py has no numpy for bench/peers/scene_to_glb.py" >&2; exit 1; }

vary_sizes=$(echo $sizes | tr ' ' ',')
lp_flags=(--frames "$frames" --warmup "$warmup" --ibl --shadow-cascades 1 --shadow-size 2048 --no-bloom --aa off
          --no-ao --no-dither --tonemap aces)
# PEERS_LIGHTPASS_FLAGS: more lightpass flags for the same matched work (e.g. --gbuffer-mode visibility).
read -r -a more_flags <<< "${PEERS_LIGHTPASS_FLAGS:-}"
lp_flags+=("${more_flags[@]}")
names=()
# NAME SCENE CONVERTER-FLAGS (the light subset: the issue's "gallery, 1 sun" and "cornell, 1 sun, 3 points")
for spec in "gallery scenes/gallery.json --suns 1 --points 0" "cornell scenes/cornell.json --suns 1"; do
  read -r name scene conv <<< "$spec"
  echo "== peers: $name"
  rm -f "$out/peers_lightpass_$name.json" "$out"/peers_filament_"$name"_*.json  # no stale numbers in the table
  if ! "$conv_py" bench/peers/scene_to_glb.py "$scene" --out-dir "$work" --name "$name" $conv; then
    echo "peers: converting $scene failed" >&2; continue
  fi
  names+=("$name")
  extra=()
  [ "$("$conv_py" -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["points"]))' "$work/$name.peer.json")" = 0 ] \
    && extra=(--no-local-lights)
  "$lp" bench --scene "$work/$name.lightpass.json" "${lp_flags[@]}" "${extra[@]}" --floors \
    --vary "--size $vary_sizes" --timings-json "$out/peers_lightpass_$name.json" -q \
    || echo "peers: lightpass bench on $name failed" >&2
  first=1
  for size in $sizes; do
    img=()
    if [ "$first" = 1 ]; then  # one image per renderer at the first size, to see that both draw the same scene
      img=(--image "$work/filament_${name}_$size.png")
      "$lp" render --scene "$work/$name.lightpass.json" --ibl --shadow-cascades 1 --shadow-size 2048 --no-bloom \
        --aa off --no-ao --no-dither --tonemap aces "${extra[@]}" --size "$size" --out "$work/lightpass_${name}_$size.png" -q \
        || echo "peers: lightpass render of $name failed" >&2
      first=0
    fi
    if [ "$filament_ok" = 1 ]; then
      "$py" bench/peers/filament.py "$work/$name.peer.json" --size "$size" --frames "$frames" --warmup "$warmup" \
        --shadow-size 2048 --tone-mapping aces --out "$out/peers_filament_${name}_$size.json" "${img[@]}" \
        2> "$work/filament_${name}_$size.log" || echo "peers: Filament on $name $size failed (see $work/filament_${name}_$size.log)" >&2
    fi
  done
done
[ ${#names[@]} -gt 0 ] || { echo "peers: no scene converted" >&2; exit 1; }
echo "peers: converted scenes and one image per renderer and scene in $work"
"$conv_py" bench/peers/summarize_peers.py "$out" "${names[@]}"
