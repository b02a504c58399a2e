#!/bin/bash
# KHR_materials_clearcoat on the GPU: what gbuffer.clearcoat (RGBA16F, allocated only when an opaque
# material has a coat) and the coat's lobe in every light pass cost. One process per run, interleaved
# base, new, base, new:
#   - gallery and pbr-spheres (no coat): base (main) against new, which must match (no target, the
#     same programs);
#   - clearcoat-spheres (a coat on 12 of 15 spheres: the target written and read, the lobe in the suns,
#     the IBL and the local lights) against pbr-spheres on the new build, both G-buffer modes, 1080p
#     and 4K, with the tiled and clustered local-light methods.
# From the repository root on the GPU machine:
#   bench/khr_clearcoat.sh BUNDLE OUTDIR   (BUNDLE: run (new), run-base (main), gl_tests, lib/)
# Tables: bench/compare_runs.py OUTDIR frame_gallery frame_pbr-spheres ; clearcoat.md here.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LIGHTPASS_GL_STATE_CHECKS=1 LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 \
  --gtest_filter='Gltf*:GBuffer*:VisibilityBuffer*:Ibl.WhiteFurnace*' > $R/gl_tests.txt 2>&1; tail -4 $R/gl_tests.txt
$B/run graph --scene scenes/clearcoat-spheres.json --explain > $R/graph_clearcoat.txt 2>&1
for round in 1 2; do for v in base new; do
  LP=$B/run; [ $v = base ] && LP=$B/run-base
  o=$R/$v$round; mkdir -p $o
  for s in gallery pbr-spheres; do
    $LP bench --scene scenes/$s.json --frames 200 --warmup 30 --floors --vary '--gbuffer-mode classic,visibility' \
      --vary '--size 1920x1080,3840x2160' --timings-json $o/frame_$s.json -q > $o/frame_$s.log 2>&1
  done
  if [ $v = new ]; then
    $LP bench --scene scenes/clearcoat-spheres.json --frames 200 --warmup 30 --floors --vary '--gbuffer-mode classic,visibility' \
      --vary '--size 1920x1080,3840x2160' --vary '--local-lights tiled,clustered' \
      --timings-json $o/frame_clearcoat-spheres.json -q > $o/frame_clearcoat-spheres.log 2>&1
  fi
done; done
python3 - $R <<'PY'
import json, sys
R = sys.argv[1]
rows = ["| round | scene | flags | frame ms | gbuffer or resolve ms | global_lights ms | ibl ms | local_lights ms |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |"]
for rnd in ("new1", "new2"):
    for s in ("pbr-spheres", "clearcoat-spheres"):
        d = json.load(open(f"{R}/{rnd}/frame_{s}.json"))
        for run in d["runs"]:
            p = run["passes"]
            g = sum(p[k]["median_ms"] for k in ("gbuffer", "gbuffer_visibility", "gbuffer_resolve") if k in p)
            cell = lambda k: f"{p[k]['median_ms']:.4f}" if k in p else "skipped"
            rows.append(f"| {rnd} | {s} | {run['flags']} | {p['frame']['median_ms']:.3f} | {g:.4f} | {cell('global_lights')} | "
                        f"{cell('ibl')} | {cell('local_lights')} |")
open(f"{R}/clearcoat.md", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
PY
