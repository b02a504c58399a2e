#!/bin/bash
# Cost of alpha-tested shadow casters against opaque ones (docs/shadows.md, "Alpha in shadows"): a
# forest of 8 x 8 canopies of models/leaf_cards.gltf (12288 leaf cards, 24576 triangles, 0.6 m each,
# glTF MASK) over a 40 m ground, under a sun (4 cascades of 2048^2) and a shadow-casting spot, at
# 1920x1080, the cascade cache off (every cascade drawn every frame: the caster cost itself). Three
# versions of the same cards (scenes written to OUTDIR):
#   mask    the cards as they are: MASK, alpha-tested against the texture (the alpha-tested draws)
#   opaque  "material": {"opacity": 1}: the same cards and texture as OPAQUE (the opaque path: no
#           texture fetch, no discard), the baseline
#   blend   "material": {"opacity": 0.99}: BLEND, the hashed alpha test
# each with --shadow-raster conservative (hardware where the GPU has it), conservative with the
# geometry shader, split, plain and compute. 200 frames after 20 per row. The table
# (OUTDIR/alpha_shadow_cost.md) gives per row the median GPU ms of shadow_map_0 and spot_shadows and
# their ratio to the opaque row of the same raster; OUTDIR/explain_*.txt say how many triangles each
# cascade drew and how many of them alpha-tested. The gl_tests log (OUTDIR/gl_tests_alpha_shadow.txt)
# has the alpha tests on this driver and the BLEND 0.5 means (OUTDIR/blend_half.txt). About 4 minutes.
# From the repository root on the GPU machine:
#   bench/alpha_shadow_cost.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/)
# FRAMES, WARMUP, SIZE and SHADOW_SIZE (defaults 200, 20, 1920x1080, 2048) shrink it for a dry run.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 --gtest_filter='ShadowAlpha*:ShadowCasterAlpha*' \
  > $R/gl_tests_alpha_shadow.txt 2>&1
tail -3 $R/gl_tests_alpha_shadow.txt
grep "BLEND 0.5" $R/gl_tests_alpha_shadow.txt | tee $R/blend_half.txt
python3 - "$R" "$(pwd)" <<'PY'
import json, sys
R, root = sys.argv[1], sys.argv[2]
overrides = {"mask": None, "opaque": {"opacity": 1}, "blend": {"opacity": 0.99}}
for name, material in overrides.items():
    models = [{"name": "ground", "primitive": "plane", "scale": [40, 1, 40],
               "material": {"diffuse": [0.6, 0.58, 0.52], "specular": [0.04, 0.04, 0.04], "shininess": 16}}]
    for i in range(8):
        for j in range(8):
            m = {"name": f"canopy_{i}_{j}", "gltf": f"{root}/models/leaf_cards.gltf",
                 "translate": [(i - 3.5) * 4.5, 2.0, (j - 3.5) * 4.5]}
            if material: m["material"] = material
            models.append(m)
    scene = {"description": f"bench/alpha_shadow_cost.sh: 64 canopies of leaf cards ({name})",
             "camera": {"position": [14, 9, 18], "target": [0, 1, 0], "fov": 55, "near": 0.1, "far": 120},
             "models": models,
             "lights": [{"type": "directional", "direction": [-0.35, -1, -0.45], "intensity": 3},
                        {"type": "spot", "position": [-6, 12, 6], "direction": [0.4, -1, -0.4], "intensity": 200,
                         "range": 30, "innerAngle": 35, "outerAngle": 45, "castsShadow": True}],
             "ambient": [0.06, 0.07, 0.09]}
    json.dump(scene, open(f"{R}/forest_{name}.json", "w"), indent=1)
PY
RASTERS='--shadow-raster conservative|--shadow-raster conservative --shadow-conservative geometry-shader|--shadow-raster split|--shadow-raster plain|--shadow-raster compute'
COMMON="--size ${SIZE:-1920x1080} --shadow-size ${SHADOW_SIZE:-2048} --shadow-cascades 4 --shadow-cache off"
for v in mask opaque blend; do
  $B/run graph --scene $R/forest_$v.json $COMMON --explain > $R/explain_$v.txt 2>&1
  $B/run bench --scene $R/forest_$v.json $COMMON --frames ${FRAMES:-200} --warmup ${WARMUP:-20} --vary "$RASTERS" \
    --timings-json $R/alpha_shadow_$v.json -q > /dev/null 2> $R/bench_${v}_progress.txt \
    || { echo "bench $v failed"; tail -3 $R/bench_${v}_progress.txt; }
done
python3 - "$R" <<'PY'
import json, sys
R = sys.argv[1]
runs = {}
for v in ["mask", "opaque", "blend"]:
    try: runs[v] = json.load(open(f"{R}/alpha_shadow_{v}.json"))["runs"]
    except (OSError, KeyError, ValueError) as e: print(f"alpha_shadow_{v}.json: {e}"); runs[v] = []
def ms(run, name):
    p = run["passes"].get(name)
    return p["median_ms"] if p else None
rows = ["| casters | raster flags | shadow_map_0 ms | x opaque | spot_shadows ms | x opaque | frame ms |",
        "| --- | --- | --- | --- | --- | --- | --- |"]
base = {r["flags"]: r for r in runs["opaque"]}
for v in ["opaque", "mask", "blend"]:
    for r in runs[v]:
        b = base.get(r["flags"])
        cells = []
        for name in ["shadow_map_0", "spot_shadows"]:
            t, t0 = ms(r, name), (ms(b, name) if b else None)
            cells += [f"{t:.3f}" if t is not None else "-", f"{t / t0:.2f}" if t is not None and t0 else "-"]
        rows.append(f"| {v} | {r['flags']} | {cells[0]} | {cells[1]} | {cells[2]} | {cells[3]} | {ms(r, 'frame'):.3f} |")
open(f"{R}/alpha_shadow_cost.md", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
PY
