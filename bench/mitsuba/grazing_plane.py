#!/usr/bin/env python3
"""A smooth plane seen at grazing angles under lamps just above the horizon, against the exact split sum.

Renders bench/mitsuba/maps/lamps_low.hdr reflected by a GGX plane (Ks = 1, diffuse 0) with lightpass
(--ibl --brdf ggx --exr) and computes, on the CPU in float64, what lightpass's split sum would give if
both of its factors were exact, per plane pixel:
    prefiltered(R') = integral L(l) D(h) max(R'.l, 0) dl / integral D(h) max(R'.l, 0) dl  (N = V = R'),
    R' = normalize(mix(R, N, alpha^2)) (lightpass's dominant direction),
    times the DFG term A + B at (N.V, roughness) (F0 = f90 = 1) of lightpass's Smith model (--specular-masking),
the map integrated over its texels (solid angle sin(theta) dtheta dphi; halved to 512 x 256 by default,
0.7 degree texels, below the 1.6 degree lobe of roughness 0.119). The difference is what the
prefiltered chain (its levels, its roughness -> mip mapping, its sampling) adds. Writes a Markdown
table (mean relative error over all plane pixels and over the pixels that reflect a lamp).

    $MITSUBA_VENV/bin/python bench/mitsuba/grazing_plane.py [--lightpass PATH] [--out DIR]
        [--shininess N | --roughness R] [--lightpass-args '...']
(Mitsuba's Python package reads and writes EXR/HDR; with --mitsuba-spp N it also path traces the same
plane, and the errors against it go to grazing_plane_mitsuba.md.)
"""
import argparse
import datetime
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import mitsuba as mi

REPO = Path(__file__).resolve().parents[2]
CAMERA = {"position": [0.0, 0.3, 0.0], "target": [0.0, 0.3 - 10.0 * math.tan(math.radians(6.0)), -10.0],
          "up": [0.0, 1.0, 0.0], "fov": 24.0, "near": 0.05, "far": 200.0}


def read_rgb(path):
    return np.array(mi.Bitmap(str(path)).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False), np.float64)


def ggx_d(nh, a):
    a2 = a * a
    d = nh * nh * (a2 - 1.0) + 1.0
    return a2 / (math.pi * d * d)


def dfg(nv, r, masking="height-correlated", nt=512, nphi=128):
    """A + B (F0 = f90 = 1) by the midpoint rule over the GGX half-vector CDF, with lightpass's Smith model
    `masking` (--specular-masking: separable G1(V) G1(L) or height-correlated)."""
    a = r * r
    a2 = a * a
    nv = max(nv, 1e-4)
    xi = (np.arange(nt) + 0.5) / nt
    cos_t = np.sqrt((1 - xi) / (1 + (a2 - 1) * xi))
    sin_t = np.sqrt(1 - cos_t ** 2)
    phi = 2 * math.pi * (np.arange(nphi) + 0.5) / nphi
    h = np.stack([np.outer(sin_t, np.cos(phi)), np.outer(sin_t, np.sin(phi)), np.outer(cos_t, np.ones(nphi))], -1)
    v = np.array([math.sqrt(1 - nv * nv), 0.0, nv])
    vh = h @ v
    l = 2 * vh[..., None] * h - v
    nl = l[..., 2]
    ok = (nl > 0) & (vh > 0)
    nl = np.where(ok, nl, 1.0)
    lv, ll = math.sqrt(nv * nv * (1 - a2) + a2), np.sqrt(nl * nl * (1 - a2) + a2)  # N.V (1 + 2 Lambda), N.L (...)
    vis = 0.5 / (nl * lv + nv * ll) if masking == "height-correlated" else 1.0 / ((nv + lv) * (nl + ll))
    w = np.where(ok, vis * 4 * nl * vh / cos_t[:, None], 0.0)
    return float(w.mean())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lightpass", default=str(REPO / "build/app/lightpass"))
    ap.add_argument("--map", default=str(REPO / "bench/mitsuba/maps/lamps_low.hdr"))
    ap.add_argument("--size", default="128x72")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--shininess", type=float, help="Blinn-Phong exponent of the plane (default: --roughness 0.119's)")
    g.add_argument("--roughness", type=float, help="perceptual roughness (scene-file 'roughness')")
    ap.add_argument("--lightpass-args", default="")
    ap.add_argument("--specular-masking", default="height-correlated", choices=["height-correlated", "separable"],
                    help="lightpass's Smith model (passed on as --specular-masking; the exact DFG uses it too)")
    ap.add_argument("--map-width", type=int, default=512, help="the map is halved to at most this width for the integral")
    ap.add_argument("--label", default="")
    ap.add_argument("--out", default=str(REPO / "bench/results/mitsuba" / f"{datetime.date.today().isoformat()}_grazing-plane"))
    ap.add_argument("--work", default="/tmp/lightpass-grazing")
    ap.add_argument("--mitsuba-spp", type=int, default=0,
                    help="also path trace the same plane with Mitsuba (roughconductor, GGX, F = 1) at this many "
                         "samples a pixel (reused from --work when there) and append to grazing_plane_mitsuba.md")
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    width, height = (int(v) for v in args.size.split("x"))
    out, work = Path(args.out), Path(args.work)
    out.mkdir(parents=True, exist_ok=True)
    work.mkdir(parents=True, exist_ok=True)
    if args.roughness is not None:
        material = {"diffuse": [0, 0, 0], "specular": [1, 1, 1], "roughness": args.roughness}
        rough = args.roughness
    else:
        n = 10000.0 if args.shininess is None else args.shininess
        material = {"diffuse": [0, 0, 0], "specular": [1, 1, 1], "shininess": n}
        rough = (2.0 / (n + 2.0)) ** 0.25
    alpha = rough * rough
    scene = {"description": "generated by bench/mitsuba/grazing_plane.py", "camera": CAMERA,
             "models": [{"name": "plane", "primitive": "plane", "scale": [400, 1, 400], "material": material}],
             "lights": [], "environment": {"map": str(Path(args.map).resolve()), "intensity": 1.0, "rotation": 0.0},
             "ambient": [0, 0, 0]}
    scene_path = work / "grazing_plane.json"
    scene_path.write_text(json.dumps(scene, indent=1))
    exr = work / "grazing_plane.exr"
    cmd = [args.lightpass, "render", "--scene", str(scene_path), "--ibl", "--brdf", "ggx", "--exr", str(exr),
           "--out", str(exr.with_suffix(".png")), "--size", f"{width}x{height}", "--frames", "1", "--specular-masking", args.specular_masking,
           *args.lightpass_args.split()]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"grazing_plane.py: lightpass failed: {proc.stderr.strip().splitlines()[-1:]}")
    lp = read_rgb(exr)

    # Plane pixels: the centre ray hits y = 0 within 150 m.
    pos = np.array(CAMERA["position"])
    fwd = np.array(CAMERA["target"]) - pos
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, CAMERA["up"])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    t = math.tan(math.radians(CAMERA["fov"]) / 2)
    xs = ((np.arange(width) + 0.5) / width * 2 - 1) * t * width / height
    ys = (1 - (np.arange(height) + 0.5) / height * 2) * t
    d = fwd + xs[None, :, None] * right + ys[:, None, None] * up
    d /= np.linalg.norm(d, axis=2, keepdims=True)
    hit_t = np.where(d[..., 1] < 0, -pos[1] / np.minimum(d[..., 1], -1e-9), np.inf)
    mask = hit_t < 150.0
    N = np.array([0.0, 1.0, 0.0])
    V = -d[mask]
    nv = np.clip(V[:, 1], 0, 1)
    R = 2 * nv[:, None] * N - V
    Rd = (1 - alpha * alpha) * R + alpha * alpha * N
    Rd /= np.linalg.norm(Rd, axis=1, keepdims=True)

    env = read_rgb(args.map)
    while env.shape[1] > args.map_width:  # 2x2 box: the integral's texels (a lamp keeps its energy)
        env = 0.25 * (env[0::2, 0::2] + env[1::2, 0::2] + env[0::2, 1::2] + env[1::2, 1::2])
    H, W, _ = env.shape
    theta = (np.arange(H) + 0.5) / H * math.pi
    phi = ((np.arange(W) + 0.5) / W - 0.5) * 2 * math.pi
    L = np.stack([np.outer(np.sin(theta), np.sin(phi)), np.outer(np.cos(theta), np.ones(W)),
                  -np.outer(np.sin(theta), np.cos(phi))], -1).reshape(-1, 3)
    omega = np.repeat(np.sin(theta) * (math.pi / H) * (2 * math.pi / W), W)
    rad = env.reshape(-1, 3)
    up_half = L[:, 1] > -0.2  # the lobes around R' (above the plane) never reach below this
    L, omega, rad = L[up_half], omega[up_half], rad[up_half]
    pref = np.zeros((len(Rd), 3))
    for i in range(0, len(Rd), 32):
        c = Rd[i:i + 32] @ L.T
        nh = np.sqrt(np.clip((1 + c) / 2, 0, 1))
        w = ggx_d(nh, alpha) * np.maximum(c, 0) * omega
        pref[i:i + 32] = (w @ rad) / w.sum(1, keepdims=True)
    grid = np.linspace(0, 1, 65)
    dfg_grid = np.array([dfg(x, rough, args.specular_masking) for x in grid])
    exact = pref * np.interp(nv, grid, dfg_grid)[:, None]
    got = lp[mask]
    lum = lambda c: c @ np.array([0.2126, 0.7152, 0.0722])
    e, g_ = lum(exact), lum(got)
    lampish = e > 4 * np.median(e)
    rel_all = g_.mean() / e.mean() - 1
    rel_lamp = g_[lampish].mean() / e[lampish].mean() - 1 if lampish.any() else float("nan")
    label = args.label or (args.lightpass_args or "defaults") + f" ({args.specular_masking})"
    line = (f"| {label} | {rough:.3f} | {int(mask.sum())} | {rel_all:+.3f} | {int(lampish.sum())} | {rel_lamp:+.3f} |")
    md = out / "grazing_plane.md"
    if not md.exists():
        md.write_text("# Smooth plane at grazing angles (lamps_low.hdr) against the exact split sum\n\n"
                      "Relative error of the mean luminance, lightpass / exact split sum − 1 (bench/mitsuba/grazing_plane.py).\n\n"
                      "| build / flags | roughness | plane px | all | lamp px | over lamp reflections |\n"
                      "| --- | ---: | ---: | ---: | ---: | ---: |\n")
    with open(md, "a") as f:
        f.write(line + "\n")
    print(line)
    if args.mitsuba_spp > 0:
        ref_exr = work / f"grazing_mitsuba_r{rough:.4f}_{width}x{height}_{args.mitsuba_spp}spp.exr"
        if not ref_exr.is_file():
            mi.Bitmap(mitsuba_render(args.map, alpha, width, height, args.mitsuba_spp)).write(str(ref_exr))
        ref = lum(read_rgb(ref_exr)[mask])
        lamp_ref = ref > 4 * np.median(ref)
        line = (f"| {label} | {rough:.3f} | {int(mask.sum())} | {g_.sum() / ref.sum() - 1:+.3f} | {int(lamp_ref.sum())} | "
                f"{g_[lamp_ref].sum() / ref[lamp_ref].sum() - 1:+.3f} | {e.sum() / ref.sum() - 1:+.3f} |")
        md = out / "grazing_plane_mitsuba.md"
        if not md.exists():
            md.write_text("# Smooth plane at grazing angles (lamps_low.hdr) against Mitsuba 3\n\n"
                          "Relative error of the summed luminance over the plane's pixels and over the pixels where "
                          "Mitsuba's plane is brighter than 4x its median (the lamps' reflections), lightpass / "
                          "Mitsuba − 1; last column the exact split sum's (bench/mitsuba/grazing_plane.py "
                          "--mitsuba-spp N; Mitsuba: roughconductor, GGX, F = 1, path, max depth 2).\n\n"
                          "| build / flags | roughness | plane px | all | lamp px | over lamp reflections | exact split sum, all |\n"
                          "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n")
        with open(md, "a") as f:
            f.write(line + "\n")
        print(line)


def mitsuba_render(map_path, alpha, width, height, spp):
    """The plane under the map path traced by Mitsuba; the map's orientation as ground_truth.py's."""
    scene = {"type": "scene", "integrator": {"type": "path", "max_depth": 2},
             "sensor": {"type": "perspective", "fov": CAMERA["fov"], "fov_axis": "y", "near_clip": CAMERA["near"],
                        "far_clip": CAMERA["far"],
                        "to_world": mi.ScalarTransform4f().look_at(origin=CAMERA["position"], target=CAMERA["target"],
                                                                   up=CAMERA["up"]),
                        "film": {"type": "hdrfilm", "width": width, "height": height, "rfilter": {"type": "box"},
                                 "pixel_format": "rgb"},
                        "sampler": {"type": "independent", "sample_count": spp}},
             "env": {"type": "envmap", "filename": str(map_path), "scale": 1.0,
                     "to_world": mi.ScalarTransform4f().rotate(axis=[0, 1, 0], angle=180.0)},
             "plane": {"type": "rectangle",
                       "to_world": mi.ScalarTransform4f().rotate(axis=[1, 0, 0], angle=-90.0).scale(1000.0),
                       "bsdf": {"type": "roughconductor", "material": "none", "distribution": "ggx", "alpha": alpha,
                                "specular_reflectance": {"type": "rgb", "value": [1.0, 1.0, 1.0]}}}}
    return np.array(mi.render(mi.load_dict(scene), spp=spp))


if __name__ == "__main__":
    main()
