#!/usr/bin/env python3
"""Writes hdr/sky.exr and hdr/sky.hdr: a clear sky with a sun, 1024x512 equirectangular.

Sky: Preetham, Shirley & Smits 1999 ("A practical analytic model for daylight"), turbidity T,
luminance and chromaticity from the Perez distribution, xyY -> XYZ -> linear sRGB (Rec. 709).
Sun: a disk of the real angular radius (0.2665 deg) whose texels carry the covered fraction of its
radiance (16x16 sub-samples), so the sun's irradiance is exact however few texels it covers.
Units: radiance such that the sun's irradiance at normal incidence is --sun-irradiance (default 4,
the Cornell scene's directional light); the sky keeps Preetham's absolute ratio to the sun
(sun luminance 1.6e9 cd/m^2, sky in kcd/m^2). Below the horizon: a grey Lambertian ground of
albedo 0.3 lit by the sun and the sky.

Pure Python (struct, zlib): the .hdr is Radiance RGBE with run-length-encoded scanlines, the .exr
OpenEXR 2 scanline, HALF RGB, ZIP compression (16 lines per block). Run from the repository root:
    python3 scripts/make_sky.py [--sun-dir X Y Z] [--turbidity T] [--sun-irradiance E]
"""
import argparse
import math
import os
import struct
import zlib

W, H = 1024, 512
SUN_RADIUS = math.radians(0.2665)
SUN_SOLID_ANGLE = 2.0 * math.pi * (1.0 - math.cos(SUN_RADIUS))
SUN_LUMINANCE_KCD = 1.6e6  # 1.6e9 cd/m^2
SUN_COLOR = (1.0, 0.95, 0.85)


def equirect_direction(u, v):
    """The convention of shaders/common/ibl.glsl: v = 0 is +Y, u = 0.5 looks down -Z."""
    phi, theta = (u - 0.5) * 2.0 * math.pi, v * math.pi
    return (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))


def perez(theta, gamma, c):
    a, b, cc, d, e = c
    return (1.0 + a * math.exp(b / max(math.cos(theta), 0.01))) * (1.0 + cc * math.exp(d * gamma) + e * math.cos(gamma) ** 2)


def preetham(turbidity, theta_s):
    t = turbidity
    cy = (0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771, -0.0670 * t + 0.3703)
    cx = (-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125, -0.0641 * t - 0.8989, -0.0033 * t + 0.0452)
    cyy = (-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102, -0.0441 * t - 1.6537, -0.0109 * t + 0.0529)
    chi = (4.0 / 9.0 - t / 120.0) * (math.pi - 2.0 * theta_s)
    yz = (4.0453 * t - 4.9710) * math.tan(chi) - 0.2155 * t + 2.4192  # kcd/m^2
    th = (theta_s ** 3, theta_s ** 2, theta_s, 1.0)
    tt = (t * t, t, 1.0)
    mx = ((0.00166, -0.00375, 0.00209, 0.0), (-0.02903, 0.06377, -0.03202, 0.00394), (0.11693, -0.21196, 0.06052, 0.25886))
    my = ((0.00275, -0.00610, 0.00317, 0.0), (-0.04214, 0.08970, -0.04153, 0.00516), (0.15346, -0.26756, 0.06670, 0.26688))
    xz = sum(tt[i] * sum(mx[i][j] * th[j] for j in range(4)) for i in range(3))
    yzc = sum(tt[i] * sum(my[i][j] * th[j] for j in range(4)) for i in range(3))
    return (yz, xz, yzc), (cy, cx, cyy)


def xyy_to_rgb(x, y, lum):
    big_x, big_z = x / y * lum, (1.0 - x - y) / y * lum
    return (3.2406 * big_x - 1.5372 * lum - 0.4986 * big_z,
            -0.9689 * big_x + 1.8758 * lum + 0.0415 * big_z,
            0.0557 * big_x - 0.2040 * lum + 1.0570 * big_z)


def make_sky(sun_dir, turbidity, sun_irradiance):
    n = math.sqrt(sum(c * c for c in sun_dir))
    sun = tuple(c / n for c in sun_dir)
    if sun[1] <= 0.0:
        raise SystemExit("make_sky.py: the sun must be above the horizon (sun-dir y > 0)")
    theta_s = math.acos(sun[1])
    zenith, coeffs = preetham(turbidity, theta_s)
    norms = [perez(0.0, theta_s, c) for c in coeffs]
    scale = sun_irradiance / (SUN_LUMINANCE_KCD * SUN_SOLID_ANGLE)  # radiance units per kcd/m^2
    sun_radiance = [sun_irradiance / SUN_SOLID_ANGLE * c for c in SUN_COLOR]

    def sky(d):
        theta = math.acos(max(min(d[1], 1.0), 0.0))
        gamma = math.acos(max(min(sum(a * b for a, b in zip(d, sun)), 1.0), -1.0))
        lum, x, y = (zenith[i] * perez(theta, gamma, coeffs[i]) / norms[i] for i in range(3))
        return [max(c, 0.0) * scale for c in xyy_to_rgb(x, y, lum)]

    # The ground's radiance: albedo 0.3 / pi times the horizontal irradiance of sun and sky.
    e_sky = 0.0
    steps = 64
    for i in range(steps):
        for j in range(steps * 2):
            theta = (i + 0.5) / steps * math.pi / 2
            phi = (j + 0.5) / (steps * 2) * 2 * math.pi
            d = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            rgb = sky(d)
            e_sky += (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]) * math.cos(theta) * math.sin(theta) * \
                (math.pi / 2 / steps) * (2 * math.pi / (steps * 2))
    e_ground = e_sky + sun_irradiance * sun[1]
    ground = [0.3 / math.pi * e_ground * c for c in (1.0, 0.95, 0.88)]

    pixels = []
    cos_near = math.cos(SUN_RADIUS + 3.0 * math.pi / H)
    cos_r = math.cos(SUN_RADIUS)
    sub = 16
    for y in range(H):
        row = []
        for x in range(W):
            d = equirect_direction((x + 0.5) / W, (y + 0.5) / H)
            c = sky(d) if d[1] >= 0.0 else list(ground)
            if sum(a * b for a, b in zip(d, sun)) > cos_near:  # texel near the sun: its covered fraction
                covered = 0
                for j in range(sub):
                    for i in range(sub):
                        ds = equirect_direction((x + (i + 0.5) / sub) / W, (y + (j + 0.5) / sub) / H)
                        covered += sum(a * b for a, b in zip(ds, sun)) >= cos_r
                f = covered / (sub * sub)
                c = [ci * (1.0 - f) + si * f for ci, si in zip(c, sun_radiance)]
            row.append(c)
        pixels.append(row)
    return pixels


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return (0, 0, 0, 0)
    mant, e = math.frexp(m)
    f = mant * 256.0 / m
    return (min(int(c[0] * f), 255), min(int(c[1] * f), 255), min(int(c[2] * f), 255), e + 128)


def rle_channel(data):
    """Radiance new-style run-length encoding of one component of a scanline."""
    out = bytearray()
    i, n = 0, len(data)
    while i < n:
        run = 1
        while i + run < n and run < 127 and data[i + run] == data[i]:
            run += 1
        if run >= 4:
            out += bytes((128 + run, data[i]))
            i += run
            continue
        start = i
        while i < n and i - start < 128:
            if i + 3 < n and data[i] == data[i + 1] == data[i + 2] == data[i + 3]:
                break
            i += 1
        out += bytes((i - start,)) + bytes(data[start:i])
    return out


def write_hdr(path, pixels, comment="lightpass scripts/make_sky.py (Preetham 1999)"):
    """`pixels`: rows top first, each a list of [r, g, b]; the size is theirs."""
    h, w = len(pixels), len(pixels[0])
    out = bytearray(b"#?RADIANCE\n# " + comment.encode() + b"\nFORMAT=32-bit_rle_rgbe\n\n")
    out += ("-Y %d +X %d\n" % (h, w)).encode()
    for row in pixels:
        e = [rgbe(c) for c in row]
        out += bytes((2, 2, w >> 8, w & 255))
        for k in range(4):
            out += rle_channel([p[k] for p in e])
    write_atomically(path, bytes(out))


def write_exr(path, pixels):
    """`pixels`: rows top first, each a list of [r, g, b]; the size is theirs."""
    h, w = len(pixels), len(pixels[0])

    def attr(name, typ, data):
        return name.encode() + b"\0" + typ.encode() + b"\0" + struct.pack("<i", len(data)) + data

    chlist = b"".join(ch.encode() + b"\0" + struct.pack("<iB3xii", 1, 0, 1, 1) for ch in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", chlist) +
              attr("compression", "compression", b"\x03") + attr("dataWindow", "box2i", box) +
              attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\x00") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    lines = 16
    chunks = []
    for y0 in range(0, h, lines):
        raw = bytearray()
        for y in range(y0, min(y0 + lines, h)):
            for k in (2, 1, 0):  # B, G, R: channels in alphabetical order
                raw += b"".join(struct.pack("<e", min(p[k], 65504.0)) for p in pixels[y])
        # OpenEXR ZIP: interleave even/odd bytes, delta predictor, zlib.
        t = raw[0::2] + raw[1::2]
        pred = bytearray(len(t))
        pred[0] = t[0]
        for i in range(1, len(t)):
            pred[i] = (t[i] - t[i - 1] + 128 + 256) & 255
        data = zlib.compress(bytes(pred), 9)
        if len(data) >= len(raw):
            data = bytes(raw)
        chunks.append(struct.pack("<ii", y0, len(data)) + data)
    offset = len(header) + 8 * len(chunks)
    table = bytearray()
    for c in chunks:
        table += struct.pack("<Q", offset)
        offset += len(c)
    write_atomically(path, header + bytes(table) + b"".join(chunks))


def write_atomically(path, data):
    tmp = "%s.tmp-%d" % (path, os.getpid())
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    # Default: where the Cornell scene's directional light comes from (-direction).
    ap.add_argument("--sun-dir", type=float, nargs=3, default=[0.25, 0.45, -1.0])
    ap.add_argument("--turbidity", type=float, default=3.0)
    ap.add_argument("--sun-irradiance", type=float, default=4.0)
    ap.add_argument("--out", default="hdr/sky")
    a = ap.parse_args()
    if not 1.7 <= a.turbidity <= 10.0:
        raise SystemExit("make_sky.py: --turbidity %g: Preetham's fit holds for 1.7..10" % a.turbidity)
    pixels = make_sky(a.sun_dir, a.turbidity, a.sun_irradiance)
    os.makedirs(os.path.dirname(a.out) or ".", exist_ok=True)
    write_hdr(a.out + ".hdr", pixels)
    write_exr(a.out + ".exr", pixels)
    print("wrote %s.hdr and %s.exr (%dx%d)" % (a.out, a.out, W, H))


if __name__ == "__main__":
    main()
