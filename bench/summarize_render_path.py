#!/usr/bin/env python3
"""bench/render_path.sh's table: per scene and size, at each light count, the median GPU ms of the
whole frame and of the opaque geometry + lighting passes for deferred (tiled and clustered local
lights) and forward+, and forward+ / deferred clustered. Geometry + lighting: deferred's gbuffer
(or gbuffer_visibility + gbuffer_resolve),
global_lights, ibl, local_lights, emission; forward+'s depth_prepass and forward_opaque (each
variant's shadow maps, AO, sky and post effects are the same passes in both)."""
import json
import re
import sys

DEFERRED = ("gbuffer", "gbuffer_visibility", "gbuffer_resolve", "global_lights", "ibl", "local_lights", "emission")
FORWARD = ("depth_prepass", "forward_opaque")


def flag(flags, name):
    m = re.search(rf"--{name} (\S+)", flags)
    return m.group(1) if m else None


def variant(flags):
    if flag(flags, "render-path") == "forward+":
        return "forward+"
    return "deferred " + (flag(flags, "local-lights") or "?")


def main(paths):
    order = ("deferred tiled", "deferred clustered", "forward+")
    for path in paths:
        try:
            d = json.load(open(path))
        except (OSError, ValueError) as e:
            print(f"## {path}\n\nnot readable: {e}\n")
            continue
        cells = {}
        for run in d["runs"]:
            p = run["passes"]
            v = variant(run["flags"])
            shading = sum(p[n]["median_ms"] for n in (FORWARD if v == "forward+" else DEFERRED) if n in p)
            frame = p.get("frame", {}).get("median_ms")
            key = (f"{run['width']}x{run['height']}", int(flag(run["flags"], "light-count")), v)
            cells[key] = (frame, shading, run.get("frames"))
        print(f"## {d.get('scene', path)}\n\nDevice: {d.get('device', '?')}\n")
        for size in sorted({k[0] for k in cells}, key=lambda s: int(s.split("x")[0])):
            print(f"**{size}**: GPU ms, frame / geometry + lighting (frames)\n")
            print("| lights | " + " | ".join(order) + " | forward+ / deferred clustered (frame) |")
            print("|---:|" + "---:|" * (len(order) + 1))
            for n in sorted({k[1] for k in cells if k[0] == size}):
                row = []
                for v in order:
                    c = cells.get((size, n, v))
                    row.append(f"{c[0]:.3f} / {c[1]:.3f} ({c[2]})" if c and c[0] is not None else "-")
                f, c = cells.get((size, n, "forward+")), cells.get((size, n, "deferred clustered"))
                row.append(f"{f[0] / c[0]:.3g}" if f and c and f[0] and c[0] else "-")
                print(f"| {n} | " + " | ".join(row) + " |")
            print()


if __name__ == "__main__":
    main(sys.argv[1:])
