#!/usr/bin/env python3
"""bench/lighting_clustered.sh VARIANTS=1's tables, from OUTDIR/variants_<variant>_<scene>.json: per
scene and size, the local_lights pass's median GPU ms of tiled (measured with the `default` variant)
and of each clustered variant (16 px), with clustered / tiled (against the tiled measured in the
variant's own process where it has one: `default`, `stop28`, `one_dispatch`, `lists`; the other process's tiled
is shown again, which shows how much tiled moves between processes); then issue #18's targets per variant:
clustered <= tiled in every cell, and >= 2x faster than tiled where tiles span near and far (the
depth-discontinuity and fence scenes, 256 lights and more)."""
import glob
import json
import os
import re
import sys

ORDER = ("stop28", "lists", "one_dispatch", "default", "compact", "compact2", "bits32", "group_walk", "merged_list",
         "pair_union", "all_slices", "no_box", "merge1_5", "merge2", "merge4", "merge8", "cull_only", "tile_only",
         "tiled_cull_only", "tiled_pad8k")
SCENES = ("gallery", "depth-discontinuity", "fence")
SPANNING = ("depth-discontinuity", "fence")


def flag(flags, name):
    m = re.search(rf"--{name} (\S+)", flags)
    return m.group(1) if m else None


def load(path):
    """{(size, lights, method): median local_lights ms}, device"""
    d = json.load(open(path))
    cells = {}
    for run in d["runs"]:
        local = run["passes"].get("local_lights")
        if not local:
            continue
        method = flag(run["flags"], "local-lights")
        if method == "clustered" and flag(run["flags"], "cluster-size") not in (None, "16"):
            method += " " + flag(run["flags"], "cluster-size")  # another tile size: its own column
        key = (f"{run['width']}x{run['height']}", int(flag(run["flags"], "light-count")), method)
        cells[key] = local["median_ms"]
    return cells, d.get("device", "?")


def main(outdir):
    found = {}
    device = "?"
    for path in glob.glob(os.path.join(outdir, "variants_*.json")):
        m = re.match(r"variants_(.+)_(gallery|depth-discontinuity|fence)\.json$", os.path.basename(path))
        if not m:
            continue
        try:
            cells, device = load(path)
        except (OSError, ValueError, KeyError) as e:
            print(f"{path}: not readable: {e}\n")
            continue
        if m.group(1).startswith("tiled_"):  # a variant of the tiled method: its own column
            cells = {(k[0], k[1], "clustered"): ms for k, ms in cells.items() if k[2] == "tiled"}
        found[(m.group(1), m.group(2))] = cells
        # Other tile sizes of the same kernel (e.g. `default` at --cluster-size 32): variant "<v> <px>px",
        # against the same process's tiled.
        for px in sorted({k[2].split(" ")[1] for k in cells if k[2].startswith("clustered ")}):
            found[(f"{m.group(1)} {px}px", m.group(2))] = {
                (k[0], k[1], "clustered" if k[2] == f"clustered {px}" else k[2]): ms
                for k, ms in cells.items() if k[2] in (f"clustered {px}", "tiled")}
    variants = [v for v in ORDER if any(k[0] == v for k in found)]
    variants += sorted({k[0] for k in found} - set(variants))
    print(f"# Clustered kernel variants against tiled (`local_lights` GPU ms, median)\n\nDevice: {device}\n")
    worst = {v: [] for v in variants}
    for scene in SCENES:
        tiled = found.get(("default", scene), {})
        if not any(k[1] == scene for k in found):
            continue
        sizes = sorted({k[0] for (v, s), c in found.items() if s == scene for k in c}, key=lambda s: int(s.split("x")[0]))
        for size in sizes:
            counts = sorted({k[1] for (v, s), c in found.items() if s == scene for k in c if k[0] == size})
            print(f"## {scene} {size}: ms (clustered / tiled)\n")
            second = next((v for v in variants if v != "default" and
                           any(k[2] == "tiled" for k in found.get((v, scene), {}))), None)
            again = second is not None
            print("| lights | tiled | " + " | ".join(variants) + (f" | tiled again ({second}'s run) |" if again else " |"))
            print("|---:|" + "---:|" * (len(variants) + 1 + int(again)))
            for n in counts:
                t = tiled.get((size, n, "tiled"))
                row = [f"{t:.3f}" if t is not None else "-"]
                for v in variants:
                    own = found.get((v, scene), {})
                    c = own.get((size, n, "clustered"))
                    if c is None:
                        row.append("-")
                        continue
                    ref = own.get((size, n, "tiled"), t)
                    row.append(f"{c:.3f} ({c / ref:.2f})" if ref else f"{c:.3f}")
                    if ref:
                        worst[v].append((scene, size, n, c / ref))
                other = found.get((second, scene), {}).get((size, n, "tiled")) if again else None
                if other is not None:
                    row.append(f"{other:.3f}")
                print(f"| {n} | " + " | ".join(row) + " |")
            print()
    print("## Issue #18's targets per variant\n")
    print("| variant | clustered / tiled, worst (where) | least speed-up where tiles span near and far, >= 256 lights (where) |")
    print("|---|---:|---:|")
    for v in variants:
        rows = worst[v]
        if not rows or v.startswith("tiled_"):
            continue
        w = max(rows, key=lambda r: r[3])
        span = [r for r in rows if r[0] in SPANNING and r[2] >= 256]
        least = max(span, key=lambda r: r[3]) if span else None
        ls = f"{1.0 / least[3]:.2f}x ({least[0]} {least[1]}, {least[2]})" if least else "-"
        print(f"| {v} | {w[3]:.2f} ({w[0]} {w[1]}, {w[2]}) | {ls} |")
    print("\n(targets: worst <= 1.00 and least speed-up >= 2.00x)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
