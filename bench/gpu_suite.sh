#!/usr/bin/env bash
# The GPU benchmarks of lightpass in one go, each as one `lightpass bench` process (one scene load,
# every variant timed in turn; medians after warm-up; floors measured on the same GPU).
#   bench/gpu_suite.sh LIGHTPASS OUTDIR [PART ...]
# PART: lights shadows ibl post frame sweep products scale scene peers visibility (default: all). Needs ../shared/assets for the gallery scene and
# the Poly Haven maps. Tables: bench/summarize_bench.py OUTDIR/<part>.json (see bench/results/*/README.md).
set -uo pipefail
lp=$1 out=$2
shift 2
parts=${*:-lights shadows ibl post frame sweep products scale scene peers visibility}
mkdir -p "$out"
maps="hdr/sky.exr"
for m in ../shared/assets/hdri-polyhaven-1k/*.hdr ../shared/assets/hdri-polyhaven-1k/*.exr; do [ -f "$m" ] && maps="$maps $m"; done

for part in $parts; do
  echo "== $part"
  case $part in
    lights)  # each local-light method x light count x size on the Stanford models
      "$lp" bench --scene scenes/gallery.json --frames 100 --warmup 10 --floors --max-seconds 3 --min-frames 3 \
        --vary '--local-lights fullscreen,scissor,volumes,tiled' --vary '--light-count 1,32,256,1024,4096' \
        --vary '--size 1920x1080,3840x2160' --timings-json "$out/local_lights.json" ;;
    shadows)  # shadow map size x PCF kernel, two shadow-casting suns
      "$lp" bench --scene scenes/gallery.json --size 1920x1080 --frames 100 --floors --no-local-lights \
        --vary '--shadow-size 512,1024,2048,4096' --vary '--pcf off,3x3,5x5,poisson' \
        --timings-json "$out/shadows.json" ;;
    ibl)  # bake time per map and setting (one process per bake: wall time incl. the CPU SH), then pass ms
      : > "$out/ibl_bakes.txt"
      for map in $maps; do
        scene=$(mktemp --suffix=.json)
        python3 - "$map" "$scene" <<'PY'
import json, os, sys
d = json.load(open("scenes/ibl-spheres.json"))
d["environment"]["map"] = os.path.abspath(sys.argv[1])
json.dump(d, open(sys.argv[2], "w"))
PY
        for setting in "--ibl-samples 64" "--ibl-samples 256" "--ibl-samples 1024" \
                       "--ibl-samples 256 --ibl-specular-size 128" "--ibl-samples 256 --ibl-specular-size 512"; do
          line=$("$lp" render --scene "$scene" --ibl $setting --size 64x64 --out "$out/bake.png" 2>&1 | grep -E "ibl: baked|-> cubemap" | tr '\n' ' ')
          echo "$(basename "$map") | $setting | $line" | tee -a "$out/ibl_bakes.txt"
        done
        rm -f "$scene"
      done
      "$lp" bench --scene scenes/ibl-spheres.json --frames 100 --floors \
        --vary '--brdf-only|--ibl|--ibl --ibl-diffuse cubemap' --vary '--size 1920x1080,3840x2160' \
        --timings-json "$out/ibl.json" ;;
    post)  # bloom ms vs kernel size per implementation, toon, interop (seed 001's table, redone)
      "$lp" bench --scene scenes/cornell.json --frames 100 --floors --bloom \
        --vary '--post-backend glsl|--post-backend glsl --bloom-blur fragment|--post-backend glsl --bloom-method mip-chain|--post-backend cuda|--post-backend cuda --bloom-method mip-chain' \
        --vary '--bloom-kernel 5,10,25,50,100' --vary '--size 1920x1080,3840x2160' \
        --timings-json "$out/bloom.json"
      "$lp" bench --scene scenes/cornell.json --frames 100 --floors --toon \
        --vary '--post-backend glsl,cuda' --vary '--size 1920x1080,3840x2160' --timings-json "$out/toon.json" ;;
    frame)  # every bundled scene, default settings
      for s in cornell gallery ibl-spheres unlit; do
        "$lp" bench --scene scenes/$s.json --frames 200 --warmup 30 --floors \
          --vary '--size 1920x1080,3840x2160' --timings-json "$out/frame_$s.json"
      done ;;
    sweep)  # every quality knob: GPU ms against error vs the knob's best value (bench/sweep_report.py adds FLIP)
      "$lp" sweep --scene scenes/cornell.json --size 1920x1080 --frames 100 \
        --knob gbuffer-format --knob gbuffer-position --knob shadow-size --knob shadow-pcf --knob shadow-cascades \
        --knob local-light-method --knob light-range-cutoff --knob bloom-kernel --knob bloom-method \
        --out-dir "$out/sweep_cornell"
      "$lp" sweep --scene scenes/ibl-spheres.json --size 1920x1080 --frames 100 \
        --knob ibl-samples --knob ibl-face-size --knob ibl-diffuse --out-dir "$out/sweep_ibl" ;;
    products)  # knobs that interact, swept together (every combination; the Pareto front picks the pairs)
      "$lp" sweep --scene scenes/cornell.json --size 1920x1080 --frames 100 \
        --knob shadow-size+shadow-pcf --knob bloom-method+bloom-kernel --out-dir "$out/sweep_products_cornell"
      "$lp" sweep --scene scenes/ibl-spheres.json --size 1920x1080 --frames 100 \
        --knob ibl-samples+ibl-face-size --out-dir "$out/sweep_products_ibl" ;;
    scale)  # --render-scale: the small Cornell box at 1080p, the Stanford models with two shadowed suns at 4K
      "$lp" sweep --scene scenes/cornell.json --size 1920x1080 --frames 100 --knob render-scale \
        --out-dir "$out/sweep_render_scale_cornell"
      "$lp" sweep --scene scenes/gallery.json --size 3840x2160 --frames 100 --knob render-scale \
        --out-dir "$out/sweep_render_scale_gallery_4k"
      "$lp" bench --scene scenes/gallery.json --frames 100 --warmup 10 --floors \
        --vary '--render-scale 0.25,0.5,0.75,1' --vary '--size 1920x1080,3840x2160' \
        --timings-json "$out/render_scale.json" ;;
    visibility)  # the G-buffer stage, classic raster against the visibility buffer (bench/visibility.sh's runs)
      for s in gallery cornell; do
        "$lp" bench --scene scenes/$s.json --frames 100 --warmup 10 --floors --max-seconds 4 --min-frames 10 \
          --vary '--gbuffer-mode classic,visibility' \
          --vary '--gbuffer unpacked --gbuffer-position stored|--gbuffer oct32 --gbuffer-position depth' \
          --vary '--size 1920x1080,3840x2160' --timings-json "$out/visibility_$s.json"
      done
      "$lp" sweep --scene scenes/gallery.json --size 3840x2160 --frames 100 --knob gbuffer-mode \
        --out-dir "$out/sweep_gbuffer_mode"
      python3 bench/summarize_visibility.py "$out/visibility_gallery.json" "$out/visibility_cornell.json" \
        --sweep "$out/sweep_gbuffer_mode/sweep.csv" > "$out/visibility.md" ;;
    scene)  # scene-driven graph against every pass forced on
      bench/scene_driven.sh "$lp" 1920x1080 200 30 "$out/scene_driven" ;;
    peers)  # lightpass against Filament (filly wheel from peers-wheels/ beside the bundle): OUTDIR/peers.md
      bench/peers/run.sh "$lp" "$out" ;;
    *) echo "unknown part $part" >&2; exit 2 ;;
  esac
done
