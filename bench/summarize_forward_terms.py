#!/usr/bin/env python3
"""bench/forward_terms.sh's table: per scene and size, what each shading term costs in forward+'s
fragment shader (forward_opaque as it is, less forward_opaque with the term taken out) against the
deferred compute pass that evaluates the same shader functions, and their ratio.

  suns + shadows   full - no_sun       against global_lights (suns, shadows and the ambient term)
  IBL              full - no_ibl       against ibl
  material         material            against gbuffer_resolve (the material from the visibility
                   (raster, material,   buffer, written to the G-buffer targets)
                   one RGBA16F write)
  raster           depth_prepass       against gbuffer_visibility (depth + triangle id)
  early tests      early - full        (about 0: the driver already tests depth before the shader)

Usage: summarize_forward_terms.py OUTDIR (reads OUTDIR/forward_terms_<scene>_<variant>.json)."""
import json
import os
import sys

VARIANTS = ("full", "no_sun", "no_ibl", "material", "early", "deferred")


def load(outdir, scene, variant):
    """{size: {pass: median ms}} of one bench file, {} when missing or unreadable."""
    try:
        d = json.load(open(os.path.join(outdir, f"forward_terms_{scene}_{variant}.json")))
    except (OSError, ValueError):
        return {}
    out = {}
    for run in d.get("runs", []):
        out[f"{run['width']}x{run['height']}"] = {
            k: v["median_ms"] for k, v in run["passes"].items() if isinstance(v, dict) and "median_ms" in v
        }
    return out


def fmt(x):
    return "-" if x is None else f"{x:.3f}"


def ratio(a, b):
    return "-" if a is None or b is None or b <= 0 else f"{a / b:.1f}×"


def main(outdir):
    device = ""
    try:
        device = open(os.path.join(outdir, "device.txt")).read().strip()
    except OSError:
        pass
    print(f"forward+ shading terms, fragment against compute. Device: {device or 'unknown'}; one local light;")
    print("median GPU ms (bench/forward_terms.sh). Fragment: forward_opaque's time with the term, less without it.\n")
    print("| scene, size | forward_opaque | suns + shadows: fragment / compute | IBL: fragment / compute "
          "| material: fragment / compute | raster: depth_prepass / gbuffer_visibility | early tests − full |")
    print("| --- | ---: | --- | --- | --- | --- | ---: |")
    for scene in ("gallery", "cornell"):
        runs = {v: load(outdir, scene, v) for v in VARIANTS}
        for size in ("1920x1080", "3840x2160"):
            def p(v, name):
                return runs[v].get(size, {}).get(name)
            full = p("full", "forward_opaque")
            if full is None:
                print(f"| {scene} {size} | missing | | | | | |")
                continue
            no_sun, no_ibl, material, early = (p(v, "forward_opaque") for v in ("no_sun", "no_ibl", "material", "early"))
            sun = None if no_sun is None else full - no_sun
            ibl = None if no_ibl is None else full - no_ibl
            d_sun, d_ibl, d_mat = p("deferred", "global_lights"), p("deferred", "ibl"), p("deferred", "gbuffer_resolve")
            pre, vis = p("full", "depth_prepass"), p("deferred", "gbuffer_visibility")
            cells = [
                f"{fmt(sun)} / {fmt(d_sun)} ({ratio(sun, d_sun)})",
                f"{fmt(ibl)} / {fmt(d_ibl)} ({ratio(ibl, d_ibl)})" if d_ibl is not None else f"{fmt(ibl)} / no IBL pass",
                f"{fmt(material)} / {fmt(d_mat)} ({ratio(material, d_mat)})",
                f"{fmt(pre)} / {fmt(vis)} ({ratio(pre, vis)})",
                fmt(None if early is None else early - full),
            ]
            print(f"| {scene} {size} | {fmt(full)} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: summarize_forward_terms.py OUTDIR")
    main(sys.argv[1])
