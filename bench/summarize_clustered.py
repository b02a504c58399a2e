#!/usr/bin/env python3
"""bench/lighting_clustered.sh's tables. Per scene and size:
1. the local_lights pass's median GPU ms for deferred tiled and clustered (16- and 32-pixel froxel
   tiles; `clustered 16` runs --clustered-kernel auto, the default, and `clustered 16 froxels` the
   clustered kernel alone), each with measured/floor (the floor: the bytes the pass must move once,
   over the measured bandwidth), and clustered/tiled;
2. the whole frame and the opaque geometry + lighting passes for deferred tiled, deferred clustered
   (16 px) and forward+ (deferred: gbuffer or gbuffer_visibility + gbuffer_resolve, global_lights, ibl,
   local_lights, emission; forward+: depth_prepass, forward_opaque), and forward+ / deferred
   clustered (frame);
then issue #18's targets: clustered (16 px, the default) <= tiled in every cell, and >= 2x faster
than tiled where tiles span near and far (the depth-discontinuity and fence scenes)."""
import json
import re
import sys

DEFERRED = ("gbuffer", "gbuffer_visibility", "gbuffer_resolve", "global_lights", "ibl", "local_lights", "emission")
FORWARD = ("depth_prepass", "forward_opaque")
LOCAL = ("tiled", "clustered 16", "clustered 16 froxels", "clustered 32")
RATIOS = ("clustered 16", "clustered 16 froxels", "clustered 32")
SPANNING = ("depth-discontinuity", "fence")  # scenes whose tiles span near and far


def flag(flags, name):
    m = re.search(rf"--{name} (\S+)", flags)
    return m.group(1) if m else None


def variant(flags):
    if flag(flags, "render-path") == "forward+":
        return "forward+"
    method = flag(flags, "local-lights") or "?"
    if method == "clustered":
        kernel = flag(flags, "clustered-kernel")
        return f"clustered {flag(flags, 'cluster-size') or '16'}" + (f" {kernel}" if kernel and kernel != "auto" else "")
    return method


def size_key(s):
    return int(s.split("x")[0])


def load(path):
    d = json.load(open(path))
    cells = {}
    for run in d["runs"]:
        p = run["passes"]
        v = variant(run["flags"])
        local = p.get("local_lights")
        shading = sum(p[n]["median_ms"] for n in (FORWARD if v == "forward+" else DEFERRED) if n in p)
        key = (f"{run['width']}x{run['height']}", int(flag(run["flags"], "light-count")), v)
        cells[key] = {
            "local": local["median_ms"] if local else None,
            "floor": local.get("floor_ms") if local else None,
            "frame": p.get("frame", {}).get("median_ms"),
            "shading": shading,
            "frames": run.get("frames"),
            "kernel": run.get("clustered_kernel", {}).get("shading"),  # auto: the kernel the race kept
        }
    return d, cells


def ratio(a, b):
    return a / b if a is not None and b else None


def fmt(x, digits=3):
    return "-" if x is None else f"{x:.{digits}g}"


def main(paths):
    targets = []
    for path in paths:
        try:
            d, cells = load(path)
        except (OSError, ValueError, KeyError) as e:
            print(f"## {path}\n\nnot readable: {e}\n")
            continue
        scene = d.get("scene", path)
        print(f"## {scene}\n\nDevice: {d.get('device', '?')}\n")
        sizes = sorted({k[0] for k in cells}, key=size_key)
        for size in sizes:
            counts = sorted({k[1] for k in cells if k[0] == size})
            print(f"**{size}**: `local_lights` GPU ms (frames) · measured/floor [the kernel auto kept]\n")
            print("| lights | " + " | ".join(LOCAL) + " | " + " | ".join(f"{v} / tiled" for v in RATIOS) + " |")
            print("|---:|" + "---:|" * (len(LOCAL) + len(RATIOS)))
            for n in counts:
                row = []
                for v in LOCAL:
                    c = cells.get((size, n, v))
                    if not c or c["local"] is None:
                        row.append("-")
                        continue
                    floor = f" · {c['local'] / c['floor']:.3g}×" if c["floor"] else ""
                    kept = f" [{c['kernel']}]" if c.get("kernel") else ""
                    row.append(f"{c['local']:.3f} ({c['frames']}){floor}{kept}")
                t = cells.get((size, n, "tiled"), {}).get("local")
                for v in RATIOS:
                    c = cells.get((size, n, v), {}).get("local")
                    row.append(fmt(ratio(c, t)))
                    if v == "clustered 16" and c is not None and t:
                        targets.append((scene, size, n, c / t))
                print(f"| {n} | " + " | ".join(row) + " |")
            print()
            order = ("tiled", "clustered 16", "forward+")
            print(f"**{size}**: GPU ms, frame / opaque geometry + lighting (deferred tiled, deferred clustered "
                  "16 px, forward+)\n")
            print("| lights | deferred tiled | deferred clustered | forward+ | forward+ / deferred clustered (frame) |")
            print("|---:|---:|---:|---:|---:|")
            for n in counts:
                row = []
                for v in order:
                    c = cells.get((size, n, v))
                    row.append(f"{c['frame']:.3f} / {c['shading']:.3f}" if c and c["frame"] is not None else "-")
                f, c = cells.get((size, n, "forward+")), cells.get((size, n, "clustered 16"))
                row.append(fmt(ratio(f and f["frame"], c and c["frame"])))
                print(f"| {n} | " + " | ".join(row) + " |")
            print()
    if not targets:
        return
    print("## Issue #18's targets (clustered 16 px against tiled, `local_lights` ms)\n")
    print("| scene | size | clustered / tiled, worst (lights) | tiled / clustered at 1024 · 4096 · 16384 lights |")
    print("|---|---|---:|---:|")
    for scene in dict.fromkeys(t[0] for t in targets):
        for size in sorted({t[1] for t in targets if t[0] == scene}, key=size_key):
            rows = [t for t in targets if t[0] == scene and t[1] == size]
            worst = max(rows, key=lambda t: t[3])
            speed = {t[2]: 1.0 / t[3] for t in rows if t[3] > 0}
            big = " · ".join(f"{speed[n]:.2f}×" if n in speed else "-" for n in (1024, 4096, 16384))
            print(f"| {scene} | {size} | {worst[3]:.3g} ({worst[2]}) | {big} |")
    worst = max(targets, key=lambda t: t[3])
    # Where both columns run the same kernel (auto below 32 lights, or where the race kept tiles) the
    # ratio still moves by a few tenths of a percent from run to run: said, not hidden.
    above = [t for t in targets if t[3] > 1.0]
    beyond_noise = [t for t in targets if t[3] > 1.01]
    verdict = "met" if not above else ("met within 1% (the two medians' run-to-run spread)" if not beyond_noise else "not met")
    print(f"\n- clustered <= tiled everywhere: {verdict} (worst {worst[3]:.4f}: {worst[0]} {worst[1]}, {worst[2]} lights; "
          f"{len(above)} of {len(targets)} cells above 1, {len(beyond_noise)} above 1.01)")
    spanning = [t for t in targets if any(s in t[0] for s in SPANNING) and t[2] >= 256]
    if spanning:
        least = max(spanning, key=lambda t: t[3])
        print(f"- >= 2x faster where tiles span near and far (depth-discontinuity and fence, 256 lights and more): "
              f"{'met' if least[3] <= 0.5 else 'not met'} (least {1.0 / least[3]:.2f}×: {least[0]} {least[1]}, "
              f"{least[2]} lights)")


if __name__ == "__main__":
    main(sys.argv[1:])
