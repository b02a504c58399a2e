#!/usr/bin/env python3
"""The sampled specular IBL (--ibl-specular sampled) emulated on the CPU, against Mitsuba (issue #16).

The split sum (the prefiltered chain read along one direction x the DFG LUT) loses the lobe's shape:
at grazing view the true GGX lobe is not the round N = V = R lobe (split_sum_budget.py). This script
evaluates, per pixel of ground_truth.py's 160x90 view (analytic sphere normals), the estimator of
shaders/common/ibl_sampled.glsl over lightpass's own textures: its environment cube (512^2, full
solid-angle-weighted mip chain) and prefiltered chain (256^2, 6 levels), read from the --ibl-cache
files of one lightpass render of the same scene; trilinear, seamless cube lookups.

  'sampled N' (source 'prefiltered', the shader's): N fixed samples (one Hammersley set for every
  pixel, no noise) of the GGX distribution of visible normals (Heitz 2018) for the pixel's V, drawn
  from alpha' = sqrt(alpha^2 - alpha_s^2) (alpha_s: the sub-lobe at the lobe's peak; at least
  alpha / 10); each L read from the prefiltered chain at the roughness whose lobe spans `span`
  times the sample's solid angle 1 / (N pdf(L)) (a lobe of alpha_s spans about 4 pi alpha_s^2),
  weighted by f cos / pdf = G2(V, L) / G1(V) and split by Schlick's Fc = (1 - V.H)^5:
      specular = F0 A sum(L w (1 - Fc)) / sum(w (1 - Fc)) + f90 B sum(L w Fc) / sum(w Fc)
  with A, B the exact DFG terms: a uniform environment returns F0 A + f90 B at any N.
  'cube S 0 N' (source 'cube'): classic filtered importance sampling instead, each L read from the
  environment cube at lod 0.5 log2(sample solid angle / texel solid angle) + S (box-filtered texels,
  no narrowing): against a lamp of a few texels its tent of texels shows the sample pattern.
  'split sum (measured)': lightpass's render (bench/results/mitsuba/2026-11-24_ibl-against-mitsuba/after_1024_spheres.csv);
  'split sum (emulated)': the same lookup here (checks this emulation against the renderer);
  'exact BRDF integral' (--exact): lightpass's BRDF integrated over the cube's 256^2 level.

Rows: GGX spheres (F0 = 1); cells: relative error of the sphere's mean against Mitsuba, whole
sphere (within 0.9 of its radius) / core (N.V >= 0.7). Run (after ground_truth.py left the Mitsuba
composites of lamp50k and royal_esplanade_1k, 160x90, 128 spp, in --work):

    $MITSUBA_VENV/bin/python bench/mitsuba/sampled_specular.py --work /tmp/lightpass-mitsuba [--exact] [--out FILE]
"""
import argparse
import datetime
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ground_truth as gt  # noqa: E402
from split_sum_budget import WIDTH, HEIGHT, sphere_pixels  # noqa: E402

CUBE = 512
MAPS = ["lamp50k", "royal_esplanade_1k"]


# ---------------------------------------------------------------------------------------------
# The environment cube as lightpass makes it (GL face order +X -X +Y -Y +Z -Z, t grows downwards)

def cube_direction(face, s, t):
    one = np.ones_like(s)
    d = [np.stack([one, -t, -s], -1), np.stack([-one, -t, s], -1), np.stack([s, one, t], -1),
         np.stack([s, -one, -t], -1), np.stack([s, -t, one], -1), np.stack([-s, -t, -one], -1)][face]
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def face_st(d):
    """Face index and (s, t) in [-1, 1] of directions d (..., 3): the inverse of cube_direction."""
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    ax, ay, az = np.abs(x), np.abs(y), np.abs(z)
    face = np.where((ax >= ay) & (ax >= az), np.where(x > 0, 0, 1),
                    np.where(ay >= az, np.where(y > 0, 2, 3), np.where(z > 0, 4, 5)))
    m = np.choose(face, [ax, ax, ay, ay, az, az])
    s = np.choose(face, [-z, z, x, x, x, -x]) / m
    t = np.choose(face, [-y, -y, z, -z, -y, -y]) / m
    return face, s, t


def texel_solid_angle(size):
    """Exact solid angle of every texel of a face of `size` (as cubeTexelSolidAngle)."""
    h = 2.0 / size
    e = np.arange(size + 1) * h - 1.0
    X, Y = np.meshgrid(e, e, indexing="xy")
    a = np.arctan2(X * Y, np.sqrt(X * X + Y * Y + 1.0))
    return a[:-1, :-1] - a[:-1, 1:] - a[1:, :-1] + a[1:, 1:]  # [j, i]


def read_lightpass_cache(path, cube_size, levels, sh):
    """The cubes of a lightpass --ibl-cache file: "lightpass-ibl 1\\n<key>\\n", 9 SH vec3 (float) for a bake,
    then each cube's levels (6 faces of rows, RGBA half). Returns the first cube's levels as (6, s, s, 3)."""
    data = Path(path).read_bytes()
    pos = data.index(b"\n", data.index(b"\n") + 1) + 1
    if sh:
        pos += 9 * 3 * 4
    out = []
    for l in range(levels):
        s = max(cube_size >> l, 1)
        n = 6 * s * s * 4
        a = np.frombuffer(data, np.float16, n, pos).astype(np.float64).reshape(6, s, s, 4)[..., :3]
        out.append(a)
        pos += n * 2
    return out


def lightpass_chains(map_name, lightpass, work):
    """lightpass's own environment cube (512^2, full chain) and prefiltered chain (256^2, 6 levels) of a
    map, from its --ibl-cache files (made by rendering bench/mitsuba/scenes/<map>.json once)."""
    import subprocess
    cache = Path(work) / f"ibl-cache-{map_name}"
    cubes, bakes = sorted(cache.glob("cube-*.lpibl")), sorted(cache.glob("bake-*.lpibl"))
    if not cubes or not bakes:
        cache.mkdir(parents=True, exist_ok=True)
        scene = gt.REPO / f"bench/mitsuba/scenes/{map_name}.json"
        cmd = [str(lightpass), "render", "--scene", str(scene), "--ibl", "--no-ao", "--brdf", "ggx", "--size", "16x16",
               "--frames", "1", "--out", str(cache / "render.png"), "--ibl-cache", str(cache)]
        subprocess.run(cmd, check=True, capture_output=True)
        cubes, bakes = sorted(cache.glob("cube-*.lpibl")), sorted(cache.glob("bake-*.lpibl"))
    return (read_lightpass_cache(cubes[0], CUBE, int(math.log2(CUBE)) + 1, False),
            read_lightpass_cache(bakes[0], 256, 6, True))


def sample_level(level, d):
    """Bilinear, seamless lookup of one mip (6, s, s, 3) along directions d (M, 3): a tap outside its
    face is the texel of the neighbouring face that holds that tap's direction."""
    size = level.shape[1]
    face, s, t = face_st(d)
    x, y = (s + 1) * 0.5 * size - 0.5, (t + 1) * 0.5 * size - 0.5
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = x - x0, y - y0
    out = np.zeros(d.shape[:-1] + (3,))
    for dx, dy, wt in ((0, 0, (1 - fx) * (1 - fy)), (1, 0, fx * (1 - fy)), (0, 1, (1 - fx) * fy), (1, 1, fx * fy)):
        i, j = x0 + dx, y0 + dy
        inside = (i >= 0) & (i < size) & (j >= 0) & (j < size)
        f2, i2, j2 = face.copy(), np.clip(i, 0, size - 1), np.clip(j, 0, size - 1)
        if size > 1 and not inside.all():
            o = ~inside
            st = (np.stack([i[o], j[o]], -1) + 0.5) / size * 2 - 1
            dd = np.zeros((o.sum(), 3))
            for f in range(6):
                k = face[o] == f
                if k.any():
                    dd[k] = cube_direction(f, st[k, 0], st[k, 1])
            fo, so, to = face_st(dd)
            f2[o] = fo
            i2[o] = np.clip(((so + 1) * 0.5 * size).astype(int), 0, size - 1)
            j2[o] = np.clip(((to + 1) * 0.5 * size).astype(int), 0, size - 1)
        out += wt[..., None] * level[f2, j2, i2]
    return out


def sample_cube(levels, d, lod):
    lod = np.clip(lod, 0.0, len(levels) - 1.0)
    lo = np.floor(lod).astype(int)
    hi = np.minimum(lo + 1, len(levels) - 1)
    t = (lod - lo)[..., None]
    out = np.zeros(d.shape[:-1] + (3,))
    for l in range(len(levels)):
        a, b = lo == l, hi == l
        if a.any():
            out[a] += (1 - t[a]) * sample_level(levels[l], d[a])
        if b.any():
            out[b] += t[b] * sample_level(levels[l], d[b])
    return out


# ---------------------------------------------------------------------------------------------
# The estimator (shaders/common/ibl_sampled.glsl)

def radical_inverse(i):
    i = np.asarray(i, np.uint64)
    out = np.zeros(i.shape)
    f = 0.5
    while np.any(i):
        out += f * (i & 1)
        i >>= 1
        f *= 0.5
    return out


def point_set(n, kind):
    i = np.arange(n)
    if kind == "hammersley":
        return np.stack([(i + 0.5) / n, radical_inverse(i)], -1)
    raise ValueError(kind)


def sample_vndf(Ve, alpha, u):
    """Heitz 2018: view (M, 3) in tangent space (z = normal), points u (n, 2) -> microfacet normals (M, n, 3)."""
    Vh = np.stack([alpha * Ve[:, 0], alpha * Ve[:, 1], Ve[:, 2]], -1)
    Vh /= np.linalg.norm(Vh, axis=-1, keepdims=True)
    lensq = Vh[:, 0] ** 2 + Vh[:, 1] ** 2
    inv = np.where(lensq > 0, 1 / np.sqrt(np.maximum(lensq, 1e-30)), 0.0)
    T1 = np.where((lensq > 0)[:, None], np.stack([-Vh[:, 1] * inv, Vh[:, 0] * inv, 0 * inv], -1), np.array([1.0, 0, 0]))
    T2 = np.cross(Vh, T1)
    r = np.sqrt(u[:, 0])[None, :]
    phi = 2 * math.pi * u[:, 1][None, :]
    t1, t2 = r * np.cos(phi), r * np.sin(phi)
    s = 0.5 * (1 + Vh[:, 2])[:, None]
    t2 = (1 - s) * np.sqrt(np.maximum(1 - t1 * t1, 0)) + s * t2
    nh = (t1[..., None] * T1[:, None, :] + t2[..., None] * T2[:, None, :]
          + np.sqrt(np.maximum(1 - t1 * t1 - t2 * t2, 0))[..., None] * Vh[:, None, :])
    ne = np.stack([alpha * nh[..., 0], alpha * nh[..., 1], np.maximum(nh[..., 2], 0)], -1)
    return ne / np.linalg.norm(ne, axis=-1, keepdims=True)


MASKING = "height-correlated"  # lightpass's Smith model (--specular-masking): separable or height-correlated


def smith_g2(lv, ll):
    """G2 from Smith's Lambdas of V and L under MASKING."""
    return 1 / ((1 + lv) * (1 + ll)) if MASKING == "separable" else 1 / (1 + lv + ll)


def smith_lambda(c, a):
    c = np.maximum(c, 1e-6)
    return 0.5 * (np.sqrt(1 + a * a * (1 - c * c) / (c * c)) - 1)


def ggx_d(c, a):
    dd = c * c * (a * a - 1) + 1
    return a * a / (math.pi * dd * dd)


def basis(n):
    sgn = np.where(n[:, 2] >= 0, 1.0, -1.0)
    a = -1 / (sgn + n[:, 2])
    b = n[:, 0] * n[:, 1] * a
    t = np.stack([1 + sgn * n[:, 0] ** 2 * a, sgn * b, -sgn * n[:, 0]], -1)
    bb = np.stack([b, sgn + n[:, 1] ** 2 * a, -n[:, 1]], -1)
    return t, bb


def sampled_specular(chains, N, V, alpha, ab, u, source, k, narrow=False, f0=1.0):
    """Radiance reflected by a GGX surface (F0 = f90 = f0) at each pixel: the estimator above.
    source 'cube': each sample reads the environment cube at lod 0.5 log2(its solid angle / the texel's) + k.
    source 'prefiltered': each sample reads the prefiltered chain at the roughness whose lobe spans k times
    the sample's solid angle (a GGX lobe of alpha_s spans about 4 pi alpha_s^2); `narrow`: the samples
    come from (and are weighted by) the lobe of alpha' = sqrt(alpha^2 - alpha_s^2), alpha_s the sub-lobe at
    the lobe's peak, so the sum of the sub-lobes is about as wide as alpha's lobe."""
    cube, prefiltered = chains
    T, B = basis(N)
    nv = np.clip(np.sum(N * V, -1), 1e-4, 1.0)
    Ve = np.stack([np.sum(V * T, -1), np.sum(V * B, -1), nv], -1)
    Ve /= np.linalg.norm(Ve, axis=-1, keepdims=True)
    n = u.shape[0]
    a_s_peak = min(math.sqrt(k / n), 1.0) * alpha  # the sub-lobe at the lobe's peak, where pdf = 1 / (4 pi alpha^2)
    a_samp = math.sqrt(max(alpha * alpha - a_s_peak * a_s_peak, 0.01 * alpha * alpha)) if narrow else alpha
    H = sample_vndf(Ve, a_samp, u)                                 # (M, n, 3) tangent space
    vh = np.sum(Ve[:, None, :] * H, -1)
    L = 2 * vh[..., None] * H - Ve[:, None, :]
    nl = L[..., 2]
    ok = (nl > 0) & (vh > 0)
    # f cos / pdf = G2(V, L) / G1(V) of the sampled lobe (a_samp): the sub-lobes widen it back to about alpha
    lv, ll = smith_lambda(nv, a_samp)[:, None], smith_lambda(np.maximum(nl, 1e-6), a_samp)
    w = np.where(ok, smith_g2(lv, ll) * (1 + lv), 0.0)
    fc = (1 - np.clip(vh, 0, 1)) ** 5
    # pdf(L) = G1(V) D(H) / (4 N.V)
    g1 = 1 / (1 + smith_lambda(nv, a_samp)[:, None])
    pdf = g1 * ggx_d(H[..., 2], a_samp) / (4 * nv[:, None])
    omega_s = 1.0 / (n * np.maximum(pdf, 1e-30))
    Lw = L[..., 0:1] * T[:, None, :] + L[..., 1:2] * B[:, None, :] + L[..., 2:3] * N[:, None, :]
    if source == "cube":
        texel = (2.0 / CUBE) ** 2 * np.max(np.abs(Lw), -1) ** 3  # the texel's solid angle at L
        lod = 0.5 * np.log2(omega_s / texel) + k
        rad = sample_cube(cube, Lw.reshape(-1, 3), lod.reshape(-1)).reshape(Lw.shape)
    else:
        a_s = np.minimum(np.sqrt(k * omega_s / (4 * math.pi)), alpha)
        r_s = np.sqrt(a_s)
        lod = (len(prefiltered) - 1) * r_s * (2 - r_s)
        rad = sample_cube(prefiltered, Lw.reshape(-1, 3), lod.reshape(-1)).reshape(Lw.shape)
    wa, wb = w * (1 - fc), w * fc
    la = np.sum(rad * wa[..., None], 1) / np.maximum(np.sum(wa, 1), 1e-30)[:, None]
    lb = np.where((np.sum(wb, 1) > 0)[:, None], np.sum(rad * wb[..., None], 1) / np.maximum(np.sum(wb, 1), 1e-30)[:, None], la)
    return f0 * ab[:, 0:1] * la + f0 * ab[:, 1:2] * lb


def dfg_ab(nv, alpha, n=128):
    """Exact split-sum A, B (F = F0 (1 - Fc) + f90 Fc), midpoint rule over the GGX half-vector."""
    u = (np.arange(n) + 0.5) / n
    x1, x2 = np.meshgrid(u, u, indexing="ij")
    a2 = alpha * alpha
    ch = np.sqrt((1 - x2) / (1 + (a2 - 1) * x2))
    sh = np.sqrt(np.maximum(1 - ch * ch, 0))
    hx = sh * np.cos(2 * math.pi * x1)
    out = []
    for c in nv:
        c = min(max(float(c), 1e-4), 1.0)
        vh = math.sqrt(1 - c * c) * hx + c * ch
        nl = 2 * vh * ch - c
        ok = (nl > 0) & (vh > 0)
        nl = np.where(ok, nl, 1.0)
        g2 = smith_g2(smith_lambda(c, alpha), smith_lambda(nl, alpha))
        w = np.where(ok, g2 * vh / (c * ch), 0.0)
        fc = (1 - np.clip(vh, 0, 1)) ** 5
        out.append([np.mean(w * (1 - fc)), np.mean(w * fc)])
    return np.array(out)


def measured_split_sum(map_name):
    """lightpass's split sum as measured (bench/results/mitsuba/2026-11-24_ibl-against-mitsuba/after_1024_spheres.csv)."""
    import csv
    path = gt.REPO / "bench/results/mitsuba/2026-11-24_ibl-against-mitsuba/after_1024_spheres.csv"
    out = {}
    if path.is_file():
        for row in csv.DictReader(path.open()):
            if row.get("map") == map_name:
                out[row["sphere"]] = (float(row["rel_mean_error"]), float(row["rel_mean_error_core"]))
    return out


def split_sum(prefiltered, N, V, alpha, ab):
    """lightpass's split sum: the prefiltered chain along mix(R, N, alpha^2) at lod 5 r (2 - r), x (A + B)."""
    nv = np.clip(np.sum(N * V, -1), 0.0, 1.0)
    R = 2 * nv[:, None] * N - V
    d = R + (N - R) * alpha * alpha
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    r = math.sqrt(alpha)
    lod = (len(prefiltered) - 1) * r * (2 - r)
    return sample_cube(prefiltered, d, np.full(len(d), lod)) * ab.sum(1)[:, None]


def exact_integral(cube, N, V, alpha, level=1):
    """The integral of lightpass's BRDF (F = 1) over the cube's texels at `level` (256^2: sharper than
    every lobe here), per pixel."""
    size = cube[level].shape[1]
    om = texel_solid_angle(size)
    ij = (np.arange(size) + 0.5) / size * 2 - 1
    s, t = np.meshgrid(ij, ij, indexing="xy")
    D = np.concatenate([cube_direction(f, s, t).reshape(-1, 3) for f in range(6)])
    O = np.concatenate([om.reshape(-1)] * 6)
    R = cube[level].reshape(-1, 3)
    nv = np.clip(np.sum(N * V, -1), 1e-4, 1.0)
    out = []
    for i in range(len(N)):
        nl = D @ N[i]
        m = nl > 0
        h = D[m] + V[i]
        h /= np.linalg.norm(h, axis=1, keepdims=True)
        f = ggx_d(h @ N[i], alpha) * smith_g2(smith_lambda(nv[i], alpha), smith_lambda(nl[m], alpha)) / (4 * nv[i])
        out.append((R[m] * (f * O[m])[:, None]).sum(0))
    return np.array(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--work", default="/tmp/lightpass-mitsuba", help="where ground_truth.py left the Mitsuba composites")
    ap.add_argument("--lightpass", default=str(gt.REPO / "build/app/lightpass"))
    ap.add_argument("--spp", type=int, default=128)
    ap.add_argument("--maps", nargs="*", default=MAPS)
    ap.add_argument("--counts", default="4,8,16,32,64,128")
    ap.add_argument("--span", type=float, default=2.0, help="LP_SAMPLED_SUBLOBE_SPAN")
    ap.add_argument("--variants", default="", help="extra columns: source:span:narrow:count, e.g. cube:1:0:32")
    ap.add_argument("--exact", action="store_true", help="add the exact integral of lightpass's BRDF (minutes)")
    ap.add_argument("--min-alpha", type=float, default=0.15)
    ap.add_argument("--out", default=str(gt.REPO / "bench/results/mitsuba" / f"{datetime.date.today().isoformat()}_ibl-against-mitsuba" / "sampled_specular.md"))
    ap.add_argument("--specular-masking", default="height-correlated", choices=["height-correlated", "separable"],
                    help="lightpass's Smith model (the DFG terms, the weights and --exact)")
    args = ap.parse_args()
    globals()["MASKING"] = args.specular_masking
    variants = [("prefiltered", args.span, True, int(c)) for c in args.counts.split(",")]
    for v in filter(None, args.variants.split(",")):
        src, span, narrow, count = v.split(":")
        variants.append((src, float(span), narrow == "1", int(count)))
    head = ["split sum (measured)", "split sum (emulated)"] + (["exact BRDF integral"] if args.exact else []) + \
        [f"sampled {n}" if (src, sp, nar) == ("prefiltered", args.span, True) else f"{src} {sp:g} {int(nar)} {n}"
         for src, sp, nar, n in variants]
    lines = ["# Sampled specular IBL emulated on the CPU, against Mitsuba 128 spp", "",
             "Generated by `bench/mitsuba/sampled_specular.py` (its docstring defines the estimator; sub-lobe span "
             f"{args.span:g}, narrowed sampling). Relative error of the sphere's mean radiance against Mitsuba, whole "
             "sphere / N·V ≥ 0.7; lightpass's own environment cube and prefiltered chain (its --ibl-cache files).", ""]
    for map_name in args.maps:
        ref_path = Path(args.work) / f"{map_name}_mitsuba_{WIDTH}x{HEIGHT}_{args.spp}spp_scalar_rgb.exr"
        if not ref_path.is_file():
            sys.exit(f"sampled_specular.py: {ref_path}: no Mitsuba composite (run bench/mitsuba/run.sh --maps ... "
                     f"--size {WIDTH}x{HEIGHT} --spp {args.spp} --work {args.work})")
        gt.mi.set_variant("scalar_rgb")
        ref = gt.read_rgb(ref_path)
        chains = lightpass_chains(map_name, args.lightpass, args.work)
        measured = measured_split_sum(map_name)
        lines += [f"## {map_name}", "", "| sphere | " + " | ".join(head) + " |", "| --- |" + " ---: |" * len(head)]
        for name, centre, kind, a, _ in gt.spheres():
            if kind != "ggx" or a < args.min_alpha:
                continue
            mask, N, V = sphere_pixels(np.array(centre, float))
            nv = np.clip(np.sum(N * V, 1), 0.0, 1.0)
            core = nv >= 0.7
            ab = dfg_ab(nv, a)
            m = ref[mask]

            def cell(v):
                return f"{v.mean() / m.mean() - 1:+.3f} / {v[core].mean() / m[core].mean() - 1:+.3f}"
            meas = measured.get(name)
            cells = [f"{meas[0]:+.3f} / {meas[1]:+.3f}" if meas else "—", cell(split_sum(chains[1], N, V, a, ab))]
            if args.exact:
                cells.append(cell(exact_integral(chains[0], N, V, a)))
            for src, span, narrow, n in variants:
                cells.append(cell(sampled_specular(chains, N, V, a, ab, point_set(n, "hammersley"), src, span, narrow)))
            lines.append(f"| {name} | " + " | ".join(cells) + " |")
            print(map_name, lines[-1], flush=True)
        lines.append("")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text("\n".join(lines) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
