#!/bin/bash
# CUDA post without the interop tax, on the GPU: bloom + composite at kernel 5 1920x1080 and kernel
# 100 3840x2160 (and toon at both sizes) for CUDA on shared textures (--cuda-interop external),
# CUDA with map/unmap per use (--cuda-interop map), GLSL compute, CUDA with the interop auto chose
# (--cuda-interop auto: shared textures with Vulkan semaphores only where measured faster than
# map/unmap), and what --post-backend auto chose (measured afresh into OUTDIR/cache); the same
# bloom with --bloom-method mip-chain (effect "mipchain") in GLSL, CUDA on shared textures and auto. `external`
# is ordered by Vulkan semaphores where info's `sync:` line says so, else by host waits. Per pass: GL-timed ms (what the frame pays, interop and
# syncs included), CUDA kernel ms, interop ms, the bandwidth floor and measured/floor. Also runs the
# CUDA tests (shared textures vs the CPU reference), the kernel-only bloom benchmark of post_cuda_bench
# (bench/cuda/post_cuda_bench.cpp; bloom_kernels.txt: separable with the direct and the tensor-core blur, and the mip chain, kernel
# 3..100, 1080p and 4K, against the floor; and plain copy kernels, CUDA arrays and linear memory),
# the cost of one hand-over to CUDA and back by itself (hand_over.txt) and records `info`. From the repository root:
#   bench/post_interop.sh BUNDLE OUTDIR    (BUNDLE: run, cuda_tests, post_cuda_bench, lib/)
#   SMOKE=1 bench/post_interop.sh BUNDLE OUTDIR   tiny sizes, few frames (checks the plumbing)
#   KERNELS_ONLY=1 bench/post_interop.sh BUNDLE OUTDIR   cuda_tests and the kernel-only benchmarks alone
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p "$R"
frames=200; warmup=30
cases="k5_1920x1080 k100_3840x2160"
if [[ "${SMOKE:-0}" == 1 ]]; then frames=3; warmup=1; cases="k5_96x64 k9_128x72"; fi
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$R/device.txt" 2>/dev/null || echo "no nvidia-smi" > "$R/device.txt"
export LIGHTPASS_CACHE_DIR=$R/cache
"$B/run" info > "$R/info.txt" 2>&1; grep -E "^(renderer|cuda|interop|sync):" "$R/info.txt"
if [[ -x "$B/cuda_tests" ]]; then
  LD_LIBRARY_PATH=$B/lib "$B/cuda_tests" > "$R/cuda_tests.txt" 2>&1; tail -2 "$R/cuda_tests.txt"
fi
if [[ -x "$B/post_cuda_bench" ]]; then
  # Kernel-only: the fused bloom + composite on RGBA16F CUDA arrays (no GL), separable (direct and
  # tensor-core blur and what auto picks) and mip chain, kernel 3..100 at 1080p and 4K, CUDA events,
  # vs the floor; the mip chain's tuning; and the copy kernels that show what bandwidth CUDA arrays
  # and linear memory reach.
  : > "$R/bloom_kernels.txt"
  for b in kernels mip-chain-tuning copy-kernels; do
    LD_LIBRARY_PATH=$B/lib "$B/post_cuda_bench" $b >> "$R/bloom_kernels.txt" 2>&1 \
      || echo "bloom kernel benchmark $b failed: $(tail -1 "$R/bloom_kernels.txt")"
  done
  # What one GL -> CUDA -> GL hand-over costs a GL frame by itself (a kernel of a few microseconds
  # on 64x48 texels), under each ordering, and one map/unmap call instead.
  LD_LIBRARY_PATH=$B/lib "$B/post_cuda_bench" hand-over \
    > "$R/hand_over.txt" 2>&1 || echo "hand-over benchmark failed: $(tail -1 "$R/hand_over.txt")"
  grep "hand-over bench" "$R/hand_over.txt"
fi
if [[ "${KERNELS_ONLY:-0}" == 1 ]]; then
  python3 "$(dirname "$0")/summarize_post_interop.py" "$R" | tee "$R/post_interop.md"
  exit 0
fi
cuda=1
grep -q "^cuda:.*(compute [0-9]" "$R/info.txt" || { cuda=0; echo "(no CUDA device: CUDA rows skipped)"; }
run() {  # name size kernel extra-args...   (auto runs keep the info lines that say what it chose)
  local name=$1 size=$2 k=$3 quiet=-q; shift 3
  [[ $name == auto_* || $name == cuda-auto_* ]] && quiet=
  "$B/run" render --scene scenes/cornell.json --size "$size" --frames $frames --warmup $warmup --floors $quiet \
    --bloom --bloom-kernel "$k" --timings-json "$R/$name.json" --out "$R/$name.png" "$@" > "$R/$name.log" 2>&1 \
    || { echo "render $name failed: $(tail -1 "$R/$name.log")"; rm -f "$R/$name.json"; }
}
for c in $cases; do
  k=${c%%_*}; k=${k#k}; size=${c#*_}
  run "glsl_bloom_${c}" "$size" "$k" --post-backend glsl
  run "glsl_toon_${c}" "$size" "$k" --no-bloom --toon --post-backend glsl
  if [[ $cuda == 1 ]]; then
    run "cuda-external_bloom_${c}" "$size" "$k" --post-backend cuda --cuda-interop external
    run "cuda-map_bloom_${c}" "$size" "$k" --post-backend cuda --cuda-interop map
    run "cuda-auto_bloom_${c}" "$size" "$k" --post-backend cuda --cuda-interop auto --post-remeasure
    run "cuda-external_toon_${c}" "$size" "$k" --no-bloom --toon --post-backend cuda --cuda-interop external
    run "cuda-map_toon_${c}" "$size" "$k" --no-bloom --toon --post-backend cuda --cuda-interop map
    run "auto_bloom_${c}" "$size" "$k" --post-backend auto --post-remeasure
    # The mip chain (effect name "mipchain"): CUDA on shared textures and what auto picks.
    run "cuda-external_mipchain_${c}" "$size" "$k" --bloom-method mip-chain --post-backend cuda --cuda-interop external
    run "auto_mipchain_${c}" "$size" "$k" --bloom-method mip-chain --post-backend auto --post-remeasure
  fi
  run "glsl_mipchain_${c}" "$size" "$k" --bloom-method mip-chain --post-backend glsl
done
grep -h "post backend auto\|post effects:" "$R"/auto_*.log "$R"/cuda-auto_*.log 2>/dev/null | sort -u > "$R/auto_choices.txt"
python3 "$(dirname "$0")/summarize_post_interop.py" "$R" | tee "$R/post_interop.md"
