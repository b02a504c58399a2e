#!/usr/bin/env python3
"""bench/lighting_clustered.sh's table: per scene and size, the local_lights pass's median GPU ms for
the tiled and clustered methods at each light count, each with measured/floor (the floor: the bytes
the pass must move once, over the measured bandwidth), and clustered/tiled."""
import json
import re
import sys


def flag(flags, name):
    m = re.search(rf"--{name} (\S+)", flags)
    return m.group(1) if m else None


def main(paths):
    for path in paths:
        d = json.load(open(path))
        cells = {}
        for run in d["runs"]:
            p = run["passes"].get("local_lights")
            if not p:
                continue
            key = (f"{run['width']}x{run['height']}", int(flag(run["flags"], "light-count")), flag(run["flags"], "local-lights"))
            cells[key] = (p["median_ms"], p.get("floor_ms"), run.get("frames"))
        print(f"## {d.get('scene', path)}\n\nDevice: {d.get('device', '?')}\n")
        for size in sorted({k[0] for k in cells}, key=lambda s: int(s.split("x")[0])):
            print(f"**{size}**: `local_lights` GPU ms (frames) · measured/floor\n")
            print("| lights | tiled | clustered | clustered / tiled |")
            print("|---:|---:|---:|---:|")
            for n in sorted({k[1] for k in cells if k[0] == size}):
                row = []
                for m in ("tiled", "clustered"):
                    c = cells.get((size, n, m))
                    if not c:
                        row.append("-")
                        continue
                    ms, floor, frames = c
                    ratio = f" · {ms / floor:.3g}×" if floor else ""
                    row.append(f"{ms:.3f} ({frames}){ratio}")
                t, c = cells.get((size, n, "tiled")), cells.get((size, n, "clustered"))
                row.append(f"{c[0] / t[0]:.3g}" if t and c and t[0] > 0 else "-")
                print(f"| {n} | " + " | ".join(row) + " |")
            print()


if __name__ == "__main__":
    main(sys.argv[1:])
