#!/usr/bin/env python3
"""Converts a lightpass scene file into what a peer renderer (Filament through filly) loads:

  OUTDIR/NAME.glb             the scene's triangles: one mesh per model and one node per model or
                              per instance of it (models[].instances; its transform as the node
                              matrix), one primitive per material, and the camera as a glTF camera node.
                              Motion ("spin", a sun's "turn") is not converted: the peer draws time 0
  OUTDIR/NAME.peer.json       the rest for the peer: camera, suns, point lights, environment map
                              (a Radiance .hdr), triangle count and world bounds, the material mapping
  OUTDIR/NAME.lightpass.json  the same scene for lightpass with the same light subset and map, so
                              both renderers draw the same work

  scene_to_glb.py SCENE.json --out-dir DIR [--name NAME] [--suns N] [--points N]

--suns / --points keep the scene's first N directional / point (and spot) lights (default: all).

Geometry follows lightpass's loaders (engine/io/obj_loader.cpp, engine/scene/primitives.cpp), so the
GLB has the triangles lightpass draws: OBJ quads split on the shorter diagonal (tinyobjloader's rule),
larger polygons fanned, degenerate and non-finite triangles dropped, normals generated per position
(area-weighted) when any are missing. Materials: Blinn-Phong Kd/Ks/Ns to metallic-roughness, see
mtl_to_metallic_roughness(). Needs Python 3 with numpy. Errors are one line naming the file.
"""
import argparse
import json
import math
import os
import struct
import sys

import numpy as np

DIELECTRIC_F0 = 0.04
MAX_COORDINATE = 1e18  # positions beyond it count as non-finite (obj_text.cpp)


class ConvertError(Exception):
    pass


# ---------------------------------------------------------------- materials

def perceived_brightness(c):
    """Perceived brightness of a linear colour (the weights of the glTF spec-gloss conversion)."""
    return math.sqrt(0.299 * c[0] ** 2 + 0.587 * c[1] ** 2 + 0.114 * c[2] ** 2)


def solve_metallic(diffuse, specular):
    """Metallic factor m for diffuse brightness d and specular brightness s, modelling the diffuse
    albedo as base (1 - m) and F0 as 0.04 (1 - m) + base m (glTF, Filament). With base = d / (1 - m):
    0.04 m^2 + (d + s - 0.08) m + (0.04 - s) = 0, the root in [0, 1]; 0 for s at or below 0.04."""
    if specular <= DIELECTRIC_F0:
        return 0.0
    a = DIELECTRIC_F0
    b = diffuse + specular - 2.0 * DIELECTRIC_F0
    c = DIELECTRIC_F0 - specular
    d = max(b * b - 4.0 * a * c, 0.0)
    return min(max((-b + math.sqrt(d)) / (2.0 * a), 0.0), 1.0)


def roughness_from_shininess(ns):
    """lightpass's own Ns -> perceptual roughness (engine/scene/mesh_ops.cpp): alpha = r^2 = sqrt(2 / (Ns + 2)),
    the inverse of the mapping its glTF loader applies, so lightpass reading the GLB gets Ns back."""
    n = min(max(float(ns), 0.0), 10000.0)
    return math.sqrt(math.sqrt(2.0 / (n + 2.0)))


def mtl_to_metallic_roughness(kd, ks, ns):
    """Blinn-Phong (Kd, Ks, Ns) to glTF metallic-roughness (base colour, metallic, roughness).

    Kd below stands for lightpass's diffuse layer Kd (1 - Ks) (its GGX BRDF: base Kd under a dielectric of
    F0 = Ks). metallic m = solve_metallic(brightness(Kd), brightness(Ks)): 0 for a dielectric Ks <= 0.04, rising
    towards 1 as Ks outweighs Kd. Base colour per channel: the diffuse estimate Kd / (1 - m) (so that the
    diffuse albedo base (1 - m) stays Kd) blended towards the specular estimate (Ks - 0.04 (1 - m)) / m by
    m^2 (the KHR spec-gloss conversion's blend), clamped to [0, 1]. Roughness: roughness_from_shininess(Ns).
    A dielectric material (Ks <= 0.04) keeps base = Kd (1 - Ks) exactly (F0 stays Filament's 0.04)."""
    ks = [min(max(float(x), 0.0), 1.0) for x in ks]
    # lightpass's diffuse layer under its GGX BRDF is Kd (1 - Ks) (shaders/common/material.glsl
    # materialDiffuseAlbedo: glTF's fresnel_mix of a dielectric of F0 = Ks over base Kd), so that is the
    # albedo base (1 - m) must equal; Kd itself only where Ks = 0.
    kd = [float(x) * (1.0 - s) for x, s in zip(kd, ks)]
    m = solve_metallic(perceived_brightness(kd), perceived_brightness(ks))
    eps = 1e-6
    base = []
    for c in range(3):
        from_diffuse = kd[c] / max(1.0 - m, eps)
        from_specular = (ks[c] - DIELECTRIC_F0 * (1.0 - m)) / max(m, eps)
        base.append(min(max(from_diffuse + (from_specular - from_diffuse) * m * m, 0.0), 1.0))
    return base, m, roughness_from_shininess(ns)


def default_material():
    """lightpass's Material{} (engine/scene/mesh.hpp)."""
    return {"name": "default", "diffuse": [0.8, 0.8, 0.8], "specular": [0.04, 0.04, 0.04], "shininess": 32.0,
            "emission": [0.0, 0.0, 0.0], "opacity": 1.0, "flat": False}


def parse_mtl(path, warnings):
    """The MTL fields lightpass reads (Kd, Ks, Ke, Ns, d / Tr), in file order; maps are not carried."""
    materials, current = [], None
    with open(path, encoding="utf-8-sig", errors="replace") as f:
        for line in f:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            key = words[0]
            if key == "newmtl":
                current = default_material()
                current["name"] = " ".join(words[1:])
                current["diffuse"] = [0.0, 0.0, 0.0]  # tinyobjloader's material_t: colours start at 0, Ns at 1
                current["specular"] = [0.0, 0.0, 0.0]
                current["shininess"] = 1.0
                materials.append(current)
                continue
            if current is None:
                continue
            try:
                if key in ("Kd", "Ks", "Ke") and len(words) >= 2:
                    vals = [float(w) for w in words[1:4]]
                    while len(vals) < 3:
                        vals.append(vals[0])
                    vals = [max(v, 0.0) if math.isfinite(v) else 0.0 for v in vals]
                    current[{"Kd": "diffuse", "Ks": "specular", "Ke": "emission"}[key]] = vals
                elif key == "Ns" and len(words) >= 2:
                    current["shininess"] = min(max(float(words[1]), 0.0), 10000.0)
                elif key == "d" and len(words) >= 2:
                    current["opacity"] = min(max(float(words[1]), 0.0), 1.0)
                elif key == "Tr" and len(words) >= 2:
                    current["opacity"] = min(max(1.0 - float(words[1]), 0.0), 1.0)
                elif key.startswith("map_") or key in ("bump", "norm", "disp"):
                    warnings.append(f"{path}: material '{current['name']}': {key} is not carried into the GLB (untextured)")
            except ValueError:
                warnings.append(f"{path}: material '{current['name']}': bad {key}; kept the default")
    return materials


# ---------------------------------------------------------------- meshes

class Mesh:
    """Positions and normals (float32, n x 3), triangles (int64, t x 3) and the material per triangle,
    plus the materials it indexes."""

    def __init__(self, positions, normals, triangles, triangle_material, materials):
        self.positions = np.asarray(positions, dtype=np.float32).reshape(-1, 3)
        self.normals = np.asarray(normals, dtype=np.float32).reshape(-1, 3)
        self.triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
        self.triangle_material = np.asarray(triangle_material, dtype=np.int64).reshape(-1)
        self.materials = materials


def make_plane(size=1.0, subdivisions=8):
    n = max(1, subdivisions)
    pos, nrm, tris = [], [], []
    for z in range(n + 1):
        for x in range(n + 1):
            u, w = np.float32(x) / np.float32(n), np.float32(z) / np.float32(n)
            pos.append([(u - np.float32(0.5)) * np.float32(size), 0.0, (w - np.float32(0.5)) * np.float32(size)])
            nrm.append([0.0, 1.0, 0.0])
    for z in range(n):
        for x in range(n):
            a = z * (n + 1) + x
            b, c = a + 1, a + n + 1
            d = c + 1
            tris += [[a, c, b], [b, c, d]]
    return Mesh(pos, nrm, tris, [0] * len(tris), [default_material()])


def make_sphere(radius=0.5, segments=64, rings=32):
    segments, rings = max(3, segments), max(2, rings)
    pi = np.float32(3.14159265358979)
    pos, nrm, tris = [], [], []
    for r in range(rings + 1):
        theta = pi * np.float32(r) / np.float32(rings)
        for s in range(segments + 1):
            phi = np.float32(2.0) * pi * np.float32(s) / np.float32(segments)
            nv = [np.sin(theta) * np.cos(phi), np.cos(theta), -np.sin(theta) * np.sin(phi)]
            nrm.append(nv)
            pos.append([c * np.float32(radius) for c in nv])
    row = segments + 1
    for r in range(rings):
        for s in range(segments):
            a = r * row + s
            b, c = a + 1, a + row
            d = c + 1
            if r != 0:
                tris.append([a, c, b])
            if r != rings - 1:
                tris.append([b, c, d])
    return Mesh(pos, nrm, tris, [0] * len(tris), [default_material()])


def make_cube(size=1.0):
    h = 0.5 * size
    pos, nrm, tris = [], [], []
    for n in ([1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]):
        n = np.array(n, dtype=np.float64)
        t = np.array([1.0, 0.0, 0.0]) if abs(n[1]) > 0.5 else np.array([-n[2], 0.0, n[0]])
        b = np.cross(n, t)
        base = len(pos)
        for cx, cy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append(list((n + cx * t + cy * b) * h))
            nrm.append(list(n))
        tris += [[base, base + 1, base + 2], [base, base + 2, base + 3]]
    return Mesh(pos, nrm, tris, [0] * len(tris), [default_material()])


def _obj_index(token, count):
    """A 1-based (or negative, relative) OBJ index to 0-based; -1 when absent or zero."""
    if token == "":
        return -1
    i = int(token)
    if i > 0:
        return i - 1
    if i < 0:
        return count + i
    return -1


def load_obj(path, warnings):
    """An OBJ as lightpass's loader reads it (tinyobjloader with triangulation, then obj_loader.cpp's
    dedup, drops and normals)."""
    if not os.path.isfile(path):
        raise ConvertError(f"{path}: file not found")
    folder = os.path.dirname(path)
    vs, vns, vts = [], [], []
    corners = []  # (v, t, n) per triangle corner, three per triangle
    tri_mat = []
    materials, material_index = [], {}
    current_mat = -1
    polygons_fanned = 0
    with open(path, encoding="utf-8-sig", errors="replace") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            key = words[0]
            if key == "v":
                try:
                    p = [float(w) for w in words[1:4]]
                except ValueError:
                    p = [float("nan")] * 3
                while len(p) < 3:
                    p.append(0.0)
                vs.append(p)
            elif key == "vn":
                vns.append([float(w) for w in words[1:4]] + [0.0] * (3 - len(words[1:4])))
            elif key == "vt":
                vts.append(0)
            elif key == "f":
                face = []
                for w in words[1:]:
                    parts = w.split("/")
                    v = _obj_index(parts[0], len(vs))
                    t = _obj_index(parts[1], len(vts)) if len(parts) > 1 else -1
                    n = _obj_index(parts[2], len(vns)) if len(parts) > 2 else -1
                    face.append((v, t, n))
                if len(face) < 3:
                    continue
                if len(face) == 3:
                    tris = [face]
                elif len(face) == 4:
                    ids = [c[0] for c in face]
                    if any(i < 0 or i >= len(vs) for i in ids):
                        continue  # tinyobjloader skips a quad with an invalid index
                    q = np.array([vs[i] for i in ids], dtype=np.float32)
                    e02, e13 = q[2] - q[0], q[3] - q[1]
                    if np.float32(np.dot(e02, e02)) < np.float32(np.dot(e13, e13)):
                        tris = [[face[0], face[1], face[2]], [face[0], face[2], face[3]]]
                    else:
                        tris = [[face[0], face[1], face[3]], [face[1], face[2], face[3]]]
                else:
                    polygons_fanned += 1
                    tris = [[face[0], face[k], face[k + 1]] for k in range(1, len(face) - 1)]
                for t in tris:
                    corners.extend(t)
                    tri_mat.append(current_mat)
            elif key == "usemtl":
                current_mat = material_index.get(" ".join(words[1:]), -1)
            elif key == "mtllib":
                for name in words[1:]:
                    mtl = name if os.path.isabs(name) else os.path.normpath(os.path.join(folder, name))
                    if not os.path.isfile(mtl):
                        warnings.append(f"{path}: mtllib {mtl}: file not found; using default materials")
                        continue
                    for m in parse_mtl(mtl, warnings):
                        if m["name"] not in material_index:
                            material_index[m["name"]] = len(materials)
                            materials.append(m)
    if polygons_fanned:
        warnings.append(f"{path}: {polygons_fanned} polygons of more than 4 vertices fanned (tinyobjloader ear-clips: "
                        "same triangle count for convex polygons)")
    positions = np.array(vs, dtype=np.float32).reshape(-1, 3)
    pos64 = positions.astype(np.float64)
    bad_pos = ~np.all(np.isfinite(pos64), axis=1) | np.any(np.abs(pos64) > MAX_COORDINATE, axis=1)
    c = np.array(corners, dtype=np.int64).reshape(-1, 3, 3)  # triangle, corner, (v, t, n)
    tri_mat = np.array(tri_mat, dtype=np.int64)
    if len(c) == 0:
        raise ConvertError(f"{path}: no triangles")
    vi = c[:, :, 0]
    in_range = np.all((vi >= 0) & (vi < len(positions)), axis=1)
    dropped_index = int(np.count_nonzero(~in_range))
    c, vi, tri_mat = c[in_range], vi[in_range], tri_mat[in_range]
    finite = ~np.any(bad_pos[vi], axis=1)
    dropped_nonfinite = int(np.count_nonzero(~finite))
    c, vi, tri_mat = c[finite], vi[finite], tri_mat[finite]
    degenerate = degenerate_triangles(pos64[vi[:, 0]], pos64[vi[:, 1]], pos64[vi[:, 2]])
    degenerate |= (vi[:, 0] == vi[:, 1]) | (vi[:, 1] == vi[:, 2]) | (vi[:, 0] == vi[:, 2])
    dropped_degenerate = int(np.count_nonzero(degenerate))
    c, vi, tri_mat = c[~degenerate], vi[~degenerate], tri_mat[~degenerate]
    if dropped_index:
        warnings.append(f"{path}: {dropped_index} faces with out-of-range vertex indices dropped")
    if dropped_degenerate or dropped_nonfinite:
        warnings.append(f"{path}: dropped {dropped_degenerate} degenerate and {dropped_nonfinite} non-finite triangles")
    if len(c) == 0:
        raise ConvertError(f"{path}: no triangles")

    default_id = len(materials)
    materials = materials + [default_material()]
    tri_mat = np.where((tri_mat < 0) | (tri_mat >= default_id), default_id, tri_mat)

    normals_in = np.array(vns, dtype=np.float64).reshape(-1, 3)
    n_idx = c[:, :, 2]
    t_idx = c[:, :, 1]
    n_idx = np.where((n_idx >= 0) & (n_idx < len(normals_in)), n_idx, -1)
    t_idx = np.where((t_idx >= 0) & (t_idx < len(vts)), t_idx, -1)
    # Output vertices: one per distinct (position, normal, uv) corner, as obj_loader.cpp's dedup.
    keys = np.stack([vi.reshape(-1), n_idx.reshape(-1), t_idx.reshape(-1)], axis=1)
    unique_keys, inverse = np.unique(keys, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    out_pos = positions[unique_keys[:, 0]]
    nk = unique_keys[:, 1]
    missing = nk < 0
    out_nrm = np.zeros((len(unique_keys), 3), dtype=np.float64)
    if len(normals_in):
        raw = normals_in[np.where(missing, 0, nk)]
        length = np.linalg.norm(raw, axis=1)
        good = ~missing & (length > 0) & np.isfinite(length)
        out_nrm[good] = raw[good] / length[good, None]
        missing |= ~good
    triangles = inverse.reshape(-1, 3)
    if np.any(missing):
        # Area-weighted per OBJ position, so that vertices split by seams share one normal.
        acc = np.zeros((len(positions), 3), dtype=np.float64)
        p = out_pos.astype(np.float64)
        face_n = np.cross(p[triangles[:, 1]] - p[triangles[:, 0]], p[triangles[:, 2]] - p[triangles[:, 0]])
        for k in range(3):
            np.add.at(acc, unique_keys[triangles[:, k], 0], face_n)
        n = acc[unique_keys[:, 0]]
        length = np.linalg.norm(n, axis=1)
        ok = (length > 0) & np.isfinite(length)
        out_nrm = np.tile([0.0, 1.0, 0.0], (len(unique_keys), 1))
        out_nrm[ok] = n[ok] / length[ok, None]
    return Mesh(out_pos, out_nrm, triangles, tri_mat, materials)


def degenerate_triangles(a, b, c):
    """lightpass's degenerateTriangle (mesh_ops.cpp), in double: area below 1e-10 of the longest edge squared."""
    e0, e1, e2 = b - a, c - a, c - b
    area2 = np.linalg.norm(np.cross(e0, e1), axis=1)
    longest2 = np.maximum(np.maximum(np.sum(e0 * e0, axis=1), np.sum(e1 * e1, axis=1)), np.sum(e2 * e2, axis=1))
    with np.errstate(invalid="ignore"):
        return ~(area2 > 1e-10 * longest2) | ~np.isfinite(area2)


# ---------------------------------------------------------------- transforms and camera

def rotation(axis, degrees):
    r = math.radians(degrees)
    c, s = math.cos(r), math.sin(r)
    m = np.eye(4)
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def vec3(value, default):
    if value is None:
        return list(default)
    if isinstance(value, (int, float)):
        return [float(value)] * 3
    return [float(x) for x in value]


def model_matrix(model):
    """scene_loader.cpp's order: translate x rotate Y x rotate X x rotate Z x scale (x z-up turn)."""
    t = vec3(model.get("translate"), [0, 0, 0])
    rot = vec3(model.get("rotate"), [0, 0, 0])
    s = vec3(model.get("scale"), [1, 1, 1])
    m = np.eye(4)
    m[:3, 3] = t
    m = m @ rotation("y", rot[1]) @ rotation("x", rot[0]) @ rotation("z", rot[2])
    m = m @ np.diag([s[0], s[1], s[2], 1.0])
    if model.get("up") == "z":
        m = m @ rotation("x", -90.0)
    return m


def camera_world_matrix(position, target, up):
    """The camera node's matrix: columns right, up, back (glTF cameras look down -Z), position."""
    p, t, u = (np.array(x, dtype=np.float64) for x in (position, target, up))
    f = t - p
    f /= np.linalg.norm(f)
    r = np.cross(f, u)
    if np.linalg.norm(r) < 1e-12:
        raise ConvertError("camera.up is parallel to the view direction")
    r /= np.linalg.norm(r)
    u2 = np.cross(r, f)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = r, u2, -f, p
    return m


# ---------------------------------------------------------------- GLB

class GlbWriter:
    def __init__(self):
        self.bin = bytearray()
        self.gltf = {"asset": {"version": "2.0", "generator": "lightpass bench/peers/scene_to_glb.py"},
                     "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                     "accessors": [], "bufferViews": [], "buffers": [], "cameras": []}

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data), "target": target}
        self.bin += data
        self.gltf["bufferViews"].append(view)
        return len(self.gltf["bufferViews"]) - 1

    def accessor(self, array, kind, target, with_bounds=False):
        array = np.ascontiguousarray(array)
        comp = {np.dtype(np.float32): 5126, np.dtype(np.uint32): 5125}[array.dtype]
        acc = {"bufferView": self._view(array.tobytes(), target), "componentType": comp,
               "count": int(array.shape[0]), "type": kind}
        if with_bounds:
            acc["min"] = [float(x) for x in array.min(axis=0)]
            acc["max"] = [float(x) for x in array.max(axis=0)]
        self.gltf["accessors"].append(acc)
        return len(self.gltf["accessors"]) - 1

    def write(self, path):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.gltf["buffers"] = [{"byteLength": len(self.bin)}]
        if not self.gltf["cameras"]:
            del self.gltf["cameras"]
        text = json.dumps(self.gltf, separators=(",", ":")).encode("utf-8")
        text += b" " * ((4 - len(text) % 4) % 4)
        total = 12 + 8 + len(text) + 8 + len(self.bin)
        tmp = path + ".tmp"
        with open(tmp, "wb") as f:
            f.write(struct.pack("<4sII", b"glTF", 2, total))
            f.write(struct.pack("<I4s", len(text), b"JSON"))
            f.write(text)
            f.write(struct.pack("<I4s", len(self.bin), b"BIN\x00"))
            f.write(self.bin)
        os.replace(tmp, path)  # never a half-written GLB under the final name


def gltf_material(m):
    base, metallic, roughness = mtl_to_metallic_roughness(m["diffuse"], m["specular"], m["shininess"])
    out = {"name": m["name"], "doubleSided": True,  # lightpass draws OBJ and primitive materials double-sided
           "pbrMetallicRoughness": {"baseColorFactor": base + [m["opacity"]], "metallicFactor": metallic,
                                    "roughnessFactor": roughness}}
    e = m.get("emission", [0, 0, 0])
    if max(e) > 0:
        scale = max(e)
        if scale > 1.0:
            out["emissiveFactor"] = [x / scale for x in e]
            out["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": scale}}
        else:
            out["emissiveFactor"] = list(e)
    if m["opacity"] < 1.0:
        out["alphaMode"], out["alphaCutoff"] = "MASK", 0.5  # lightpass's deferred path draws d < 1 as MASK
    if m.get("flat"):
        out["extensions"] = dict(out.get("extensions", {}), KHR_materials_unlit={})
    record = {"name": m["name"], "Kd": m["diffuse"], "Ks": m["specular"], "Ns": m["shininess"],
              "baseColor": base, "metallic": metallic, "roughness": roughness}
    return out, record


# ---------------------------------------------------------------- scene

def resolve(base, p):
    return p if os.path.isabs(p) else os.path.normpath(os.path.join(base, p))


def peer_environment_map(map_path):
    """filly reads Radiance .hdr (and PNG/JPEG) panoramas; an .exr map uses the .hdr of the same name
    beside it (hdr/sky.exr and hdr/sky.hdr are the same sky from scripts/make_sky.py)."""
    root, ext = os.path.splitext(map_path)
    if ext.lower() in (".hdr", ".png", ".jpg", ".jpeg"):
        if not os.path.isfile(map_path):
            raise ConvertError(f"environment.map {map_path}: file not found")
        return map_path
    for candidate in (root + ".hdr", root + ".HDR"):
        if os.path.isfile(candidate):
            return candidate
    raise ConvertError(f"environment.map {map_path}: filly reads Radiance .hdr, PNG or JPEG, and no {root}.hdr is beside it")


# ---------------------------------------------------------------- environment lights

# lightpass's defaults (--ibl-extract-lights 4, --ibl-extract-threshold 100; engine/render/ibl_lights.hpp)
ENV_LIGHTS_MAX = 4
ENV_LIGHTS_THRESHOLD = 100.0
ENV_LIGHT_MAX_SOLID_ANGLE = 0.005 * 4.0 * math.pi
LUMA = np.array([0.2126, 0.7152, 0.0722])


def read_hdr(path):
    """A Radiance .hdr (flat or RLE scanlines, -Y H +X W) as float64 RGB rows top first."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"\n\n")
    line_end = data.find(b"\n", end + 2)
    if end < 0 or line_end < 0:
        raise ConvertError(f"{path}: not a Radiance .hdr")
    res = data[end + 2:line_end].split()
    if len(res) != 4 or res[0] != b"-Y" or res[2] != b"+X":
        raise ConvertError(f"{path}: unsupported .hdr orientation {data[end + 2:line_end]!r}")
    h, w = int(res[1]), int(res[3])
    buf, pos = np.frombuffer(data, np.uint8), line_end + 1
    rgbe = np.zeros((h, w, 4), np.uint8)
    for y in range(h):
        if 8 <= w < 32768 and buf[pos] == 2 and buf[pos + 1] == 2 and (int(buf[pos + 2]) << 8 | int(buf[pos + 3])) == w:
            pos += 4
            for c in range(4):
                x = 0
                while x < w:
                    n = int(buf[pos]); pos += 1
                    if n > 128:
                        rgbe[y, x:x + n - 128, c] = buf[pos]; pos += 1; x += n - 128
                    else:
                        rgbe[y, x:x + n, c] = buf[pos:pos + n]; pos += n; x += n
        else:
            rgbe[y] = buf[pos:pos + 4 * w].reshape(w, 4); pos += 4 * w
    e = rgbe[..., 3].astype(np.int32)
    return np.where(e[..., None] > 0, rgbe[..., :3] * np.ldexp(1.0, e - 136)[..., None], 0.0)


def write_hdr(path, img):
    """Float RGB rows top first as a flat (uncompressed) Radiance .hdr."""
    m = img.max(-1)
    e = np.where(m > 1e-32, np.floor(np.log2(np.maximum(m, 1e-32))) + 1, 0).astype(np.int32)
    rgbe = np.zeros(img.shape[:2] + (4,), np.uint8)
    rgbe[..., :3] = np.clip(np.floor(img * np.ldexp(256.0, -e)[..., None]), 0, 255)
    rgbe[..., 3] = np.where(m > 1e-32, e + 128, 0)
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {img.shape[0]} +X {img.shape[1]}\n".encode())
        f.write(rgbe.tobytes())


def extract_environment_lights(img, rotation_deg, max_lights=ENV_LIGHTS_MAX, ratio=ENV_LIGHTS_THRESHOLD):
    """lightpass's extractEnvironmentLights (engine/render/ibl_lights.cpp) on an equirect map (v = 0 at
    +Y, centre column at -Z): regions (8-neighbours, wrapping in longitude) of texels above `ratio` times
    the solid-angle median luminance, at most 0.5% of the sphere; each one's excess over the mean of
    the texels around it leaves the map (in place) and becomes a light. Returns the lights, brightest
    first: {"towards": unit world direction (map rotated by rotation_deg about +Y), "irradiance": RGB
    E at normal incidence}."""
    h, w, _ = img.shape
    row_sa = (2 * math.pi / w) * (math.pi / h) * np.sin((np.arange(h) + 0.5) / h * math.pi)
    sa = np.broadcast_to(row_sa[:, None], (h, w))
    lum = img @ LUMA
    order = np.argsort(lum, axis=None)
    acc = np.cumsum(sa.ravel()[order])
    median = lum.ravel()[order[np.searchsorted(acc, 0.5 * acc[-1])]]
    threshold = ratio * max(median, 0.01 * (lum * sa).sum() / sa.sum())
    label = -np.ones((h, w), np.int64)
    regions = []

    def neighbours(y, x):
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                if (dy or dx) and 0 <= y + dy < h:
                    yield y + dy, (x + dx) % w

    for y0, x0 in zip(*np.nonzero(lum > threshold)):
        if label[y0, x0] >= 0:
            continue
        label[y0, x0] = len(regions)
        texels, stack = [], [(y0, x0)]
        while stack:
            y, x = stack.pop()
            texels.append((y, x))
            for yy, xx in neighbours(y, x):
                if label[yy, xx] < 0 and lum[yy, xx] > threshold:
                    label[yy, xx] = len(regions)
                    stack.append((yy, xx))
        regions.append(texels)
    rot = math.radians(rotation_deg)
    lights = []
    for texels in regions:
        if sum(row_sa[y] for y, _ in texels) > ENV_LIGHT_MAX_SOLID_ANGLE:
            continue
        ring = {(yy, xx) for y, x in texels for yy, xx in neighbours(y, x) if label[yy, xx] < 0}
        ring_sa = sum(row_sa[y] for y, _ in ring)
        background = sum(img[y, x] * row_sa[y] for y, x in ring) / ring_sa if ring_sa > 0 else np.zeros(3)
        irradiance, direction = np.zeros(3), np.zeros(3)
        for y, x in texels:
            excess = img[y, x] - np.minimum(img[y, x], background)
            irradiance += excess * row_sa[y]
            phi, theta = ((x + 0.5) / w - 0.5) * 2 * math.pi, (y + 0.5) / h * math.pi
            d = np.array([math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi)])
            d = np.array([d[0] * math.cos(rot) + d[2] * math.sin(rot), d[1], -d[0] * math.sin(rot) + d[2] * math.cos(rot)])
            direction += d * float(excess @ LUMA) * row_sa[y]
        if irradiance @ LUMA > 0 and np.linalg.norm(direction) > 0:
            lights.append((float(irradiance @ LUMA), texels, background, irradiance, direction / np.linalg.norm(direction)))
    lights.sort(key=lambda l: -l[0])
    out = []
    for _, texels, background, irradiance, direction in lights[:max_lights]:
        for y, x in texels:
            img[y, x] = np.minimum(img[y, x], background)
        out.append({"towards": [float(v) for v in direction], "irradiance": [float(v) for v in irradiance]})
    return out


def load_model_mesh(model, base, where, warnings):
    if "primitive" in model:
        kind = model["primitive"]
        makers = {"plane": make_plane, "sphere": make_sphere, "cube": make_cube}
        if kind not in makers:
            raise ConvertError(f"{where}.primitive: unknown primitive '{kind}' (plane, sphere, cube)")
        mesh = makers[kind]()
    elif "obj" in model:
        mesh = load_obj(resolve(base, model["obj"]), warnings)
    elif "gltf" in model:
        raise ConvertError(f"{where}.gltf: glTF models are not converted (OBJ and primitives only)")
    else:
        raise ConvertError(f"{where}: needs one of \"obj\" or \"primitive\"")
    over = model.get("material", {})
    for m in mesh.materials:
        if "diffuse" in over:
            m["diffuse"] = vec3(over["diffuse"], [0, 0, 0])
        if "specular" in over:
            m["specular"] = vec3(over["specular"], [0, 0, 0])
        if "shininess" in over:
            m["shininess"] = float(over["shininess"])
        if "flat" in over:
            m["flat"] = bool(over["flat"])
    return mesh


def convert(scene_path, out_dir, name=None, suns=None, points=None, log=print):
    """Writes NAME.glb, NAME.peer.json and NAME.lightpass.json into out_dir; returns the sidecar dict."""
    try:
        with open(scene_path, encoding="utf-8") as f:
            scene = json.load(f)
    except FileNotFoundError:
        raise ConvertError(f"{scene_path}: file not found")
    except json.JSONDecodeError as e:
        raise ConvertError(f"{scene_path}: invalid JSON: {e}")
    base = os.path.dirname(os.path.abspath(scene_path))
    name = name or os.path.splitext(os.path.basename(scene_path))[0]
    if "camera" not in scene:
        raise ConvertError(f"{scene_path}: camera: missing (the peer needs the scene's own camera)")
    cam = scene["camera"]
    camera = {"position": vec3(cam.get("position"), [0, 1, 3]), "target": vec3(cam.get("target"), [0, 0, 0]),
              "up": vec3(cam.get("up"), [0, 1, 0]), "fov": float(cam.get("fov", 45.0)),
              "near": float(cam.get("near", 0.05)), "far": float(cam.get("far", 100.0))}

    warnings = []
    glb = GlbWriter()
    material_records = []
    triangles = 0
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for i, model in enumerate(scene.get("models", [])):
        where = f"models[{i}]"
        try:
            mesh = load_model_mesh(model, base, where, warnings)
        except ConvertError as e:
            raise ConvertError(f"{scene_path}: {where}: {e}")
        # models[].instances: the mesh once, a node per instance (its placement after the model's own).
        xform = model_matrix(model)
        instances = model.get("instances")
        xforms = [model_matrix(p) @ xform for p in instances] if instances else [xform]
        used = np.unique(mesh.triangles)
        homogeneous = np.c_[mesh.positions[used].astype(np.float64), np.ones(len(used))]
        for x in xforms:
            world = (homogeneous @ x.T)[:, :3]
            lo, hi = np.minimum(lo, world.min(axis=0)), np.maximum(hi, world.max(axis=0))
        pos_acc = glb.accessor(mesh.positions, "VEC3", 34962, with_bounds=True)
        nrm_acc = glb.accessor(mesh.normals.astype(np.float32), "VEC3", 34962)
        primitives = []
        for mat_id in sorted(set(int(x) for x in mesh.triangle_material)):
            tris = mesh.triangles[mesh.triangle_material == mat_id].astype(np.uint32).reshape(-1)
            triangles += len(tris) // 3 * len(xforms)
            gm, record = gltf_material(mesh.materials[mat_id])
            gm["name"] = f"{model.get('name', where)}/{gm['name']}"
            record["name"] = gm["name"]
            glb.gltf["materials"].append(gm)
            material_records.append(record)
            primitives.append({"attributes": {"POSITION": pos_acc, "NORMAL": nrm_acc},
                               "indices": glb.accessor(tris, "SCALAR", 34963), "mode": 4,
                               "material": len(glb.gltf["materials"]) - 1})
        glb.gltf["meshes"].append({"name": model.get("name", where), "primitives": primitives})
        for k, x in enumerate(xforms):
            node_name = model.get("name", where) + (f"[{k}]" if instances else "")
            glb.gltf["nodes"].append({"name": node_name, "mesh": len(glb.gltf["meshes"]) - 1,
                                      "matrix": [float(v) for v in x.T.reshape(-1)]})  # column-major
            glb.gltf["scenes"][0]["nodes"].append(len(glb.gltf["nodes"]) - 1)
    if triangles == 0:
        raise ConvertError(f"{scene_path}: models: no triangles to convert")
    exts = sorted({e for m in glb.gltf["materials"] for e in m.get("extensions", {})})
    if exts:
        glb.gltf["extensionsUsed"] = exts
    glb.gltf["cameras"].append({"type": "perspective", "name": "camera", "perspective": {
        "yfov": math.radians(camera["fov"]), "znear": camera["near"], "zfar": camera["far"]}})
    cm = camera_world_matrix(camera["position"], camera["target"], camera["up"])
    glb.gltf["nodes"].append({"name": "camera", "camera": 0, "matrix": [float(x) for x in cm.T.reshape(-1)]})
    glb.gltf["scenes"][0]["nodes"].append(len(glb.gltf["nodes"]) - 1)

    lights = scene.get("lights", [])
    directional = [l for l in lights if l.get("type") == "directional"]
    local = [l for l in lights if l.get("type") in ("point", "spot")]
    kept_dir = directional if suns is None else directional[:suns]
    kept_local = local if points is None else local[:points]
    sun_list = [{"direction": vec3(l.get("direction"), [0, -1, 0]), "color": vec3(l.get("color"), [1, 1, 1]),
                 "intensity": float(l.get("intensity", 1.0)), "shadows": bool(l.get("shadows", True))} for l in kept_dir]
    point_list = []
    for l in kept_local:
        p = {"type": l["type"], "position": vec3(l.get("position"), [0, 0, 0]), "color": vec3(l.get("color"), [1, 1, 1]),
             "intensity": float(l.get("intensity", 1.0)), "range": float(l.get("range", 1.0))}
        if l["type"] == "spot":
            p.update(direction=vec3(l.get("direction"), [0, -1, 0]), innerAngle=float(l.get("innerAngle", 0.0)),
                     outerAngle=float(l.get("outerAngle", 30.0)))
        point_list.append(p)

    env = dict(scene.get("environment", {}))
    peer_env = None
    if env.get("map"):
        source = resolve(base, env["map"])
        peer_env = {"map": os.path.abspath(peer_environment_map(source)), "source_map": source,
                    "intensity": float(env.get("intensity", 1.0)), "rotation": float(env.get("rotation", 0.0))}
        # lightpass lights the map's small bright sources (a sun) as distant lights with the BRDF and keeps
        # the rest in its SH and prefiltered chain. filly gives Filament no SH, so Filament's diffuse IBL is
        # the prefiltered chain's roughness-1 level, whose lobe is not the cosine: a 4-texel sun lit an
        # up-facing floor at 46-100% of its irradiance depending on its elevation. Filament gets the same
        # split: the residual map (NAME.env.hdr) and the sources as unshadowed directional lights.
        img = read_hdr(peer_env["map"])
        peer_env["lights"] = extract_environment_lights(img, peer_env["rotation"])
        if peer_env["lights"]:
            os.makedirs(out_dir, exist_ok=True)
            peer_env["unextracted_map"] = peer_env["map"]
            peer_env["map"] = os.path.abspath(os.path.join(out_dir, name + ".env.hdr"))
            write_hdr(peer_env["map"], img)

    os.makedirs(out_dir, exist_ok=True)
    glb_path = os.path.join(out_dir, name + ".glb")
    glb.write(glb_path)

    # The same scene for lightpass: the kept lights, absolute paths, the peer's map, IBL on, exposure 0.
    matched = json.loads(json.dumps(scene))
    matched["description"] = f"{scene.get('description', name)} [peer-matched: {len(kept_dir)} directional, {len(kept_local)} local lights]"
    for model in matched.get("models", []):
        for key in ("obj", "gltf"):
            if key in model:
                model[key] = resolve(base, model[key])
    matched["lights"] = kept_dir + kept_local
    if peer_env:
        matched["environment"]["map"] = peer_env.get("unextracted_map", peer_env["map"])
        matched["environment"]["ibl"] = True
    # A fixed exposure of 0 EV: the intensities are scaled for Filament's default camera (EV100 15) so
    # that both show the same radiance at lightpass's 0 EV; auto exposure would meter each differently.
    matched["exposure"] = 0
    lp_path = os.path.join(out_dir, name + ".lightpass.json")
    with open(lp_path, "w", encoding="utf-8") as f:
        json.dump(matched, f, indent=1)

    sidecar = {"scene": os.path.abspath(scene_path), "glb": name + ".glb", "lightpass_scene": name + ".lightpass.json",
               "triangles": int(triangles), "bounds": [[float(x) for x in lo], [float(x) for x in hi]],
               "camera": camera, "suns": sun_list, "points": point_list, "environment": peer_env,
               "ambient": vec3(scene.get("ambient"), [0.03, 0.03, 0.03]), "materials": material_records,
               "warnings": warnings}
    with open(os.path.join(out_dir, name + ".peer.json"), "w", encoding="utf-8") as f:
        json.dump(sidecar, f, indent=1)
    for w in warnings:
        log(f"warning: {w}")
    log(f"{glb_path}: {triangles} triangles, {len(glb.gltf['materials'])} materials, "
        f"{len(sun_list)} suns, {len(point_list)} local lights")
    return sidecar


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--name")
    ap.add_argument("--suns", type=int, help="keep the first N directional lights (default: all)")
    ap.add_argument("--points", type=int, help="keep the first N point and spot lights (default: all)")
    a = ap.parse_args(argv)
    for flag in ("suns", "points"):
        if getattr(a, flag) is not None and getattr(a, flag) < 0:
            ap.error(f"--{flag} must be >= 0")
    try:
        convert(a.scene, a.out_dir, a.name, a.suns, a.points)
    except ConvertError as e:
        print(f"scene_to_glb: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
