#!/usr/bin/env python3
"""How much of a scene's screen is tiles that span near and far, and what the clustered method's
tightened froxels could save there, from the scene file alone (CPU ray casting; scenes made of the
unit cube, plane and sphere primitives with translate and scale, as scenes/depth-discontinuity.json
and scenes/fence.json are). For each 16-pixel tile: its pixels' eye depths, the 24 default depth
slices they occupy (the froxel grid's exponential slices between the camera's near and far planes),
and, per pixel, the volume a light's centre must lie in for the pixel to be shaded with it: the
tiled method's tile frustum between the nearest and farthest pixel grown by the lights' radius R,
against the clustered method's, the pixel's slice's tightened range grown by R (lightpass's
--light-count lights fill the scene's bounding box uniformly with a radius set by their count, so
these volumes are proportional to the lights each pixel is shaded with: their ratio is the most the
shading can gain, the culling and fixed costs aside). Usage:
  bench/tile_depth_spans.py [--size 1920x1080] [--lights 1024] scenes/fence.json scenes/depth-discontinuity.json
Prints a Markdown table."""
import argparse
import json
import math

import numpy as np

SLICES = 24  # LocalLightSettings::clusterSlices' default
TILE = 16


def camera_basis(cam):
    """The camera's position and unit right, up and forward vectors (y up, as the renderer's look-at)."""
    pos = np.array(cam["position"], float)
    fwd = np.array(cam["target"], float) - pos
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    return pos, right, up, fwd


def camera_rays(cam, width, height):
    pos, right, up, fwd = camera_basis(cam)
    t = math.tan(math.radians(cam.get("fov", 60.0)) / 2.0)
    x = ((np.arange(width) + 0.5) / width * 2.0 - 1.0) * t * width / height
    y = (1.0 - (np.arange(height) + 0.5) / height * 2.0) * t
    X, Y = np.meshgrid(x, y)
    d = fwd[None, None, :] + X[..., None] * right + Y[..., None] * up  # eye z = -1 per unit of d
    return pos, d, fwd


def scene_depths(scene, width, height):
    """Eye depth (distance along the view axis) of each pixel's nearest surface; inf for none."""
    pos, d, fwd = camera_rays(scene["camera"], width, height)
    best = np.full(d.shape[:2], np.inf)
    lo_all, hi_all = np.full(3, np.inf), np.full(3, -np.inf)
    for m in scene["models"]:
        c = np.array(m.get("translate", [0, 0, 0]), float)
        s = m.get("scale", 1.0)
        s = np.array(s if isinstance(s, list) else [s] * 3, float)
        prim = m["primitive"]
        if prim == "sphere":
            r = 0.5 * s  # an ellipsoid: the unit-diameter sphere scaled
            o = (pos - c) / r
            dd = d / r
            a = np.einsum("ijk,ijk->ij", dd, dd)
            b = 2.0 * np.einsum("ijk,k->ij", dd, o)
            cc = o @ o - 1.0
            disc = b * b - 4 * a * cc
            ok = disc >= 0
            t = np.where(ok, (-b - np.sqrt(np.maximum(disc, 0))) / (2 * a), np.inf)
            t = np.where(t > 0, t, np.inf)
            lo, hi = c - r, c + r
        else:  # cube: unit cube; plane: unit square in xz (a box of no height)
            half = 0.5 * s * (np.array([1.0, 0.0, 1.0]) if prim == "plane" else 1.0)
            lo, hi = c - half, c + half
            with np.errstate(divide="ignore", invalid="ignore"):
                t0 = (lo - pos) / d
                t1 = (hi - pos) / d
            tmin = np.nanmax(np.minimum(t0, t1), axis=2)
            tmax = np.nanmin(np.maximum(t0, t1), axis=2)
            t = np.where((tmax >= tmin) & (tmax > 0), np.maximum(tmin, 0), np.inf)
        best = np.minimum(best, t)  # |d . fwd| = 1, so t is the eye depth
        lo_all, hi_all = np.minimum(lo_all, lo), np.maximum(hi_all, hi)
    return best, (lo_all, hi_all)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--lights", type=int, default=1024)
    ap.add_argument("scenes", nargs="+")
    a = ap.parse_args()
    width, height = map(int, a.size.split("x"))
    print(f"Tiles of {TILE} px at {width}x{height}, {SLICES} slices, lights' radius for {a.lights} lights "
          "(lightpass's --light-count: about 8 overlap a point of the scene's box)\n")
    print("| scene | tiles with a surface | > 1 occupied slice | far / near >= 4 | far / near >= 10 | "
          "lights shaded per pixel, tiled / clustered: all tiles | tiles with far / near >= 4 |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for path in a.scenes:
        scene = json.load(open(path))
        z, (lo, hi) = scene_depths(scene, width, height)
        near, far = scene["camera"].get("near", 0.1), scene["camera"].get("far", 100.0)
        z = np.where(z < far, z, np.inf)
        size = np.maximum(hi - lo, 1e-3)
        radius = (8.0 * size.prod() / (4.18879 * a.lights)) ** (1 / 3)  # generateDemoLights' mean range
        ty, tx = (height + TILE - 1) // TILE, (width + TILE - 1) // TILE
        pad = np.full((ty * TILE, tx * TILE), np.inf)
        pad[:height, :width] = z
        tiles = pad.reshape(ty, TILE, tx, TILE).transpose(0, 2, 1, 3).reshape(ty * tx, TILE * TILE)
        n_surface = n_multi = n4 = n10 = 0
        tiled_all = clustered_all = tiled_span = clustered_span = 0.0
        for t in tiles:
            t = t[np.isfinite(t)]
            if t.size == 0:
                continue
            n_surface += 1
            sl = np.clip(np.floor(np.log(t / near) / math.log(far / near) * SLICES), 0, SLICES - 1).astype(int)
            occ = np.unique(sl)
            d0, d1 = t.min(), t.max()
            # Volume of the tile's pyramid between depths a and b grows as b^3 - a^3.
            vol = lambda x, y: max(y + radius, 0) ** 3 - max(x - radius, 0) ** 3
            vt = vol(d0, d1)
            # Each pixel is shaded with the lights of its slice's tightened range grown by the radius
            # (clustered) or of the tile's whole range (tiled): per pixel, summed over the tile.
            vc = sum(np.count_nonzero(sl == j) * vol(t[sl == j].min(), t[sl == j].max()) for j in occ)
            vt *= t.size
            tiled_all += vt
            clustered_all += vc
            n_multi += len(occ) > 1
            if d1 >= 4 * d0:
                n4 += 1
                tiled_span += vt
                clustered_span += vc
            n10 += d1 >= 10 * d0
        pct = lambda n: f"{n} ({100.0 * n / n_surface:.0f}%)"
        span = f"{tiled_span / clustered_span:.2f}" if clustered_span > 0 else "-"
        print(f"| {path} | {n_surface} | {pct(n_multi)} | {pct(n4)} | {pct(n10)} | "
              f"{tiled_all / clustered_all:.2f} | {span} |")


if __name__ == "__main__":
    main()
