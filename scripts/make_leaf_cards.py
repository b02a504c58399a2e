#!/usr/bin/env python3
"""make_leaf_cards.py [OUT]: writes models/leaf_cards.gltf (default), a canopy of alpha-tested leaf
cards for scenes/leaf-cards.json and bench/alpha_shadow_cost.sh. Standard library only (the PNG is
written with zlib); the generated file is committed.

One mesh, a 0.6 m square card (uv 0..1, doubleSided) whose material is alphaMode MASK, cutoff 0.5,
with a 64 x 64 base colour texture: a green leaf (an ellipse along the card's diagonal, alpha 255)
with a midrib gap and holes (alpha 0), transparent outside. CARDS nodes instance it in a canopy
(a jittered grid of CARDS_X x CARDS_Z columns, CARDS_Y layers), each turned by a pseudo-random
rotation from a fixed seed, so the file is the same every time.
"""
import base64, json, math, os, random, struct, sys, zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "models", "leaf_cards.gltf")
CARDS_X, CARDS_Y, CARDS_Z = 8, 3, 8
SIDE = 0.6
TEX = 64


def png(width, height, rgba):
    raw = b"".join(b"\x00" + bytes(rgba[y * width * 4:(y + 1) * width * 4]) for y in range(height))
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def leaf_texture():
    rgba = []
    for y in range(TEX):
        for x in range(TEX):
            u, v = (x + 0.5) / TEX * 2 - 1, (y + 0.5) / TEX * 2 - 1
            a, b = (u + v) / math.sqrt(2), (u - v) / math.sqrt(2)  # along and across the diagonal
            inside = (a / 0.95) ** 2 + (b / 0.45) ** 2 < 1.0
            midrib = abs(b) < 0.03
            hole = any((a - c) ** 2 + (b - d) ** 2 < 0.012 for c, d in ((0.35, 0.18), (-0.3, -0.16), (0.05, 0.22)))
            opaque = inside and not midrib and not hole
            shade = 0.75 + 0.25 * (1 - abs(b) / 0.45) if inside else 0.0
            rgba += [int(60 * shade), int(150 * shade), int(50 * shade), 255 if opaque else 0]
    return png(TEX, TEX, rgba)


def quaternion(rng):
    # A uniformly random rotation (Shoemake).
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    return [math.sqrt(1 - u1) * math.sin(2 * math.pi * u2), math.sqrt(1 - u1) * math.cos(2 * math.pi * u2),
            math.sqrt(u1) * math.sin(2 * math.pi * u3), math.sqrt(u1) * math.cos(2 * math.pi * u3)]


def main():
    h = SIDE / 2
    positions = [(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)]
    normals = [(0, 0, 1)] * 4
    uvs = [(0, 1), (1, 1), (1, 0), (0, 0)]
    indices = [0, 1, 2, 0, 2, 3]
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    blob += b"".join(struct.pack("<3f", *n) for n in normals)
    blob += b"".join(struct.pack("<2f", *t) for t in uvs)
    blob += struct.pack("<6H", *indices) + b"\x00\x00"
    rng = random.Random(20261207)
    nodes = []
    for iy in range(CARDS_Y):
        for iz in range(CARDS_Z):
            for ix in range(CARDS_X):
                t = [(ix - (CARDS_X - 1) / 2) * 0.45 + rng.uniform(-0.15, 0.15), iy * 0.45 + rng.uniform(-0.15, 0.15),
                     (iz - (CARDS_Z - 1) / 2) * 0.45 + rng.uniform(-0.15, 0.15)]
                nodes.append({"mesh": 0, "translation": [round(c, 4) for c in t],
                              "rotation": [round(c, 6) for c in quaternion(rng)]})
    doc = {
        "asset": {"version": "2.0", "generator": "lightpass scripts/make_leaf_cards.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": [{"name": "leaf_card", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                          "indices": 3, "material": 0}]}],
        "materials": [{"name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0,
                                                "roughnessFactor": 0.8}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(leaf_texture()).decode()}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48, "target": 34962},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 32, "target": 34962},
                        {"buffer": 0, "byteOffset": 128, "byteLength": 12, "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-h, -h, 0], "max": [h, h, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
                      {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }
    with open(OUT, "w") as f:
        json.dump(doc, f, separators=(",", ":"))
        f.write("\n")
    print(f"{OUT}: {len(nodes)} cards, {os.path.getsize(OUT)} bytes")


main()
