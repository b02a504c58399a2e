#!/usr/bin/python3
"""The raster IBL against lightpass's own path tracer (`lightpass reference`), per object: a roughness
grid of GGX spheres (F0 = 1, diffuse 0: the specular IBL alone) and a rough and a smooth plane seen at
grazing angles, under environment maps: hdr/sky.hdr, hdr/studio.exr and bench/mitsuba/make_maps.py's
`lamp` (a 2-texel lamp of 50,000) and `window` (one hard-edged 60 x 35 degree window of 20 over a dim
room). Any device: accuracy, not speed (llvmpipe at small sizes is fine).

For each map and raster variant it renders the frame (`render --ibl --no-ao --brdf ggx --exr`), and
once per map the tracer (`reference --direct-only --pixel-centre`: the environment seen from the first
surface, through the pixel centre, which is what the IBL models; the spheres' few interreflections are
left out on both sides). Per object the error is sum(raster) / sum(tracer) - 1 of the luminance over the
pixels whose centre ray meets it (spheres: within 0.9 of the radius, off the tessellated silhouette).
The tracer's noise on that sum is its per-pixel standard error (the accumulation's sample variance,
`pathTraceNoise`) propagated over the pixels: the `reference` line's mean relative standard error over
the square root of the object's pixel count (an estimate: it takes the image's mean RSE for each pixel).

    /usr/bin/python3 bench/ibl_truth.py [--lightpass build/app/lightpass] [--out DIR] [--spp N]
        [--size 160x96] [--variants 'split-sum=--ibl-specular split-sum' ...] [--maps sky studio lamp window]

Writes DIR/ibl_truth.md (one table per scene: rows objects, columns variants) and DIR/ibl_truth.json.
"""
import argparse
import json
import math
import os
import re
import struct
import subprocess
import sys
import zlib
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "bench" / "mitsuba"))
from make_maps import lamp_map, window_map, write_rgbe  # noqa: E402

RADIUS = 0.5
ROUGHNESS = [0.2, 0.35, 0.5, 0.625, 0.75, 0.875, 1.0]
SPHERE_CAMERA = {"position": [0.0, 0.0, 11.0], "target": [0.0, 0.0, 0.0], "up": [0.0, 1.0, 0.0], "fov": 30.0,
                 "near": 0.1, "far": 100.0}
# The grazing planes: eye 0.3 m above a 40 x 40 m plane, looking 6 degrees down (as bench/mitsuba/grazing_plane.py).
PLANE_CAMERA = {"position": [0.0, 0.3, 0.0], "target": [0.0, 0.3 - 10.0 * math.tan(math.radians(6.0)), -10.0],
                "up": [0.0, 1.0, 0.0], "fov": 24.0, "near": 0.05, "far": 200.0}
PLANE_ROUGHNESS = {"plane_rough": 0.5, "plane_smooth": 0.1}
PLANE_HALF = 20.0


def read_exr(path):
    """RGB float32 of a scanline ZIP / uncompressed EXR of FLOAT or HALF channels (what lightpass writes)."""
    data = Path(path).read_bytes()
    if struct.unpack_from("<I", data, 0)[0] != 20000630:
        raise ValueError(f"{path}: not an EXR file")
    pos, header = 8, {}
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        tend = data.index(b"\0", end + 1)
        size = struct.unpack_from("<i", data, tend + 1)[0]
        header[name] = data[tend + 5:tend + 5 + size]
        pos = tend + 5 + size
    pos += 1
    channels, c = [], 0
    raw = header["channels"]
    while raw[c] != 0:
        end = raw.index(b"\0", c)
        channels.append((raw[c:end].decode(), struct.unpack_from("<i", raw, end + 1)[0]))
        c = end + 17
    xmin, ymin, xmax, ymax = struct.unpack("<4i", header["dataWindow"])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    compression = header["compression"][0]
    lines = {0: 1, 2: 1, 3: 16}[compression]
    blocks = (h + lines - 1) // lines
    offsets = struct.unpack_from(f"<{blocks}Q", data, pos)
    sizes = {1: 2, 2: 4}
    out = {name: np.zeros((h, w), np.float32) for name, _ in channels}
    for off in offsets:
        y, n = struct.unpack_from("<ii", data, off)
        block = data[off + 8:off + 8 + n]
        count = min(lines, ymax + 1 - y)
        expected = count * w * sum(sizes[t] for _, t in channels)
        if compression != 0 and n < expected:
            t = np.frombuffer(zlib.decompress(block), np.uint8).astype(np.int32)
            t = np.cumsum(np.concatenate([t[:1], t[1:] - 128])) & 0xFF
            t = t.astype(np.uint8)
            half = (len(t) + 1) // 2
            raw_block = np.empty(len(t), np.uint8)
            raw_block[0::2], raw_block[1::2] = t[:half], t[half:]
            block = raw_block.tobytes()
        p = 0
        for row in range(count):
            for name, kind in channels:
                dtype = np.float16 if kind == 1 else np.float32
                out[name][y - ymin + row] = np.frombuffer(block, dtype, w, p).astype(np.float32)
                p += w * sizes[kind]
    return np.stack([out["R"], out["G"], out["B"]], -1)


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def rays(camera, width, height):
    pos = np.array(camera["position"], float)
    fwd = np.array(camera["target"], float) - pos
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, camera["up"])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    t = math.tan(math.radians(camera["fov"]) / 2)
    xs = ((np.arange(width) + 0.5) / width * 2 - 1) * t * width / height
    ys = (1 - (np.arange(height) + 0.5) / height * 2) * t
    d = fwd + xs[None, :, None] * right + ys[:, None, None] * up
    return pos, d / np.linalg.norm(d, axis=2, keepdims=True)


def sphere_grid():
    out = []
    for i, r in enumerate(ROUGHNESS):
        x = (i - (len(ROUGHNESS) - 1) / 2) * 1.4
        out.append((f"sphere_r{r:.3f}", [x, 0.0, 0.0], r))
    return out


def sphere_masks(width, height):
    pos, d = rays(SPHERE_CAMERA, width, height)
    masks = {}
    for name, c, _ in sphere_grid():
        oc = pos - np.array(c)
        b = d @ oc
        masks[name] = b * b - (oc @ oc - (0.9 * RADIUS) ** 2) > 0
    return masks


def plane_mask(width, height):
    pos, d = rays(PLANE_CAMERA, width, height)
    t = np.where(d[..., 1] < -1e-6, -pos[1] / np.minimum(d[..., 1], -1e-6), np.inf)
    p = pos + t[..., None] * d
    return np.isfinite(t) & (np.abs(p[..., 0]) < 0.9 * PLANE_HALF) & (p[..., 2] > -0.9 * PLANE_HALF) & (p[..., 2] < 0)


def scenes(map_path, workdir):
    env = {"map": os.path.relpath(map_path, workdir), "intensity": 1.0, "ibl": True}
    metal = lambda r: {"diffuse": [0, 0, 0], "specular": [1, 1, 1], "roughness": r}
    spheres = {"camera": SPHERE_CAMERA, "lights": [], "ambient": [0, 0, 0], "environment": env,
               "models": [{"name": n, "primitive": "sphere", "translate": c, "scale": 1.0, "material": metal(r)}
                          for n, c, r in sphere_grid()]}
    out = {"spheres": spheres}
    for name, r in PLANE_ROUGHNESS.items():
        out[name] = {"camera": PLANE_CAMERA, "lights": [], "ambient": [0, 0, 0], "environment": env,
                     "models": [{"name": name, "primitive": "plane", "scale": [2 * PLANE_HALF, 1, 2 * PLANE_HALF],
                                 "material": metal(r)}]}
    return out


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{p.stderr}")
    return p.stdout + p.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lightpass", default=str(REPO / "build/app/lightpass"))
    ap.add_argument("--out", default="ibl_truth_out")
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--size", default="168x96")
    ap.add_argument("--maps", nargs="*", default=["sky", "studio", "lamp", "window"])
    ap.add_argument("--scenes", nargs="*", default=["spheres", "plane_rough", "plane_smooth"])
    ap.add_argument("--variants", nargs="*", default=["split-sum=--ibl-specular split-sum",
                                                      "sampled64=--ibl-specular sampled --ibl-specular-samples 64"])
    args = ap.parse_args()
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    width, height = (int(v) for v in args.size.split("x"))
    maps = {"sky": REPO / "hdr/sky.hdr", "studio": REPO / "hdr/studio.exr"}
    if "lamp" in args.maps:
        maps["lamp"] = out / "lamp50k.hdr"
        write_rgbe(maps["lamp"], lamp_map())
    if "window" in args.maps:
        maps["window"] = out / "window.hdr"
        write_rgbe(maps["window"], window_map())
    variants = [v.split("=", 1) for v in args.variants]
    results = {}
    for map_name in args.maps:
        for scene_name, scene in scenes(maps[map_name], out).items():
            if scene_name not in args.scenes:
                continue
            stem = f"{map_name}_{scene_name}"
            path = out / f"{stem}.json"
            path.write_text(json.dumps(scene, indent=1) + "\n")
            common = ["--scene", str(path), "--size", f"{width}x{height}", "--brdf", "ggx", "--no-auto-exposure"]
            ref_exr = out / f"{stem}_pathtraced.exr"
            log = run([args.lightpass, "reference", *common, "--spp", str(args.spp), "--direct-only", "--pixel-centre",
                       "--exr", str(ref_exr), "--out", str(ref_exr.with_suffix(".png"))])
            rse = float(re.search(r"mean relative standard error ([0-9.]+)%", log).group(1)) / 100.0
            ref = luminance(read_exr(ref_exr))
            masks = sphere_masks(width, height) if scene_name == "spheres" else {scene_name: plane_mask(width, height)}
            row = {name: {"pixels": int(m.sum()), "noise": rse / math.sqrt(max(m.sum(), 1))} for name, m in masks.items()}
            for label, flags in variants:
                exr = out / f"{stem}_{label}.exr"
                run([args.lightpass, "render", *common, "--ibl", "--no-ao", "--frames", "1", *flags.split(),
                     "--exr", str(exr), "--out", str(exr.with_suffix(".png"))])
                img = luminance(read_exr(exr))
                for name, m in masks.items():
                    row[name][label] = float(img[m].sum() / ref[m].sum() - 1.0)
            results[stem] = {"map": map_name, "scene": scene_name, "spp": args.spp, "rse_pixel": rse, "objects": row}
            print(stem, json.dumps(row), flush=True)
    (out / "ibl_truth.json").write_text(json.dumps(results, indent=1) + "\n")
    lines = [f"Raster IBL against `lightpass reference --direct-only --pixel-centre --spp {args.spp}`, {width}x{height}: "
             "sum(raster) / sum(tracer) - 1 of the luminance per object; noise: the tracer's standard error of that sum.", ""]
    labels = [label for label, _ in variants]
    lines.append("| map | object | pixels | " + " | ".join(labels) + " | tracer noise |")
    lines.append("| --- | --- | ---: | " + " | ".join("---:" for _ in labels) + " | ---: |")
    for stem, r in results.items():
        for name, o in r["objects"].items():
            lines.append(f"| {r['map']} | {name} | {o['pixels']} | " + " | ".join(f"{100 * o[l]:+.1f}%" for l in labels) +
                         f" | {100 * o['noise']:.2f}% |")
    (out / "ibl_truth.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
