#!/usr/bin/python3
"""Synthetic environment maps for the Mitsuba comparison (bench/mitsuba/README.md), written as
flat (uncompressed) Radiance RGBE .hdr, 2:1 equirectangular, lightpass's convention (row 0 = +Y):

- lamp50k.hdr: a dim sky gradient (1.0 at the zenith to 0.3 at the horizon, 0.15 ground) plus a lamp
  disc of 2 texels radius whose radiance is 50,000, 28 degrees up behind the camera of ground_truth.py
  (it lights the spheres from the front): a small, very bright light that a prefilter can lose (issue #16).
- lamps_low.hdr: the same sky with three lamps (radiance 20,000, 2 texels radius) 6, 12 and 20 degrees
  above the horizon, ahead of a camera looking down -Z: what a smooth plane seen at grazing angles
  reflects (bench/mitsuba/grazing_plane.py).
- furnace.hdr: radiance 1 everywhere (white furnace: a sphere reflects exactly its albedo).
- window.hdr: a dim room (0.2 above the horizon, 0.1 below) with one large hard-edged window of radiance
  20, 60 degrees wide and 35 degrees tall, centred 25 degrees up behind a camera looking down -Z (it lights
  the spheres from the front): too wide for light extraction, so the prefiltered chain carries it all and
  a rough lobe sees its edge (issue #38).

    python3 bench/mitsuba/make_maps.py [OUTDIR]   (default bench/mitsuba/maps)
"""
import math
import sys
from pathlib import Path

import numpy as np


def write_rgbe(path, rgb):
    h, w, _ = rgb.shape
    m = np.max(rgb, axis=2)
    rgbe = np.zeros((h, w, 4), np.uint8)
    nz = m > 1e-32
    mant, exp = np.frexp(m[nz])
    scale = mant * 256.0 / m[nz]
    rgbe[nz, 0:3] = np.clip(rgb[nz] * scale[:, None], 0, 255).astype(np.uint8)
    rgbe[nz, 3] = (exp + 128).astype(np.uint8)
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {h} +X {w}\n".encode())
        f.write(rgbe.tobytes())


def lamp_map(width=1024, lamp=50000.0, radius_texels=2.0, lamp_dirs=((0.10, 0.45, 0.85),)):
    h = width // 2
    v = (np.arange(h) + 0.5) / h
    u = (np.arange(width) + 0.5) / width
    theta = v[:, None] * math.pi
    phi = (u[None, :] - 0.5) * 2 * math.pi
    d = np.stack([np.sin(theta) * np.sin(phi), np.cos(theta) * np.ones_like(phi), -np.sin(theta) * np.cos(phi)], -1)
    y = d[..., 1]
    sky = np.where(y > 0, 0.3 + 0.7 * y, 0.15)
    rgb = np.stack([sky * 0.8, sky * 0.9, sky], -1)
    texel = math.pi / h
    for lamp_dir in lamp_dirs:
        l = np.array(lamp_dir) / np.linalg.norm(lamp_dir)
        angle = np.arccos(np.clip(d @ l, -1, 1))
        rgb[angle < radius_texels * texel] = lamp
    return rgb.astype(np.float32)


def window_map(width=1024, radiance=20.0, width_degrees=60.0, height_degrees=35.0, centre_elevation=25.0,
               centre_azimuth=180.0, room=(0.2, 0.1)):
    """A hard-edged rectangular window in longitude and latitude (texels wholly in or out), over a
    uniform room: `room` above and below the horizon. Azimuth 180 is +Z (behind a camera looking down -Z)."""
    h = width // 2
    v = (np.arange(h) + 0.5) / h
    u = (np.arange(width) + 0.5) / width
    elevation = 90.0 - np.degrees(v * math.pi)
    azimuth = np.degrees((u - 0.5) * 2 * math.pi)  # 0: -Z, +90: +X
    off = (azimuth[None, :] - centre_azimuth + 180.0) % 360.0 - 180.0
    inside = (np.abs(off) <= width_degrees / 2) & (np.abs(elevation[:, None] - centre_elevation) <= height_degrees / 2)
    sky = np.where(elevation[:, None] > 0, room[0], room[1]) * np.ones((h, width))
    sky = np.where(inside, radiance, sky)
    return np.repeat(sky[..., None], 3, axis=2).astype(np.float32)


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "maps"
    out.mkdir(parents=True, exist_ok=True)
    write_rgbe(out / "lamp50k.hdr", lamp_map())
    low = []
    for elevation, azimuth in ((6, -8), (12, 5), (20, -2)):
        e, a = math.radians(elevation), math.radians(azimuth)
        low.append((math.cos(e) * math.sin(a), math.sin(e), -math.cos(e) * math.cos(a)))
    write_rgbe(out / "lamps_low.hdr", lamp_map(lamp=20000.0, lamp_dirs=low))
    write_rgbe(out / "furnace.hdr", np.ones((64, 128, 3), np.float32))
    write_rgbe(out / "window.hdr", window_map())
    print(f"wrote {out}/lamp50k.hdr, {out}/lamps_low.hdr, {out}/furnace.hdr, {out}/window.hdr")


if __name__ == "__main__":
    main()
