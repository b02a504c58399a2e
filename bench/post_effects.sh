#!/usr/bin/env bash
# Bloom and toon cost on a GPU machine: bloom ms vs kernel size {5, 10, 25, 50, 100} at
# 1920x1080 and 3840x2160 for CUDA separable, GLSL compute separable, GLSL fragment separable and
# the mip chain (GLSL and CUDA); toon ms (GLSL and CUDA); CUDA interop map/unmap ms; each with its
# floor (bytes the pass must move / this GPU's measured compute copy bandwidth, `render --floors`).
# Prints a Markdown table and keeps the per-run JSON.
#   bench/post_effects.sh [LIGHTPASS] [SCENE] [FRAMES] [OUTDIR]
#   SMOKE=1 bench/post_effects.sh ...   one tiny size and kernel, a few frames (checks the plumbing)
set -euo pipefail
lp=${1:-build/app/lightpass}
scene=${2:-scenes/cornell.json}
frames=${3:-200}
out=${4:-bench/results/post/$(date +%F)_bloom-toon}
mkdir -p "$out"
sizes="1920x1080 3840x2160"
kernels="5 10 25 50 100"
warmup=20
if [[ "${SMOKE:-0}" == 1 ]]; then sizes="96x64"; kernels="5"; frames=2; warmup=0; fi

have_cuda=1
if ! "$lp" info 2>/dev/null | grep -q "^cuda:.*(compute [0-9]"; then have_cuda=0; fi

run() {  # name size extra-args...
  local name=$1 size=$2
  shift 2
  "$lp" render --scene "$scene" --size "$size" --frames "$frames" --warmup "$warmup" --floors -q \
       --out "$out/$name.png" --timings-json "$out/$name.json" "$@" > /dev/null
  echo "$out/$name.json"
}

jsons=()
for size in $sizes; do
  for k in $kernels; do
    jsons+=("$(run "glsl-compute-separable_${size}_k$k" "$size" --bloom --bloom-kernel "$k" --post-backend glsl)")
    jsons+=("$(run "glsl-fragment-separable_${size}_k$k" "$size" --bloom --bloom-kernel "$k" --post-backend glsl --bloom-blur fragment)")
    jsons+=("$(run "glsl-mip-chain_${size}_k$k" "$size" --bloom --bloom-kernel "$k" --bloom-method mip-chain --post-backend glsl)")
    if [[ $have_cuda == 1 ]]; then
      jsons+=("$(run "cuda-separable_${size}_k$k" "$size" --bloom --bloom-kernel "$k" --post-backend cuda)")
      jsons+=("$(run "cuda-mip-chain_${size}_k$k" "$size" --bloom --bloom-kernel "$k" --bloom-method mip-chain --post-backend cuda)")
    fi
  done
  jsons+=("$(run "glsl-toon_${size}" "$size" --toon --post-backend glsl)")
  if [[ $have_cuda == 1 ]]; then jsons+=("$(run "cuda-toon_${size}" "$size" --toon --post-backend cuda)"); fi
done
[[ $have_cuda == 1 ]] || echo "(no CUDA device: CUDA rows skipped)" >&2
python3 "$(dirname "$0")/summarize_post.py" "${jsons[@]}" | tee "$out/post_effects.md"
