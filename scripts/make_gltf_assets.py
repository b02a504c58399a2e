#!/usr/bin/env python3
"""make_gltf_assets.py [OUT_DIR]: writes the glTF test assets (default tests/data/gltf/) and the PBR
sphere grid the bundled scene uses (models/pbr_spheres.glb), with pygltflib.

The generated files are committed, so CI needs no pip. To make them again:
    python3 -m venv /work/venv-gltf && /work/venv-gltf/bin/pip install pygltflib numpy
    /work/venv-gltf/bin/python scripts/make_gltf_assets.py

Files (all small):
  forms.gltf + forms.bin   one unit quad per primitive form: indices u8, u16, u32, none, an
                           interleaved buffer view (stride 32), a triangle strip, a triangle fan;
                           node i at x = 3 i
  forms.glb                the same scene as one binary file
  hierarchy.gltf           parent (T (10,0,0), R 90 deg about +Y, S 2) > child (T (1,0,0)) > a triangle
                           with a vertex at the child's origin: world (10, 0, -2) only for T R S order
  normal_plane.glb         a 2 x 2 plane facing +Y, uv u along +X and glTF v along +Z, whose normal
                           map holds one tangent-space normal (0.36, 0.48, 0.8): the shading normal
                           is (0.36, 0.8, -0.48) in world space; TANGENT given (+X, w = +1)
  normal_plane_notangent.glb  the same without TANGENT (the loader generates them)
  alpha_mask.gltf          three quads side by side, alphaMode MASK cutoff 0.5: base alpha 0.3
                           (never drawn), 0.7 (always drawn), and a texture whose left half has
                           alpha 0 and right half alpha 255 (half drawn)
  emissive.gltf            a black quad facing +Z with emissiveFactor (1, 0.5, 0.25) and
                           KHR_materials_emissive_strength 4: radiance (4, 2, 1)
  variants.gltf            two quads facing +Z (at x 0 and 1.5), white by their own materials, with
                           KHR_materials_variants "red" (left red, right blue) and "blue" (both blue)
  lights.gltf              a quad lit by a directional, a point (range 5) and a spot light (under a
                           rotated parent: at (2, 3, 0), pointing at (-1, -1, 0)/sqrt 2), and a camera
  emissive_panel.glb       (models/) the emissive quad again, for scenes/pbr-spheres.json
  viking_room.glb          (models/, only when ../shared/assets/viking-room is there; not committed:
                           CC BY 4.0, nigelgoh) the Vulkan tutorial's Z-up OBJ as a glTF, turned Y-up
                           by its node's rotation, its texture embedded
  pbr_spheres.glb          (models/) 2 rows of 5 spheres: dielectric and metal, roughness
                           0.2, 0.4, 0.6, 0.8, 1.0
  specular_spheres.glb     (models/) 2 rows of 5 dielectric spheres with KHR_materials_specular
                           (roughness 0.3): specularFactor 0, 0.25, 0.5, 0.75, 1 (bottom), and
                           specularColorFactor red, green, blue, (2, 1.6, 0.8) and, with
                           KHR_materials_ior 0 (F0 1), a specular-glossiness gold (top)
  clearcoat_spheres.glb    (models/) 3 rows of 5 red dielectric spheres (roughness 0.5) under a
                           KHR_materials_clearcoat coat: clearcoatFactor 0, 0.25, 0.5, 0.75, 1
                           (left to right) x clearcoatRoughnessFactor 0.05, 0.3, 0.6 (bottom to top)
  transmission_glass.glb   (models/) KHR_materials_transmission + KHR_materials_volume in front of a
                           striped wall (4 x 2.5, at z = -1.5, facing +Z): a clear glass sphere
                           (radius 0.5 at (-1, 0.6, 0), ior 1.5, thickness 1: its diameter), an
                           orange-tinted slab (0.9 x 1 x 0.2 at (0.25, 0.6, 0.2), thickness 0.2,
                           attenuationColor (0.95, 0.45, 0.15) at attenuationDistance 0.1) and a
                           frosted thin-walled pane (roughness 0.35, 0.6 x 0.9 at (1.3, 0.6, 0.3),
                           thickness 0)
"""
import base64, io, math, os, struct, sys

import numpy as np
import pygltflib as g
from PIL import Image

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(ROOT, "tests", "data", "gltf")
MODELS = os.path.join(ROOT, "models")
os.makedirs(OUT, exist_ok=True)

FLOAT, U8, U16, U32 = g.FLOAT, g.UNSIGNED_BYTE, g.UNSIGNED_SHORT, g.UNSIGNED_INT


class Builder:
    """One glTF with one binary buffer, filled by add_* calls."""

    def __init__(self):
        self.gltf = g.GLTF2(asset=g.Asset(version="2.0", generator="lightpass scripts/make_gltf_assets.py"))
        self.blob = bytearray()
        self.gltf.scenes = [g.Scene(nodes=[])]
        self.gltf.scene = 0

    def view(self, data, stride=None, target=None):
        while len(self.blob) % 4:
            self.blob.append(0)
        offset = len(self.blob)
        self.blob += data
        self.gltf.bufferViews.append(g.BufferView(buffer=0, byteOffset=offset, byteLength=len(data), byteStride=stride, target=target))
        return len(self.gltf.bufferViews) - 1

    def accessor(self, view, ctype, count, kind, offset=0, lo=None, hi=None):
        self.gltf.accessors.append(g.Accessor(bufferView=view, byteOffset=offset, componentType=ctype, count=count, type=kind, min=lo, max=hi))
        return len(self.gltf.accessors) - 1

    def floats(self, array, kind, bounds=False):
        a = np.asarray(array, dtype=np.float32)
        v = self.view(a.tobytes(), target=g.ARRAY_BUFFER)
        lo = a.min(axis=0).tolist() if bounds else None
        hi = a.max(axis=0).tolist() if bounds else None
        return self.accessor(v, FLOAT, len(a), kind, lo=lo, hi=hi)

    def indices(self, idx, ctype):
        dtype = {U8: np.uint8, U16: np.uint16, U32: np.uint32}[ctype]
        v = self.view(np.asarray(idx, dtype=dtype).tobytes(), target=g.ELEMENT_ARRAY_BUFFER)
        return self.accessor(v, ctype, len(idx), g.SCALAR)

    def image(self, rgba):
        png = io.BytesIO()
        Image.fromarray(np.asarray(rgba, dtype=np.uint8), "RGBA").save(png, "PNG")
        v = self.view(png.getvalue())
        self.gltf.images.append(g.Image(bufferView=v, mimeType="image/png"))
        self.gltf.textures.append(g.Texture(source=len(self.gltf.images) - 1))
        return len(self.gltf.textures) - 1

    def material(self, **kw):
        self.gltf.materials.append(g.Material(**kw))
        return len(self.gltf.materials) - 1

    def mesh(self, primitives):
        self.gltf.meshes.append(g.Mesh(primitives=primitives))
        return len(self.gltf.meshes) - 1

    def node(self, root=True, **kw):
        self.gltf.nodes.append(g.Node(**kw))
        n = len(self.gltf.nodes) - 1
        if root:
            self.gltf.scenes[0].nodes.append(n)
        return n

    def save_gltf(self, name):
        bin_name = os.path.splitext(name)[0] + ".bin"
        self.gltf.buffers = [g.Buffer(byteLength=len(self.blob), uri=bin_name)]
        with open(os.path.join(OUT, bin_name), "wb") as f:
            f.write(bytes(self.blob))
        self.gltf.save_json(os.path.join(OUT, name))

    def save_gltf_embedded(self, path):
        self.gltf.buffers = [g.Buffer(byteLength=len(self.blob), uri="data:application/octet-stream;base64," +
                                      base64.b64encode(bytes(self.blob)).decode())]
        self.gltf.save_json(path)

    def save_glb(self, path):
        self.gltf.buffers = [g.Buffer(byteLength=len(self.blob))]
        self.gltf.set_binary_blob(bytes(self.blob))
        self.gltf.save_binary(path)


QUAD_P = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]  # facing +Z
QUAD_N = [[0, 0, 1]] * 4
QUAD_UV = [[0, 1], [1, 1], [1, 0], [0, 0]]  # glTF v down the image: the image's top at y = 1
QUAD_I = [0, 1, 2, 0, 2, 3]


def forms():
    b = Builder()
    b.material(name="grey", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.8, 0.8, 0.8, 1], metallicFactor=0, roughnessFactor=0.5))
    prims = []
    pos, nrm, uv = b.floats(QUAD_P, g.VEC3, bounds=True), b.floats(QUAD_N, g.VEC3), b.floats(QUAD_UV, g.VEC2)
    attrs = lambda: g.Attributes(POSITION=pos, NORMAL=nrm, TEXCOORD_0=uv)
    for ctype in (U8, U16, U32):  # indexed, three index sizes
        prims.append(g.Primitive(attributes=attrs(), indices=b.indices(QUAD_I, ctype), material=0))
    flat_p = [QUAD_P[i] for i in QUAD_I]  # non-indexed
    prims.append(g.Primitive(attributes=g.Attributes(POSITION=b.floats(flat_p, g.VEC3, bounds=True), NORMAL=b.floats([[0, 0, 1]] * 6, g.VEC3)), material=0))
    # Interleaved: position, normal, uv in one buffer view, stride 32.
    inter = np.zeros((4, 8), dtype=np.float32)
    inter[:, 0:3], inter[:, 3:6], inter[:, 6:8] = QUAD_P, QUAD_N, QUAD_UV
    v = b.view(inter.tobytes(), stride=32, target=g.ARRAY_BUFFER)
    ip = b.accessor(v, FLOAT, 4, g.VEC3, 0, lo=[0, 0, 0], hi=[1, 1, 0])
    inn = b.accessor(v, FLOAT, 4, g.VEC3, 12)
    iuv = b.accessor(v, FLOAT, 4, g.VEC2, 24)
    prims.append(g.Primitive(attributes=g.Attributes(POSITION=ip, NORMAL=inn, TEXCOORD_0=iuv), indices=b.indices(QUAD_I, U16), material=0))
    # Strip 0 1 3 2 and fan 0 1 2 3: two triangles each, both facing +Z.
    prims.append(g.Primitive(attributes=attrs(), indices=b.indices([0, 1, 3, 2], U16), mode=g.TRIANGLE_STRIP, material=0))
    prims.append(g.Primitive(attributes=attrs(), indices=b.indices([0, 1, 2, 3], U16), mode=g.TRIANGLE_FAN, material=0))
    for i, p in enumerate(prims):
        b.node(mesh=b.mesh([p]), translation=[3.0 * i, 0, 0])
    b.save_gltf("forms.gltf")
    b.save_glb(os.path.join(OUT, "forms.glb"))


def hierarchy():
    b = Builder()
    pos = b.floats([[0, 0, 0], [0.5, 0, 0], [0, 0.5, 0]], g.VEC3, bounds=True)
    m = b.mesh([g.Primitive(attributes=g.Attributes(POSITION=pos))])
    child = b.node(root=False, mesh=m, translation=[1, 0, 0])
    s = math.sqrt(0.5)
    b.node(children=[child], translation=[10, 0, 0], rotation=[0, s, 0, s], scale=[2, 2, 2])
    b.save_gltf_embedded(os.path.join(OUT, "hierarchy.gltf"))


def normal_plane(with_tangents, name):
    b = Builder()
    P = [[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]]
    UV = [[0, 0], [1, 0], [1, 1], [0, 1]]  # u along +X, glTF v along +Z (image top at -Z)
    attrs = dict(POSITION=b.floats(P, g.VEC3, bounds=True), NORMAL=b.floats([[0, 1, 0]] * 4, g.VEC3), TEXCOORD_0=b.floats(UV, g.VEC2))
    if with_tangents:
        attrs["TANGENT"] = b.floats([[1, 0, 0, 1]] * 4, g.VEC4)
    n = np.array([0.36, 0.48, 0.8])
    texel = np.round((n * 0.5 + 0.5) * 255).astype(np.uint8)
    img = np.zeros((8, 8, 4), dtype=np.uint8)
    img[:, :, :3] = texel
    img[:, :, 3] = 255
    t = b.image(img)
    b.material(name="tilted", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[1, 1, 1, 1], metallicFactor=0, roughnessFactor=1),
               normalTexture=g.NormalMaterialTexture(index=t, scale=1.0))
    b.node(mesh=b.mesh([g.Primitive(attributes=g.Attributes(**attrs), indices=b.indices([0, 2, 1, 0, 3, 2], U16), material=0)]))
    b.save_glb(os.path.join(OUT, name))


def alpha_mask():
    b = Builder()
    pos, nrm, uv = b.floats(QUAD_P, g.VEC3, bounds=True), b.floats(QUAD_N, g.VEC3), b.floats(QUAD_UV, g.VEC2)
    idx = b.indices(QUAD_I, U16)
    img = np.full((4, 4, 4), 255, dtype=np.uint8)
    img[:, :2, 3] = 0  # left half transparent
    t = b.image(img)
    pbr = lambda a, tex=None: g.PbrMetallicRoughness(baseColorFactor=[1, 1, 1, a], metallicFactor=0, roughnessFactor=1,
                                                      baseColorTexture=g.TextureInfo(index=tex) if tex is not None else None)
    mats = [b.material(name="alpha_0.3", pbrMetallicRoughness=pbr(0.3), alphaMode=g.MASK, alphaCutoff=0.5),
            b.material(name="alpha_0.7", pbrMetallicRoughness=pbr(0.7), alphaMode=g.MASK, alphaCutoff=0.5),
            b.material(name="half_texture", pbrMetallicRoughness=pbr(1.0, t), alphaMode=g.MASK, alphaCutoff=0.5)]
    for i, m in enumerate(mats):
        b.node(mesh=b.mesh([g.Primitive(attributes=g.Attributes(POSITION=pos, NORMAL=nrm, TEXCOORD_0=uv), indices=idx, material=m)]),
               translation=[1.5 * i, 0, 0])
    b.save_gltf_embedded(os.path.join(OUT, "alpha_mask.gltf"))


def emissive():
    b = Builder()
    b.gltf.extensionsUsed = ["KHR_materials_emissive_strength"]
    b.material(name="panel", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0, 0, 0, 1], metallicFactor=0, roughnessFactor=1),
               emissiveFactor=[1, 0.5, 0.25], extensions={"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}})
    attrs = g.Attributes(POSITION=b.floats(QUAD_P, g.VEC3, bounds=True), NORMAL=b.floats(QUAD_N, g.VEC3))
    b.node(mesh=b.mesh([g.Primitive(attributes=attrs, indices=b.indices(QUAD_I, U16), material=0)]), translation=[-0.5, -0.5, 0])
    b.save_gltf_embedded(os.path.join(OUT, "emissive.gltf"))
    b.save_glb(os.path.join(MODELS, "emissive_panel.glb"))


def material_variants():
    b = Builder()
    b.gltf.extensionsUsed = ["KHR_materials_variants"]
    for name, rgb in (("white", [1, 1, 1]), ("red", [1, 0, 0]), ("blue", [0, 0, 1])):
        b.material(name=name, pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=rgb + [1], metallicFactor=0, roughnessFactor=1))
    b.gltf.extensions = {"KHR_materials_variants": {"variants": [{"name": "red"}, {"name": "blue"}]}}
    attrs = g.Attributes(POSITION=b.floats(QUAD_P, g.VEC3, bounds=True), NORMAL=b.floats(QUAD_N, g.VEC3))
    idx = b.indices(QUAD_I, U16)
    mappings = [[{"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}], [{"material": 2, "variants": [0, 1]}]]
    for i, m in enumerate(mappings):
        prim = g.Primitive(attributes=attrs, indices=idx, material=0, extensions={"KHR_materials_variants": {"mappings": m}})
        b.node(mesh=b.mesh([prim]), translation=[1.5 * i, 0, 0])
    b.save_gltf_embedded(os.path.join(OUT, "variants.gltf"))


def lights():
    b = Builder()
    b.gltf.extensionsUsed = ["KHR_lights_punctual"]
    b.gltf.extensions = {"KHR_lights_punctual": {"lights": [
        {"type": "directional", "color": [1, 0.9, 0.8], "intensity": 2.0, "name": "sun"},
        {"type": "point", "color": [1, 1, 1], "intensity": 10.0, "range": 5.0, "name": "bulb"},
        {"type": "spot", "color": [1, 1, 1], "intensity": 20.0, "name": "torch", "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}]}}
    P = [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]]
    b.material(name="floor", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.7, 0.7, 0.7, 1], metallicFactor=0, roughnessFactor=0.8))
    attrs = g.Attributes(POSITION=b.floats(P, g.VEC3, bounds=True), NORMAL=b.floats([[0, 1, 0]] * 4, g.VEC3))
    b.node(mesh=b.mesh([g.Primitive(attributes=attrs, indices=b.indices([0, 2, 1, 0, 3, 2], U16), material=0)]))
    s = math.sqrt(0.5)
    b.node(rotation=[-s, 0, 0, s], extensions={"KHR_lights_punctual": {"light": 0}})  # -Z turned to -Y: straight down
    b.node(translation=[0, 2, 0], extensions={"KHR_lights_punctual": {"light": 1}})
    # The spot under a parent (T (1, 0, 0), R 90 deg about +Y): its own T (0, 3, 1), R -45 deg about +X
    # points its -Z at (0, -1, -1)/sqrt 2; in the world it sits at (2, 3, 0) and points at (-1, -1, 0)/sqrt 2.
    c45, s45 = math.cos(math.pi / 8), math.sin(math.pi / 8)
    spot = b.node(root=False, translation=[0, 3, 1], rotation=[-s45, 0, 0, c45], extensions={"KHR_lights_punctual": {"light": 2}})
    b.node(translation=[1, 0, 0], rotation=[0, s, 0, s], children=[spot])
    b.gltf.cameras = [g.Camera(type="perspective", perspective=g.Perspective(yfov=0.8, znear=0.1, zfar=50.0, aspectRatio=1.5))]
    b.node(camera=0, translation=[0, 1, 6])  # looking down -Z at the origin's height 1
    b.save_gltf_embedded(os.path.join(OUT, "lights.gltf"))


def sphere(rings=24, segments=48):
    P, N, UV, I = [], [], [], []
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(segments + 1):
            ph = 2 * math.pi * s / segments
            n = [math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)]
            P.append([0.5 * c for c in n])
            N.append(n)
            UV.append([s / segments, r / rings])
    for r in range(rings):
        for s in range(segments):
            a, c = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            if r > 0:  # the pole rows' other triangle has no area
                I += [a, c, a + 1]
            if r < rings - 1:
                I += [a + 1, c, c + 1]
    return P, N, UV, I


def pbr_spheres():
    b = Builder()
    P, N, UV, I = sphere()
    attrs = dict(POSITION=b.floats(P, g.VEC3, bounds=True), NORMAL=b.floats(N, g.VEC3), TEXCOORD_0=b.floats(UV, g.VEC2))
    idx = b.indices(I, U16)
    for row, metal in enumerate((0.0, 1.0)):
        for col, rough in enumerate((0.2, 0.4, 0.6, 0.8, 1.0)):
            colour = [0.9, 0.6, 0.2, 1] if metal else [0.7, 0.1, 0.1, 1]
            m = b.material(name="%s_r%.1f" % ("metal" if metal else "dielectric", rough),
                           pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=colour, metallicFactor=metal, roughnessFactor=rough))
            b.node(mesh=b.mesh([g.Primitive(attributes=g.Attributes(**attrs), indices=idx, material=m)]),
                   translation=[1.2 * col - 2.4, 0.5 + 1.2 * row, 0])
    b.save_glb(os.path.join(MODELS, "pbr_spheres.glb"))


def specular_spheres():
    b = Builder()
    b.gltf.extensionsUsed = ["KHR_materials_specular", "KHR_materials_ior"]
    P, N, UV, I = sphere()
    attrs = dict(POSITION=b.floats(P, g.VEC3, bounds=True), NORMAL=b.floats(N, g.VEC3), TEXCOORD_0=b.floats(UV, g.VEC2))
    idx = b.indices(I, U16)
    tops = [({"specularColorFactor": [1, 0, 0]}, None), ({"specularColorFactor": [0, 1, 0]}, None),
            ({"specularColorFactor": [0, 0, 1]}, None), ({"specularColorFactor": [2, 1.6, 0.8]}, None),
            ({"specularColorFactor": [1.0, 0.77, 0.34]}, {"ior": 0})]
    for col in range(5):
        for row in range(2):
            spec, ior = ({"specularFactor": 0.25 * col}, None) if row == 0 else tops[col]
            ext = {"KHR_materials_specular": spec}
            if ior:
                ext["KHR_materials_ior"] = ior
            base = [0.05, 0.05, 0.05, 1] if ior else [0.5, 0.5, 0.5, 1]
            m = b.material(name="specular_%d_%d" % (row, col), extensions=ext,
                           pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=base, metallicFactor=0.0, roughnessFactor=0.3))
            b.node(mesh=b.mesh([g.Primitive(attributes=g.Attributes(**attrs), indices=idx, material=m)]),
                   translation=[1.2 * col - 2.4, 0.5 + 1.2 * row, 0])
    b.save_glb(os.path.join(MODELS, "specular_spheres.glb"))


def clearcoat_spheres():
    b = Builder()
    b.gltf.extensionsUsed = ["KHR_materials_clearcoat"]
    P, N, UV, I = sphere()
    attrs = dict(POSITION=b.floats(P, g.VEC3, bounds=True), NORMAL=b.floats(N, g.VEC3), TEXCOORD_0=b.floats(UV, g.VEC2))
    idx = b.indices(I, U16)
    for col in range(5):
        for row, coat_roughness in enumerate((0.05, 0.3, 0.6)):
            ext = {"KHR_materials_clearcoat": {"clearcoatFactor": 0.25 * col, "clearcoatRoughnessFactor": coat_roughness}}
            m = b.material(name="clearcoat_%d_%d" % (row, col), extensions=ext,
                           pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.6, 0.04, 0.03, 1], metallicFactor=0.0,
                                                                       roughnessFactor=0.5))
            b.node(mesh=b.mesh([g.Primitive(attributes=g.Attributes(**attrs), indices=idx, material=m)]),
                   translation=[1.2 * col - 2.4, 0.5 + 1.2 * row, 0])
    b.save_glb(os.path.join(MODELS, "clearcoat_spheres.glb"))


def box(sx, sy, sz):
    """An axis-aligned box of size sx x sy x sz centred on the origin: 6 faces of 4 vertices, outward
    normals, counter-clockwise from outside."""
    P, N, UV, I = [], [], [], []
    h = [sx / 2, sy / 2, sz / 2]
    for axis in range(3):
        for sign in (1, -1):
            n = [0, 0, 0]
            n[axis] = sign
            u, v = (axis + 1) % 3, (axis + 2) % 3
            if sign < 0:
                u, v = v, u
            base = len(P)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0, 0, 0]
                p[axis] = sign * h[axis]
                p[u] = a * h[u]
                p[v] = b * h[v]
                P.append(p)
                N.append(n)
                UV.append([(a + 1) / 2, (1 - b) / 2])
            I += [base, base + 1, base + 2, base, base + 2, base + 3]
    return P, N, UV, I


def transmission_glass():
    b = Builder()
    b.gltf.extensionsUsed = ["KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior"]
    # The wall: 16 vertical black and white stripes over a red-green-blue band, to see the refraction bend them.
    stripes = np.zeros((256, 256, 4), dtype=np.uint8)
    stripes[..., 3] = 255
    for x in range(256):
        stripes[:, x, :3] = 230 if (x // 16) % 2 == 0 else 20
    stripes[112:144, :, :3] = [[200, 30, 30]] * 256
    stripes[144:176, :, :3] = [[30, 170, 40]] * 256
    stripes[80:112, :, :3] = [[40, 60, 200]] * 256
    wall_texture = b.image(stripes)
    wall = b.material(name="striped_wall", pbrMetallicRoughness=g.PbrMetallicRoughness(
        baseColorTexture=g.TextureInfo(index=wall_texture), metallicFactor=0.0, roughnessFactor=0.8))
    P = [[-2, 0, 0], [2, 0, 0], [2, 2.5, 0], [-2, 2.5, 0]]
    attrs = dict(POSITION=b.floats(P, g.VEC3, bounds=True), NORMAL=b.floats(QUAD_N, g.VEC3), TEXCOORD_0=b.floats(QUAD_UV, g.VEC2))
    b.node(mesh=b.mesh([g.Primitive(attributes=g.Attributes(**attrs), indices=b.indices(QUAD_I, U16), material=wall)]),
           translation=[0, -0.2, -1.5])

    def glass(name, rough, volume):
        return b.material(name=name, extensions={"KHR_materials_transmission": {"transmissionFactor": 1.0},
                                                 "KHR_materials_volume": volume, "KHR_materials_ior": {"ior": 1.5}},
                          pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[1, 1, 1, 1], metallicFactor=0.0,
                                                                      roughnessFactor=rough))

    def solid(shape, material, translation):
        P, N, UV, I = shape
        attrs = dict(POSITION=b.floats(P, g.VEC3, bounds=True), NORMAL=b.floats(N, g.VEC3), TEXCOORD_0=b.floats(UV, g.VEC2))
        b.node(mesh=b.mesh([g.Primitive(attributes=g.Attributes(**attrs), indices=b.indices(I, U16), material=material)]),
               translation=translation)

    Ps, Ns, UVs, Is = sphere()
    solid((Ps, Ns, UVs, Is), glass("clear_glass", 0.0, {"thicknessFactor": 1.0}), [-1, 0.6, 0])
    solid(box(0.9, 1.0, 0.2), glass("tinted_slab", 0.05, {"thicknessFactor": 0.2, "attenuationColor": [0.95, 0.45, 0.15],
                                                          "attenuationDistance": 0.1}), [0.25, 0.6, 0.2])
    solid(box(0.6, 0.9, 0.02), glass("frosted_pane", 0.35, {"thicknessFactor": 0.0}), [1.3, 0.6, 0.3])
    b.save_glb(os.path.join(MODELS, "transmission_glass.glb"))


def viking_room():
    src = os.path.join(ROOT, "..", "shared", "assets", "viking-room")
    if not os.path.exists(os.path.join(src, "viking_room.obj")):
        print("no ../shared/assets/viking-room: viking_room.glb not made")
        return
    V, T, N, verts, I, seen = [], [], [], [], [], {}
    for line in open(os.path.join(src, "viking_room.obj")):
        p = line.split()
        if not p:
            continue
        if p[0] == "v":
            V.append([float(x) for x in p[1:4]])
        elif p[0] == "vt":
            T.append([float(p[1]), 1.0 - float(p[2])])  # OBJ v up, glTF v down
        elif p[0] == "vn":
            N.append([float(x) for x in p[1:4]])
        elif p[0] == "f":
            corners = []
            for c in p[1:]:
                key = tuple(int(x) - 1 for x in c.split("/"))
                if key not in seen:
                    seen[key] = len(verts)
                    verts.append(key)
                corners.append(seen[key])
            for k in range(1, len(corners) - 1):
                I += [corners[0], corners[k], corners[k + 1]]
    b = Builder()
    attrs = dict(POSITION=b.floats([V[v] for v, _, _ in verts], g.VEC3, bounds=True),
                 TEXCOORD_0=b.floats([T[t] for _, t, _ in verts], g.VEC2), NORMAL=b.floats([N[n] for _, _, n in verts], g.VEC3))
    img = np.asarray(Image.open(os.path.join(src, "viking_room.png")).convert("RGBA"))
    t = b.image(img)
    b.material(name="Texture1", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorTexture=g.TextureInfo(index=t), metallicFactor=0, roughnessFactor=0.8),
               doubleSided=True)
    s = math.sqrt(0.5)
    b.node(mesh=b.mesh([g.Primitive(attributes=g.Attributes(**attrs), indices=b.indices(I, U32), material=0)]), rotation=[-s, 0, 0, s])
    b.save_glb(os.path.join(MODELS, "viking_room.glb"))


def box_accessors(b):
    """A 0.5 m box's positions, normals and indices (a quad a face, counter-clockwise seen from
    outside; material 0); returns a function that makes a mesh entry of them."""
    P, N, I = [], [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = [0.0] * 3, [0.0] * 3
            u[(axis + 1) % 3], v[(axis + 2) % 3] = 1.0, 1.0
            if sign < 0:
                u, v = v, u  # counter-clockwise seen from outside
            base = len(P)
            for cu, cv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                P.append([0.25 * (n[k] + cu * u[k] + cv * v[k]) for k in range(3)])
                N.append(n)
            I += [base, base + 1, base + 2, base, base + 2, base + 3]
    box_attrs = dict(POSITION=b.floats(P, g.VEC3, bounds=True), NORMAL=b.floats(N, g.VEC3))
    box_indices = b.indices(I, U16)
    return lambda: b.mesh([g.Primitive(attributes=g.Attributes(**box_attrs), indices=box_indices, material=0)])


def floor_node(b):
    """A 6 m floor (material 1) as a root node."""
    F = [[-3, 0, -3], [3, 0, -3], [3, 0, 3], [-3, 0, 3]]
    floor = b.mesh([g.Primitive(attributes=g.Attributes(POSITION=b.floats(F, g.VEC3, bounds=True), NORMAL=b.floats([[0, 1, 0]] * 4, g.VEC3)),
                                indices=b.indices([0, 2, 1, 0, 3, 2], U16), material=1)])
    b.node(mesh=floor)


def node_reuse(expanded, name):
    """One box mesh drawn by five nodes (turned, scaled, one under a turned parent, one mirrored) and a
    floor drawn once; `expanded`: the same file with one mesh entry per node (the same accessors), so
    nothing is drawn twice. lightpass stores the reused box once; both render the same image."""
    b = Builder()
    b.material(name="box", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.8, 0.5, 0.2, 1], metallicFactor=0, roughnessFactor=0.5),
               doubleSided=False)
    b.material(name="floor", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.6, 0.6, 0.6, 1], metallicFactor=0, roughnessFactor=0.8))
    box_mesh = box_accessors(b)
    shared = box_mesh()
    mesh_of = (lambda: box_mesh()) if expanded else (lambda: shared)
    floor_node(b)
    s = math.sqrt(0.5)
    c30, s30 = math.cos(math.radians(15)), math.sin(math.radians(15))
    b.node(mesh=mesh_of(), translation=[-1.0, 0.25, 0.0])
    b.node(mesh=mesh_of(), translation=[0.0, 0.5, -0.75], rotation=[0, s30, 0, c30], scale=[1.5, 2.0, 1.0])
    child = b.node(root=False, mesh=mesh_of(), translation=[0.75, 0.0, 0.0], rotation=[s30, 0, 0, c30])
    b.node(translation=[0.5, 0.3, 0.75], rotation=[0, s, 0, s], children=[child])
    b.node(mesh=mesh_of(), translation=[1.5, 0.25, -0.5], scale=[-1.0, 1.0, 1.0])  # mirrors: stays baked
    b.node(mesh=mesh_of(), translation=[-1.5, 0.5, 1.0], rotation=[s30, s30, 0, math.sqrt(1 - 2 * s30 * s30)])
    b.save_gltf_embedded(os.path.join(OUT, name))


def gpu_instancing(expanded, name):
    """EXT_mesh_gpu_instancing: the node_reuse box drawn at five instances (TRANSLATION, ROTATION,
    SCALE accessors) under a node moved and turned, over a floor; `expanded`: the same placements
    written as child nodes of that node, one mesh entry each."""
    b = Builder()
    b.material(name="box", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.3, 0.5, 0.8, 1], metallicFactor=0, roughnessFactor=0.5),
               doubleSided=False)
    b.material(name="floor", pbrMetallicRoughness=g.PbrMetallicRoughness(baseColorFactor=[0.6, 0.6, 0.6, 1], metallicFactor=0, roughnessFactor=0.8))
    box_mesh = box_accessors(b)
    floor_node(b)
    c, s = math.cos(math.radians(20)), math.sin(math.radians(20))
    T = [[-1.0, 0.25, 0.0], [0.0, 0.5, -0.75], [1.0, 0.3, 0.5], [-0.5, 0.4, 1.0], [1.2, 0.25, -0.8]]
    R = [[0, 0, 0, 1], [0, s, 0, c], [s, 0, 0, c], [0, 0, s, c], [0, -s, 0, c]]
    S = [[1, 1, 1], [1.5, 2.0, 1.0], [1, 1, 1], [0.8, 0.8, 0.8], [1.0, 1.2, 1.0]]
    h = math.sqrt(0.5)
    parent = dict(translation=[0.2, 0.0, -0.1], rotation=[0, math.sin(math.radians(10)), 0, math.cos(math.radians(10))])
    if expanded:
        children = [b.node(root=False, mesh=box_mesh(), translation=t, rotation=r, scale=sc) for t, r, sc in zip(T, R, S)]
        b.node(children=children, **parent)
    else:
        b.gltf.extensionsUsed = ["EXT_mesh_gpu_instancing"]
        b.node(mesh=box_mesh(), extensions={"EXT_mesh_gpu_instancing": {"attributes": {
            "TRANSLATION": b.floats(T, g.VEC3), "ROTATION": b.floats(R, g.VEC4), "SCALE": b.floats(S, g.VEC3)}}}, **parent)
    b.save_gltf_embedded(os.path.join(OUT, name))


forms()
hierarchy()
normal_plane(True, "normal_plane.glb")
normal_plane(False, "normal_plane_notangent.glb")
alpha_mask()
emissive()
material_variants()
lights()
pbr_spheres()
specular_spheres()
clearcoat_spheres()
transmission_glass()
viking_room()
node_reuse(False, "node_reuse.gltf")
node_reuse(True, "node_reuse_expanded.gltf")
gpu_instancing(False, "gpu_instancing.gltf")
gpu_instancing(True, "gpu_instancing_expanded.gltf")
print("wrote", OUT, "and", os.path.join(MODELS, "pbr_spheres.glb"))
