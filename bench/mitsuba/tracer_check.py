#!/usr/bin/env python3
"""lightpass's path tracer against Mitsuba 3, within the noise of both.

The sphere grid of ground_truth.py (GGX spheres with Fresnel 1 across roughness, Lambertian spheres
across albedo) under each environment map, rendered whole (neighbours occlude and, with --bounces,
light each other in both renderers) by `lightpass render --render-path pathtraced` and by Mitsuba's
`path` integrator. One interaction by default (lightpass --direct-only, Mitsuba max depth 2), so the
environment's importance sampling and the BRDF's are what is checked; --bounces B compares full
transport (Mitsuba max depth B + 1). lightpass's GGX uses the separable Smith masking here
(--specular-masking separable), Mitsuba's roughconductor's model: a reference must model what it checks.

Noise, measured, not assumed: lightpass renders N and 2N samples; its samples are the same for the
first N (seeded by pixel and sample index), so 2 img(2N) - img(N) is an independent N-sample image and
the pixel-wise difference of the two halves gives each pixel's variance. Mitsuba renders twice with
two seeds. Per sphere, the standard error of each mean is sqrt(sum d^2 / 4) / n (d the two halves'
difference, n pixels), and the difference of the two renderers' means is within noise when it is
under 3 combined standard errors.

Run through bench/mitsuba/run.sh tracer [--maps ...] [--size 192x108] [--spp 256] [--bounces B].
"""
import argparse
import datetime
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import mitsuba as mi

import ground_truth as gt

REPO = gt.REPO


def render_lightpass(lightpass, scene_path, exr, width, height, spp, transport):
    cmd = [str(lightpass), "render", "--scene", str(scene_path), "--render-path", "pathtraced", "--spp", str(spp),
           *transport, "--brdf", "ggx", "--specular-masking", "separable", "--exr", str(exr),
           "--out", str(exr.with_suffix(".png")), "--size", f"{width}x{height}", "--frames", "1"]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"tracer_check.py: lightpass failed on {scene_path}: {proc.stderr.strip().splitlines()[-1:]}")
    return time.perf_counter() - t0


def sphere_stats(a, b, masks):
    """Per sphere: the mean of (a + b) / 2 over its pixels and that mean's standard error from a - b."""
    out = {}
    for name, m in masks.items():
        d = (a - b)[m].mean(axis=1)  # per pixel, grey
        n = d.size
        out[name] = (float(((a + b) / 2)[m].mean()), float(np.sqrt(np.sum(d * d) / 4.0) / n))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lightpass", default=str(REPO / "build/app/lightpass"))
    ap.add_argument("--maps", nargs="*", help="environment maps (default: hdr/sky.exr, bench/mitsuba/maps/lamp50k.hdr, "
                    "bench/mitsuba/maps/furnace.hdr)")
    ap.add_argument("--size", default="192x108")
    ap.add_argument("--spp", type=int, default=256, help="samples a pixel of each half (lightpass and Mitsuba alike)")
    ap.add_argument("--bounces", type=int, default=0, help="0: one interaction (--direct-only); B: full transport, B bounces")
    ap.add_argument("--variant", default="scalar_rgb")
    ap.add_argument("--out", default=str(REPO / "bench/results/path-tracer" / f"{datetime.date.today().isoformat()}_against-mitsuba"))
    ap.add_argument("--scenes", default=str(REPO / "bench/mitsuba/scenes"))
    ap.add_argument("--work", default="/tmp/lightpass-mitsuba-tracer")
    args = ap.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    mi.set_variant(args.variant)
    maps = [Path(m).resolve() for m in args.maps] if args.maps else [
        REPO / "hdr/sky.exr", REPO / "bench/mitsuba/maps/lamp50k.hdr", REPO / "bench/mitsuba/maps/furnace.hdr"]
    for m in maps:
        if not m.is_file():
            sys.exit(f"tracer_check.py: {m}: no such map (bench/mitsuba/make_maps.py makes the synthetic ones)")
    out, scenes, work = Path(args.out), Path(args.scenes), Path(args.work)
    for d in (out, scenes, work):
        d.mkdir(parents=True, exist_ok=True)
    transport = ["--direct-only"] if args.bounces == 0 else ["--bounces", str(args.bounces)]
    max_depth = 2 if args.bounces == 0 else args.bounces + 1
    masks = gt.sphere_masks(width, height)
    rows, lines = [], []
    for m in maps:
        stem = m.stem
        scene_path = scenes / f"{stem}.json"
        gt.lightpass_scene(m, scene_path)
        a_exr, b_exr = work / f"{stem}_lp_{args.spp}.exr", work / f"{stem}_lp_{2 * args.spp}.exr"
        lp_s = render_lightpass(args.lightpass, scene_path, a_exr, width, height, args.spp, transport)
        lp_s += render_lightpass(args.lightpass, scene_path, b_exr, width, height, 2 * args.spp, transport)
        first, both = gt.read_rgb(a_exr), gt.read_rgb(b_exr)
        second = 2.0 * both - first
        scene = gt.mitsuba_scene(m, width, height, args.spp, None, max_depth)
        t0 = time.perf_counter()
        mi0 = np.array(mi.render(scene, spp=args.spp, seed=0))
        mi1 = np.array(mi.render(scene, spp=args.spp, seed=1))
        mi_s = time.perf_counter() - t0
        gt.write_comparison(out / f"{stem}.png", both, (mi0 + mi1) / 2)
        lp, ref = sphere_stats(first, second, masks), sphere_stats(mi0, mi1, masks)
        worst = 0.0
        for name, _, kind, p, _ in gt.spheres():
            (ml, sl), (mm, sm) = lp[name], ref[name]
            sigma = float(np.hypot(sl, sm))
            z = (ml - mm) / sigma if sigma > 0 else float("inf")
            worst = max(worst, abs(z))
            rows.append({"map": stem, "sphere": name, "lightpass": ml, "lightpass_se": sl, "mitsuba": mm, "mitsuba_se": sm,
                         "rel_diff": (ml - mm) / mm if mm > 0 else float("nan"), "z": z})
        print(f"{stem}: lightpass {lp_s:.1f} s, Mitsuba {mi_s:.1f} s, largest |difference| {worst:.2f} standard errors",
              flush=True)
    lines += [f"# lightpass path tracer vs Mitsuba 3 ({args.variant}), {width}x{height}, "
              f"{'one interaction' if args.bounces == 0 else f'{args.bounces} bounces'}, 2 x {args.spp} samples each",
              "", "Per sphere: mean radiance (grey) over its pixels in each renderer (2 x N samples), the standard "
              "error of that mean (from the two N-sample halves), the relative difference and the difference in "
              "combined standard errors z. Within noise: |z| < 3.", "",
              "| map | sphere | lightpass | ± | Mitsuba | ± | rel. diff | z |", "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        lines.append(f"| {r['map']} | {r['sphere']} | {r['lightpass']:.4f} | {r['lightpass_se']:.4f} | {r['mitsuba']:.4f} | "
                     f"{r['mitsuba_se']:.4f} | {100 * r['rel_diff']:+.2f}% | {r['z']:+.2f} |")
    within = sum(1 for r in rows if abs(r["z"]) < 3)
    lines += ["", f"{within} of {len(rows)} sphere means within 3 standard errors."]
    (out / "summary.md").write_text("\n".join(lines) + "\n")
    print(f"{within} of {len(rows)} within 3 standard errors; wrote {out / 'summary.md'}")


if __name__ == "__main__":
    main()
