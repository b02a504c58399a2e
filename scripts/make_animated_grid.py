#!/usr/bin/env python3
"""make_animated_grid.py OUT.gltf [VERTICES]: a glTF (OUT.gltf + OUT.bin, no dependencies) of a wavy
grid split over 16 nodes, about VERTICES vertices in all (default 102400), with one LINEAR clip of
2 s that turns every node about its own axis and bobs it up and down: every vertex moves every frame.
bench/animation.sh renders it to measure what posing an animated model costs per frame; the small
tests/data/gltf/animated_grid.gltf (256 vertices, the CLI tests) is `make_animated_grid.py
tests/data/gltf/animated_grid.gltf 256`."""
import json, math, os, struct, sys

from gltf_buffer import GltfBuffer

out = sys.argv[1]
vertices = int(sys.argv[2]) if len(sys.argv) > 2 else 102400
nodes = 16
side = max(2, int(math.sqrt(vertices / nodes)))  # vertices per side of one node's grid
buffer = GltfBuffer()
blob, views, accessors, add = buffer.blob, buffer.views, buffer.accessors, buffer.add


positions, normals = [], []
for j in range(side):
    for i in range(side):
        x, z = i / (side - 1) - 0.5, j / (side - 1) - 0.5
        y = 0.05 * math.sin(12 * x) * math.cos(12 * z)
        positions += [x, y, z]
        dx, dz = 0.6 * math.cos(12 * x) * math.cos(12 * z), -0.6 * math.sin(12 * x) * math.sin(12 * z)
        n = (-dx, 1.0, -dz)
        length = math.sqrt(sum(c * c for c in n))
        normals += [c / length for c in n]
indices = []
for j in range(side - 1):
    for i in range(side - 1):
        a = j * side + i
        indices += [a, a + side, a + 1, a + 1, a + side, a + side + 1]
count = side * side
pos = add(struct.pack(f"<{3 * count}f", *positions), "VEC3", count, target=34962,
          minmax=([min(positions[0::3]), min(positions[1::3]), min(positions[2::3])],
                  [max(positions[0::3]), max(positions[1::3]), max(positions[2::3])]))
nrm = add(struct.pack(f"<{3 * count}f", *normals), "VEC3", count, target=34962)
idx = add(struct.pack(f"<{len(indices)}I", *indices), "SCALAR", len(indices), component=5125, target=34963)

keys = 9
times = [2.0 * k / (keys - 1) for k in range(keys)]
time_accessor = add(struct.pack(f"<{keys}f", *times), "SCALAR", keys, minmax=([0.0], [2.0]))
gltf_nodes, channels, samplers = [], [], []
for n in range(nodes):
    cx, cz = (n % 4) * 1.2 - 1.8, (n // 4) * 1.2 - 1.8
    rotations, translations = [], []
    for k, t in enumerate(times):
        angle = math.pi * t * (1 if n % 2 else -1)  # a whole turn over the 2 s clip
        rotations += [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)]
        translations += [cx, 0.25 * math.sin(math.pi * t + n), cz]
    r = add(struct.pack(f"<{4 * keys}f", *rotations), "VEC4", keys)
    tr = add(struct.pack(f"<{3 * keys}f", *translations), "VEC3", keys)
    samplers += [{"input": time_accessor, "output": r, "interpolation": "LINEAR"},
                 {"input": time_accessor, "output": tr, "interpolation": "LINEAR"}]
    channels += [{"sampler": 2 * n, "target": {"node": n, "path": "rotation"}},
                 {"sampler": 2 * n + 1, "target": {"node": n, "path": "translation"}}]
    gltf_nodes.append({"mesh": 0, "translation": [cx, 0.0, cz]})

bin_name = os.path.splitext(os.path.basename(out))[0] + ".bin"
doc = {
    "asset": {"version": "2.0", "generator": "lightpass scripts/make_animated_grid.py"},
    "buffers": [{"byteLength": len(blob), "uri": bin_name}],
    "bufferViews": views, "accessors": accessors,
    "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm}, "indices": idx}]}],
    "nodes": gltf_nodes, "scenes": [{"nodes": list(range(nodes))}], "scene": 0,
    "animations": [{"name": "turn_and_bob", "channels": channels, "samplers": samplers}],
}
with open(os.path.join(os.path.dirname(os.path.abspath(out)), bin_name), "wb") as f:
    f.write(blob)
with open(out, "w") as f:
    json.dump(doc, f)
print(f"{out}: {nodes} nodes x {count} vertices = {nodes * count} vertices, {nodes * len(indices) // 3} triangles")
