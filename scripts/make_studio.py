#!/usr/bin/env python3
"""Writes hdr/studio.exr: a neutral studio environment, 512x256 equirectangular, for a bare model.

What `lightpass render --model F` and `lightpass view F` light a model with when the file brings no
lights of its own (as the viewers of Filament, three.js and Khronos light a bare glTF by an
environment). Grey and white only, so it lends a material no colour:
  - a dome that brightens from the horizon to the zenith;
  - a key softbox above, in front and to the left of the framed model (the camera looks down -Z, so
    "in front" is +Z and "left" is -X);
  - a dimmer, wider fill softbox low on the right;
  - a small rim softbox high behind, for the edges of glossy surfaces;
  - a grey floor of albedo 0.25 lit by all of them (radiance = albedo / pi x its irradiance).
Softboxes are rectangles in angle with soft edges (a smoothstep over EDGE degrees), wide enough
(several degrees) that light extraction leaves them in the map: the whole light reaches the model
through the prefiltered cube and the SH, and shadows come from the ambient occlusion. Radiance units:
the key alone gives an irradiance of about 2 at normal incidence; a surface facing up receives about
3 in all, as from the key light (3) of a model's key-and-fill light rig without an environment.

Same conventions as scripts/make_sky.py (shaders/common/ibl.glsl: v = 0 is +Y, u = 0.5 looks down
-Z, u grows to the right seen from inside) and its OpenEXR writer (HALF RGB, ZIP). Pure Python.
Prints the irradiance it gives six axis-facing surfaces. Run from the repository root:
    python3 scripts/make_studio.py [--out hdr/studio.exr]
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_sky import equirect_direction, write_exr  # noqa: E402

W, H = 512, 256
EDGE = math.radians(4.0)  # width of a softbox's soft edge
FLOOR_ALBEDO = 0.25
HORIZON_BLEND = math.radians(1.5)  # the dome fades into the floor over +-this elevation


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


class Softbox:
    """A rectangle `width` x `height` degrees (full angles) facing the centre, centred on `toward`,
    its long side horizontal, of `radiance` inside, falling to 0 across a soft edge."""

    def __init__(self, toward, width, height, radiance):
        self.c = normalize(toward)
        self.t = normalize(cross((0.0, 1.0, 0.0), self.c))  # horizontal across the box
        self.b = cross(self.c, self.t)
        self.half = (math.radians(width) / 2, math.radians(height) / 2)
        self.radiance = radiance

    def __call__(self, d):
        z = dot(d, self.c)
        if z <= 0.0:
            return 0.0
        w = 1.0
        for axis, half in zip((self.t, self.b), self.half):
            a = abs(math.atan2(dot(d, axis), z))
            s = min(max((half + EDGE / 2 - a) / EDGE, 0.0), 1.0)
            w *= s * s * (3.0 - 2.0 * s)
        return self.radiance * w


SOFTBOXES = [
    Softbox((-0.55, 0.70, 0.45), 44.0, 28.0, 6.0),  # key
    Softbox((0.85, 0.20, 0.50), 52.0, 36.0, 1.1),   # fill
    Softbox((0.30, 0.75, -0.60), 24.0, 20.0, 3.0),  # rim
]


def dome(d):
    return 0.20 + 0.15 * max(d[1], 0.0)


def upper(d):
    """Radiance above the horizon: the dome and the softboxes."""
    return dome(d) + sum(box(d) for box in SOFTBOXES)


def irradiance(radiance, n, steps=192):
    """E on a surface of normal n: sum of L(d) cos dOmega over the sphere (midpoint rule in theta, phi)."""
    e = 0.0
    for i in range(steps):
        theta = (i + 0.5) / steps * math.pi
        st, ct = math.sin(theta), math.cos(theta)
        d_omega = (math.pi / steps) * (2 * math.pi / (2 * steps)) * st
        for j in range(2 * steps):
            phi = (j + 0.5) / (2 * steps) * 2 * math.pi
            d = (st * math.cos(phi), ct, st * math.sin(phi))
            c = dot(d, n)
            if c > 0.0:
                e += radiance(d) * c * d_omega
    return e


def make_studio():
    floor = FLOOR_ALBEDO / math.pi * irradiance(lambda d: upper(d) if d[1] > 0.0 else 0.0, (0.0, 1.0, 0.0))

    def radiance(d):
        elevation = math.asin(max(min(d[1], 1.0), -1.0))
        s = min(max((elevation + HORIZON_BLEND) / (2 * HORIZON_BLEND), 0.0), 1.0)
        s = s * s * (3.0 - 2.0 * s)
        return s * upper(d) + (1.0 - s) * floor

    pixels = []
    for y in range(H):
        row = []
        for x in range(W):
            v = radiance(equirect_direction((x + 0.5) / W, (y + 0.5) / H))
            row.append([v, v, v])
        pixels.append(row)
    return pixels, radiance, floor


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="hdr/studio.exr")
    a = ap.parse_args()
    pixels, radiance, floor = make_studio()
    os.makedirs(os.path.dirname(a.out) or ".", exist_ok=True)
    write_exr(a.out, pixels)
    print("wrote %s (%dx%d, %d bytes); floor radiance %.3f" % (a.out, W, H, os.path.getsize(a.out), floor))
    for name, n in (("+Y", (0, 1, 0)), ("-Y", (0, -1, 0)), ("+X", (1, 0, 0)), ("-X", (-1, 0, 0)),
                    ("+Z", (0, 0, 1)), ("-Z", (0, 0, -1)), ("key", SOFTBOXES[0].c)):
        print("irradiance facing %-3s %.3f" % (name, irradiance(radiance, n, steps=96)))


if __name__ == "__main__":
    main()
