#!/bin/bash
# Cost of the specular IBL method on the GPU: the "ibl" pass (deferred; split sum or per-pixel GGX
# samples of the prefiltered chain, --ibl-specular sampled --ibl-specular-samples N) and forward+'s
# "forward_opaque" (which evaluates the same IBL per fragment), at 1920x1080 and 3840x2160, for the
# split sum and 4, 8, 16, 32, 64 samples. Scenes: gallery (IBL on every surface) and the Mitsuba
# sphere grid under the 50,000 lamp (bench/mitsuba/scenes/lamp50k.json). The accuracy side of the
# trade is bench/results/mitsuba/issue16/sampled_specular.md. From the repository root on the GPU machine:
#   bench/ibl_specular.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/; the gallery needs ../shared/assets)
# Writes OUTDIR/ibl_specular_<scene>.json (lightpass bench) and OUTDIR/ibl_specular.md (the table), and
# for light extraction (0 or 4 sources lit analytically) OUTDIR/ibl_extract_<scene>.json and OUTDIR/ibl_extract.md.
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 --gtest_filter='*Ibl*:*Forward*' > $R/gl_tests_ibl.txt 2>&1
tail -3 $R/gl_tests_ibl.txt
settings='--ibl-specular split-sum'
for n in 4 8 16 32 64; do settings="$settings|--ibl-specular sampled --ibl-specular-samples $n"; done
for s in scenes/gallery.json bench/mitsuba/scenes/lamp50k.json; do
  name=$(basename $s .json)
  $B/run bench --scene $s --ibl --brdf ggx --frames 200 --warmup 30 --vary "$settings" \
    --vary '--size 1920x1080,3840x2160' --vary '--render-path deferred,forward+' \
    --timings-json $R/ibl_specular_$name.json -q > $R/ibl_specular_$name.log 2>&1 ||
    echo "bench $name failed (see $R/ibl_specular_$name.log)"
done
# Light extraction (--ibl-extract-lights): the extracted sources are a few directional lights per pixel
# in the ibl pass and forward+'s forward_opaque. lamp50k extracts 1, royal_esplanade_1k 4 (the most).
for s in bench/mitsuba/scenes/lamp50k.json bench/mitsuba/scenes/royal_esplanade_1k.json; do
  name=$(basename $s .json)
  $B/run bench --scene $s --ibl --brdf ggx --frames 200 --warmup 30 --vary '--ibl-extract-lights 0,4' \
    --vary '--ibl-specular split-sum|--ibl-specular sampled --ibl-specular-samples 64' \
    --vary '--size 1920x1080,3840x2160' --vary '--render-path deferred,forward+' \
    --timings-json $R/ibl_extract_$name.json -q > $R/ibl_extract_$name.log 2>&1 ||
    echo "bench extract $name failed (see $R/ibl_extract_$name.log)"
done
# The two tables: OUTDIR/ibl_specular.md (specular methods) and OUTDIR/ibl_extract.md (extracted lights).
python3 - $R <<'PY'
import json, os, sys
R = sys.argv[1]

def table(name, scenes, extract):
    lines = ["| scene | size | render path | specular |" + (" extracted lights |" if extract else "") +
             " ibl ms | forward_opaque ms | frame ms |",
             "| --- | --- | --- | --- |" + (" ---: |" if extract else "") + " ---: | ---: | ---: |"]
    for scene in scenes:
        path = f"{R}/{name}_{scene}.json"
        if not os.path.isfile(path):
            continue
        for run in json.load(open(path))["runs"]:
            f, p = run["flags"], run["passes"]
            size = f.split("--size ")[1].split()[0] if "--size " in f else "-"
            rpath = "forward+" if "forward+" in f else "deferred"
            spec = "split sum" if "split-sum" in f else f"sampled {f.split('--ibl-specular-samples ')[1].split()[0]}"
            lights = f.split("--ibl-extract-lights ")[1].split()[0] if "--ibl-extract-lights " in f else "-"
            cell = lambda n: f"{p[n]['median_ms']:.4f}" if n in p else "-"
            lines.append(f"| {scene} | {size} | {rpath} | {spec} |" + (f" {lights} |" if extract else "") +
                         f" {cell('ibl')} | {cell('forward_opaque')} | {cell('frame')} |")
    text = "\n".join(lines) + "\n"
    open(f"{R}/{name}.md", "w").write(text)
    print(text)

table("ibl_extract", ["lamp50k", "royal_esplanade_1k"], True)
table("ibl_specular", ["gallery", "lamp50k"], False)
PY
