#!/bin/bash
# glTF metallic-roughness materials on the GPU: the G-buffer pass (now reading up to five textures and
# converting metallic-roughness per texel) and the emission pass, on the bundled PBR scene and the
# Cornell box (MTL, no emission: the emission pass must be skipped there), at 1080p and 4K, across
# both BRDFs, plus the GL tests on that driver. From the repository root:
#   bench/gltf_materials.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/)
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 --gtest_filter='Gltf*:GBuffer*:RenderAnalytic*' > $R/gl_tests.txt 2>&1; tail -4 $R/gl_tests.txt
$B/run --version
for s in pbr-spheres cornell; do
  $B/run bench --scene scenes/$s.json --frames 200 --warmup 30 --floors --vary '--brdf blinn-phong,ggx' \
    --vary '--size 1920x1080,3840x2160' --timings-json $R/materials_$s.json -q > /dev/null 2>&1 || echo "bench $s failed"
done
python3 - $R <<'PY'
import json, sys
R = sys.argv[1]
rows = ["| scene | flags | frame ms | gbuffer ms (x floor) | emission ms (x floor) |", "| --- | --- | --- | --- | --- |"]
for name in ["materials_pbr-spheres", "materials_cornell"]:
    d = json.load(open(f"{R}/{name}.json"))
    for run in d["runs"]:
        p = run["passes"]
        def cell(k):
            if k not in p: return "skipped"
            v = p[k]
            ratio = round(v["median_ms"] / v["floor_ms"], 1) if v.get("floor_ms") else None
            return f"{v['median_ms']:.4f} ({ratio})"
        rows.append(f"| {name[10:]} | {run['flags']} | {p['frame']['median_ms']:.3f} | {cell('gbuffer')} | {cell('emission')} |")
open(f"{R}/gltf_materials.md", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
PY
