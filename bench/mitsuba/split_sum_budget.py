#!/usr/bin/env python3
"""Where the split sum loses a small lamp's energy on rough spheres (issue #16), on the CPU.

For each GGX sphere of ground_truth.py's grid under lamp50k.hdr (make_maps.py, a lamp of 50,000
behind the camera), per pixel of the same 160x90 view (whole sphere: within 0.9 of its radius, as
ground_truth.py; core: N.V >= 0.7), against the Mitsuba composite that ground_truth.py left in --work:

  exact            the integral of lightpass's BRDF (GGX D, Smith of --specular-masking, F = 1) over the
                   map's texels (the sky box-averaged 4x4, the lamp's texels kept)
  split R          the exact split sum: prefiltered integral sum L D(h) (R.l)+ dOmega / sum D (R.l)+
                   dOmega with N = V = R (Karis' N.L weighting), times the exact DFG (A + B), along R
  split R' no N.L  the same along lightpass's dominant direction R' = normalize(mix(R, N, alpha^2)),
                   without the N.L weighting in the prefilter
  split R'         with it: what lightpass's chain converges to with a continuum of levels
  lightpass levels split R' read as lightpass reads it: the trilinear blend of its two prefiltered
                   levels around lod = 5 r (2 - r) (roughness of level m: 1 - sqrt(1 - m / 5))
  Frostbite R''    the split sum along Lagarde & de Rousiers' dominant direction (mix(N, R,
                   (1 - alpha)(sqrt(1 - alpha) + alpha))), with lightpass's levels

Cells: relative error of the sphere's mean against Mitsuba, whole sphere / core. Run:

    $MITSUBA_VENV/bin/python bench/mitsuba/split_sum_budget.py [--work /tmp/lightpass-mitsuba] [--out FILE]
"""
import argparse
import datetime
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ground_truth as gt  # noqa: E402  (CAMERA, RADIUS, ROTATION_DEGREES, spheres, read_rgb, mi)
from make_maps import lamp_map  # noqa: E402

WIDTH, HEIGHT, LEVELS = 160, 90, 6


def rotate_y(d, a):
    c, s = math.cos(a), math.sin(a)
    return np.stack([c * d[..., 0] + s * d[..., 2], d[..., 1], -s * d[..., 0] + c * d[..., 2]], -1)


def map_texels():
    """World directions, solid angles and radiance (blue channel) of lamp50k's texels: the sky
    box-averaged 4x4 (it is smooth), the lamp's texels at full resolution."""
    env = lamp_map().astype(np.float64)[..., 2]
    h, w = env.shape
    theta = ((np.arange(h) + 0.5) / h * math.pi)[:, None] * np.ones((1, w))
    phi = ((np.arange(w) + 0.5) / w - 0.5)[None, :] * 2 * math.pi * np.ones((h, 1))
    d = np.stack([np.sin(theta) * np.sin(phi), np.cos(theta), -np.sin(theta) * np.cos(phi)], -1)
    omega = np.sin(theta) * (math.pi / h) * (2 * math.pi / w)
    lamp = env > 1000.0
    sky = np.where(lamp, 0.0, env)
    f = 4
    om = omega.reshape(h // f, f, w // f, f).sum((1, 3))
    rad = (sky * omega).reshape(h // f, f, w // f, f).sum((1, 3)) / om
    dd = (d * omega[..., None]).reshape(h // f, f, w // f, f, 3).sum((1, 3))
    dd /= np.linalg.norm(dd, axis=-1, keepdims=True)
    dirs = np.concatenate([dd.reshape(-1, 3), d[lamp]])
    # lightpass: world = rotateY(map, rotation)
    return rotate_y(dirs, math.radians(gt.ROTATION_DEGREES)), np.concatenate([om.reshape(-1), omega[lamp]]), \
        np.concatenate([rad.reshape(-1), env[lamp]])


def sphere_pixels(centre):
    pos = np.array(gt.CAMERA["position"], float)
    fwd = np.array(gt.CAMERA["target"], float) - pos
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, gt.CAMERA["up"])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    t = math.tan(math.radians(gt.CAMERA["fov"]) / 2)
    xs = ((np.arange(WIDTH) + 0.5) / WIDTH * 2 - 1) * t * WIDTH / HEIGHT
    ys = (1 - (np.arange(HEIGHT) + 0.5) / HEIGHT * 2) * t
    d = fwd + xs[None, :, None] * right + ys[:, None, None] * up
    d /= np.linalg.norm(d, axis=2, keepdims=True)
    oc = pos - centre
    b = d @ oc
    inside = b * b - (oc @ oc - (0.9 * gt.RADIUS) ** 2) > 0
    hit = pos + (-b - np.sqrt(np.maximum(b * b - (oc @ oc - gt.RADIUS ** 2), 0.0)))[..., None] * d
    return inside, ((hit - centre) / gt.RADIUS)[inside], -d[inside]


def ggx_d(c, a):
    dd = c * c * (a * a - 1) + 1
    return a * a / (math.pi * dd * dd)


MASKING = "height-correlated"  # lightpass's Smith model (--specular-masking): separable or height-correlated


def visibility(nv, nl, a):
    """G2 / (4 N.L N.V) of MASKING; lv = N.V (1 + 2 Lambda(V)), ll likewise."""
    a2 = a * a
    lv, ll = np.sqrt(nv * nv * (1 - a2) + a2), np.sqrt(nl * nl * (1 - a2) + a2)
    return 0.5 / (nl * lv + nv * ll) if MASKING == "height-correlated" else 1.0 / ((nv + lv) * (nl + ll))


def exact(N, V, a, dirs, omega, rad):
    out = np.zeros(len(N))
    for i in range(len(N)):
        nl = dirs @ N[i]
        m = nl > 0
        h = dirs[m] + V[i]
        h /= np.linalg.norm(h, axis=1, keepdims=True)
        nv = max(N[i] @ V[i], 1e-4)
        out[i] = np.sum(rad[m] * ggx_d(h @ N[i], a) * visibility(nv, nl[m], a) * nl[m] * omega[m])
    return out


def prefiltered(R, a, dirs, omega, rad, nl_weight=True):
    out = np.zeros(len(R))
    for i in range(len(R)):
        rl = dirs @ R[i]
        m = rl > 0
        h = dirs[m] + R[i]
        h /= np.linalg.norm(h, axis=1, keepdims=True)
        w = ggx_d(h @ R[i], a) * omega[m] * (rl[m] if nl_weight else 1.0)
        out[i] = np.sum(rad[m] * w) / np.sum(w)
    return out


def lerp_towards_n(R, N, k):
    d = R + (N - R) * k
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--work", default="/tmp/lightpass-mitsuba", help="where ground_truth.py left the Mitsuba composite")
    ap.add_argument("--spp", type=int, default=128)
    ap.add_argument("--out", default=str(gt.REPO / "bench/results/mitsuba" / f"{datetime.date.today().isoformat()}_ibl-against-mitsuba" / "split_sum_budget.md"))
    ap.add_argument("--specular-masking", default="height-correlated", choices=["height-correlated", "separable"])
    args = ap.parse_args()
    globals()["MASKING"] = args.specular_masking
    ref_path = Path(args.work) / f"lamp50k_mitsuba_{WIDTH}x{HEIGHT}_{args.spp}spp_scalar_rgb.exr"
    if not ref_path.is_file():
        sys.exit(f"split_sum_budget.py: {ref_path}: no Mitsuba composite (run bench/mitsuba/run.sh --maps "
                 f"bench/mitsuba/maps/lamp50k.hdr --size {WIDTH}x{HEIGHT} --spp {args.spp} --work {args.work})")
    gt.mi.set_variant("scalar_rgb")
    ref = gt.read_rgb(ref_path)[..., 2]
    dirs, omega, rad = map_texels()
    level_alpha = [(1 - math.sqrt(1 - m / (LEVELS - 1))) ** 2 for m in range(LEVELS)]
    dfg_cache = {}

    def dfg(nv, a):
        key = (round(float(nv), 6), a)
        if key not in dfg_cache:
            dfg_cache[key] = gt.ggx_albedo(nv, a, separable=MASKING == "separable", n=256)
        return dfg_cache[key]

    cols = ["exact", "split R", "split R' no N.L", "split R'", "lightpass levels", "Frostbite R''"]
    lines = ["# Split-sum budget: rough GGX spheres under lamp50k (CPU, against Mitsuba 128 spp)", "",
             "Generated by `bench/mitsuba/split_sum_budget.py` (its docstring defines the columns). Relative error "
             "of the sphere's mean radiance against Mitsuba, whole sphere / N·V ≥ 0.7.", "",
             "| sphere | " + " | ".join(cols) + " |", "| --- |" + " ---: |" * len(cols)]
    for name, centre, kind, a, _ in gt.spheres():
        if kind != "ggx" or a < 0.15:
            continue  # near-mirror lobes are narrower than the sky's averaged texels
        mask, N, V = sphere_pixels(np.array(centre, float))
        nv = np.clip(np.sum(N * V, 1), 0.0, 1.0)
        core = nv >= 0.7
        R = 2 * nv[:, None] * N - V
        ab = np.array([dfg(c, a) for c in nv])
        r = math.sqrt(a)
        lod = (LEVELS - 1) * r * (2 - r)
        lo = min(int(lod), LEVELS - 2)
        t = lod - lo
        Rd = lerp_towards_n(R, N, a * a)
        Rf = lerp_towards_n(R, N, 1 - (1 - a) * (math.sqrt(1 - a) + a))

        def levels(direction):
            return ((1 - t) * prefiltered(direction, level_alpha[lo], dirs, omega, rad)
                    + t * prefiltered(direction, level_alpha[lo + 1], dirs, omega, rad)) * ab

        values = [exact(N, V, a, dirs, omega, rad), prefiltered(R, a, dirs, omega, rad) * ab,
                  prefiltered(Rd, a, dirs, omega, rad, nl_weight=False) * ab, prefiltered(Rd, a, dirs, omega, rad) * ab,
                  levels(Rd), levels(Rf)]
        m = ref[mask]
        cells = [f"{v.mean() / m.mean() - 1:+.3f} / {v[core].mean() / m[core].mean() - 1:+.3f}" for v in values]
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
        print(lines[-1], flush=True)
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text("\n".join(lines) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
