#!/bin/bash
# Cost of point-light shadows (docs/shadows.md, "Point-light shadows"): the point_shadows pass per
# shadow-casting point light, kept (--shadow-cache on) and redrawn every frame (--shadow-cache off),
# and what sampling the cubes adds to local_lights. The scene (written to OUTDIR): a 40 m ground with
# 8 x 8 casters (spheres of 4096 triangles and cubes, alternating, 4.5 m apart) under N point lights
# (N = 1, 2, 4, 8; 3 m up over the grid, range 10 m) that cast shadows, and the same N lights without
# castsShadow (the baseline of local_lights). Rows per N:
#   off       castsShadow false: no point_shadows pass; local_lights without the cube lookups
#   kept      --shadow-cache on, every light still: each row kept (the pass checks its keys)
#   orbit1    --shadow-cache on, light 0 orbiting: its row redrawn every frame, the others kept
#   redrawn   --shadow-cache off: every row drawn every frame (the uncached cost)
# at 1920x1080, --shadow-size 2048 (faces of 1024^2), 200 frames after 20 at 60 frames a second of
# scene time (the orbit moves between frames). The table
# (OUTDIR/point_shadow_cost.md) gives the median GPU ms of point_shadows, that divided by N (per
# light), local_lights and the frame, and the cubes drawn and kept over the timed frames;
# OUTDIR/explain_N.txt says what each cube draws. The gl_tests log
# (OUTDIR/gl_tests_point_shadows.txt) has the point-shadow tests on this driver. About 3 minutes.
# From the repository root on the GPU machine:
#   bench/point_shadow_cost.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/)
# FRAMES, WARMUP, SIZE and SHADOW_SIZE (defaults 200, 20, 1920x1080, 2048) shrink it for a dry run.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 --gtest_filter='PointShadow*:AnimationGl.PointShadow*' \
  > $R/gl_tests_point_shadows.txt 2>&1
tail -3 $R/gl_tests_point_shadows.txt
python3 - "$R" <<'PY'
import json, sys
R = sys.argv[1]
for n in [1, 2, 4, 8]:
    for variant in ["off", "kept", "orbit1"]:
        models = [{"name": "ground", "primitive": "plane", "scale": [40, 1, 40],
                   "material": {"diffuse": [0.6, 0.58, 0.52], "specular": [0.04, 0.04, 0.04], "shininess": 16}}]
        for i in range(8):
            for j in range(8):
                kind = "sphere" if (i + j) % 2 == 0 else "cube"
                models.append({"name": f"{kind}_{i}_{j}", "primitive": kind, "scale": 1.2,
                               "translate": [(i - 3.5) * 4.5, 0.6, (j - 3.5) * 4.5]})
        lights = []
        for k in range(n):
            x, z = ((k % 4) - 1.5) * 7.0, ((k // 4) - 0.5) * 9.0
            light = {"type": "point", "position": [x, 3.0, z], "intensity": 40, "range": 10,
                     "castsShadow": variant != "off"}
            if variant == "orbit1" and k == 0:
                light["orbit"] = {"center": [x + 1.0, 3.0, z], "speed": 0.5}
            lights.append(light)
        scene = {"description": f"bench/point_shadow_cost.sh: 64 casters under {n} point lights ({variant})",
                 "camera": {"position": [14, 12, 22], "target": [0, 0, 0], "fov": 55, "near": 0.1, "far": 120},
                 "models": models, "lights": lights, "ambient": [0.02, 0.02, 0.025]}
        json.dump(scene, open(f"{R}/points_{n}_{variant}.json", "w"), indent=1)
PY
COMMON="--size ${SIZE:-1920x1080} --shadow-size ${SHADOW_SIZE:-2048} --frames ${FRAMES:-200} --warmup ${WARMUP:-20} --fps 60 -q"
for n in 1 2 4 8; do
  $B/run graph --scene $R/points_${n}_kept.json --size ${SIZE:-1920x1080} --shadow-size ${SHADOW_SIZE:-2048} --explain \
    > $R/explain_$n.txt 2>&1
  for v in off kept orbit1; do
    $B/run bench --scene $R/points_${n}_$v.json $COMMON --vary '--shadow-cache on|--shadow-cache off' \
      --timings-json $R/point_shadow_${n}_$v.json > /dev/null 2> $R/bench_${n}_${v}_progress.txt \
      || { echo "bench $n $v failed"; tail -3 $R/bench_${n}_${v}_progress.txt; }
  done
done
python3 - "$R" <<'PY'
import json, sys
R = sys.argv[1]
rows = ["| point lights | variant | point_shadows ms | per light ms | local_lights ms | frame ms | cubes drawn / kept |",
        "| --- | --- | --- | --- | --- | --- | --- |"]
f = lambda t: f"{t:.4f}" if t is not None else "-"
# (scene, --shadow-cache) per row: "redrawn" is the still scene with the cache off.
for n in [1, 2, 4, 8]:
    for v, scene, cache in [("off", "off", "on"), ("kept", "kept", "on"), ("orbit1", "orbit1", "on"), ("redrawn", "kept", "off")]:
        try:
            runs = json.load(open(f"{R}/point_shadow_{n}_{scene}.json"))["runs"]
            run = next(r for r in runs if r["flags"] == f"--shadow-cache {cache}")
        except (OSError, KeyError, ValueError, StopIteration) as e:
            rows.append(f"| {n} | {v} | {e!r} | | | | |"); continue
        p = run["passes"]
        ps = p.get("point_shadows", {}).get("median_ms")
        ll = p.get("local_lights", {}).get("median_ms")
        fr = p.get("frame", {}).get("median_ms")
        c = run.get("point_shadow_cache", {})
        cubes = f"{c.get('cubes_drawn', 0)} / {c.get('cubes_kept', 0)}" if c else "-"
        rows.append(f"| {n} | {v} | {f(ps)} | {f(ps / n if ps is not None else None)} | {f(ll)} | {f(fr)} | {cubes} |")
open(f"{R}/point_shadow_cost.md", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
PY
