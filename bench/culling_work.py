#!/usr/bin/env python3
"""The shading work light culling leaves, per warp, from the scene file alone (CPU; scenes made of the
unit cube, plane and sphere primitives, as bench/tile_depth_spans.py reads them): what bounds the
clustered method's gain over tiled before any kernel is written. Lights as lightpass's --light-count
makes them (uniform in the scene's bounding box, range r0 * (0.6 + 0.8 u) with about 8 overlapping a
point; random here, not lightpass's hash, so the same statistics, not the same lights); all treated
as point lights. A warp is 32 pixels of a 16-pixel tile (two rows), as the fused kernels map them.
Per warp:
  tested, tiled     the tile's list (sphere against the tile frustum between its nearest and
                    farthest pixel): every lane steps through all of it;
  full, tiled       the lights of that list that reach at least one lane: a step where any lane is
                    in range runs the whole BRDF for the warp (the others take the early-out);
  tested, clustered the longest list among its lanes' slices (slice depth range and box): lanes
                    step together, so the warp takes as many steps as its longest lane;
  full, ideal       the most lights reaching any one lane: no culling and no pixel order gets
                    below this (each lane must shade every light that reaches it).
Sums over all warps, per scene and light count; "full, tiled / full, ideal" bounds what any culling
can save of the BRDF work, "tested, tiled / tested, clustered" what tighter lists save of the steps.
Usage: bench/culling_work.py [--size 1920x1080] [--lights 256,1024] SCENE.json ...  (Markdown)"""
import argparse
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tile_depth_spans import SLICES, TILE, camera_basis, scene_depths  # noqa: E402


def view_matrix(cam):
    pos, right, up, fwd = camera_basis(cam)
    R = np.stack([right, up, -fwd])
    return R, -R @ pos


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--lights", default="256,1024")
    ap.add_argument("scenes", nargs="+")
    a = ap.parse_args()
    width, height = map(int, a.size.split("x"))
    counts = [int(c) for c in a.lights.split(",")]
    print(f"Warps of 32 pixels in {TILE}-pixel tiles at {width}x{height}, {SLICES} slices; sums over warps "
          "(millions of light steps)\n")
    print("| scene | lights | tested, tiled | full, tiled | tested, clustered | full, ideal | "
          "tested, tiled / clustered | full, tiled / ideal |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    rng = np.random.default_rng(1)
    for path in a.scenes:
        scene = json.load(open(path))
        cam = scene["camera"]
        z, (lo, hi) = scene_depths(scene, width, height)
        near, far = cam.get("near", 0.1), cam.get("far", 100.0)
        z = np.where(z < far, z, np.inf)
        tany = math.tan(math.radians(cam.get("fov", 60.0)) / 2.0)
        tanx = tany * width / height
        xs = ((np.arange(width) + 0.5) / width * 2.0 - 1.0) * tanx
        ys = (1.0 - (np.arange(height) + 0.5) / height * 2.0) * tany
        Rv, tv = view_matrix(cam)
        size = np.maximum(hi - lo, 1e-3)
        for n in counts:
            r0 = (8.0 * size.prod() / (4.18879 * n)) ** (1 / 3)
            world = lo + size * rng.random((n, 3))
            L = world @ Rv.T + tv  # eye space (camera looks down -z)
            rad = r0 * (0.6 + 0.8 * rng.random(n))
            dist = -L[:, 2]
            sums = np.zeros(4)
            for ty in range((height + TILE - 1) // TILE):
                for tx in range((width + TILE - 1) // TILE):
                    y0, x0 = ty * TILE, tx * TILE
                    zt = z[y0:y0 + TILE, x0:x0 + TILE]
                    if not np.isfinite(zt).any():
                        continue
                    # The tile's frustum in eye space: x / -z in [ax0, ax1], y / -z in [ay0, ay1].
                    ax0, ax1 = (x0 / width * 2 - 1) * tanx, (min(x0 + TILE, width) / width * 2 - 1) * tanx
                    ay1, ay0 = (1 - y0 / height * 2) * tany, (1 - min(y0 + TILE, height) / height * 2) * tany
                    d0, d1 = zt[np.isfinite(zt)].min(), zt[np.isfinite(zt)].max()
                    ok = (dist + rad >= d0) & (dist - rad <= d1)
                    for nx, nz, sgn in ((1, ax0, 1), (1, ax1, -1)):
                        ok &= sgn * (L[:, 0] + nz * L[:, 2]) / math.hypot(1, nz) >= -rad
                    for nz, sgn in ((ay0, 1), (ay1, -1)):
                        ok &= sgn * (L[:, 1] + nz * L[:, 2]) / math.hypot(1, nz) >= -rad
                    C = np.nonzero(ok)[0]
                    # Pixels' eye positions and slices.
                    Y, X = np.meshgrid(ys[y0:y0 + TILE], xs[x0:x0 + TILE], indexing="ij")
                    P = np.stack([X * zt, Y * zt, -zt], axis=-1).reshape(-1, 3)
                    zf = zt.reshape(-1)
                    surf = np.isfinite(zf)
                    sl = np.full(zf.shape, -1)
                    sl[surf] = np.clip(np.floor(np.log(zf[surf] / near) / math.log(far / near) * SLICES), 0, SLICES - 1)
                    reach = np.zeros((zf.size, C.size), bool)
                    if C.size:
                        dd = np.linalg.norm(P[surf][:, None, :] - L[C][None, :, :], axis=2)
                        reach[surf] = dd < rad[C][None, :]
                    # Each occupied slice's list: its tight depth range, then the box around it.
                    lists = {}
                    for j in np.unique(sl[surf]):
                        zs = zf[sl == j]
                        s0, s1 = zs.min(), zs.max()
                        m = (dist[C] + rad[C] >= s0) & (dist[C] - rad[C] <= s1)
                        cx = np.array([ax0 * s0, ax1 * s0, ax0 * s1, ax1 * s1])
                        cy = np.array([ay0 * s0, ay1 * s0, ay0 * s1, ay1 * s1])
                        blo = np.array([cx.min(), cy.min(), -s1])
                        bhi = np.array([cx.max(), cy.max(), -s0])
                        q = np.clip(L[C], blo, bhi)
                        m &= np.linalg.norm(L[C] - q, axis=1) <= rad[C]
                        lists[j] = int(m.sum())
                    single = len(lists) == 1
                    rows = min(TILE, height - y0)
                    for w in range(0, rows * TILE, 2 * TILE):  # a warp: two rows of the tile
                        lanes = np.arange(w, min(w + 2 * TILE, zf.size))
                        lanes = lanes[surf[lanes]]
                        if lanes.size == 0:
                            continue
                        sums[0] += C.size
                        sums[1] += int(reach[lanes].any(axis=0).sum())
                        sums[2] += C.size if single else max(lists[sl[i]] for i in lanes)
                        sums[3] += int(reach[lanes].sum(axis=1).max())
            t, ft, c, fi = sums / 1e6
            print(f"| {path} | {n} | {t:.2f} | {ft:.2f} | {c:.2f} | {fi:.2f} | {t / c:.2f} | {ft / fi:.2f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
