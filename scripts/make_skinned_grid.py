#!/usr/bin/env python3
"""make_skinned_grid.py OUT.gltf [VERTICES]: a glTF (OUT.gltf + OUT.bin, no dependencies) of one square
grid of about VERTICES vertices (default 102400), 1 m wide and 4 m tall in the XY plane facing +Z,
skinned to a chain of 8 joints up +Y and carrying
2 morph targets, with one LINEAR clip of 2 s that bends every joint about X and moves both morph
weights: every vertex is morphed and skinned every frame. Each vertex follows the two joints nearest
to it along the chain (weights summing to 1; JOINTS_0 unsigned bytes, WEIGHTS_0 floats). Target 0
raises a bump in the middle (POSITION and NORMAL deltas), target 1 a ripple across (POSITION).
bench/animation.sh renders it to measure what skinning and morphing cost per frame; the small
tests/data/gltf/skinned_grid.gltf (256 vertices, the CLI tests) is `make_skinned_grid.py
tests/data/gltf/skinned_grid.gltf 256`."""
import json, math, os, struct, sys

from gltf_buffer import GltfBuffer

out = sys.argv[1]
vertices = int(sys.argv[2]) if len(sys.argv) > 2 else 102400
side = max(2, int(math.sqrt(vertices)))
joints = 8
length = 4.0  # metres up +Y, the chain's length
buffer = GltfBuffer()
blob, views, accessors, add = buffer.blob, buffer.views, buffer.accessors, buffer.add


positions, normals, joint_ids, weights, bump, bump_normals, ripple = [], [], [], [], [], [], []
segment = length / joints
for j in range(side):
    for i in range(side):
        x, y = (i / (side - 1) - 0.5) * 1.0, j / (side - 1) * length
        positions += [x, y, 0.0]
        normals += [0.0, 0.0, 1.0]
        # The two joints whose centres (k + 0.5) * segment are nearest along y, blended linearly.
        f = min(max(y / segment - 0.5, 0.0), joints - 1.0)
        k0 = min(int(f), joints - 2)
        w1 = min(max(f - k0, 0.0), 1.0)
        joint_ids += [k0, k0 + 1, 0, 0]
        weights += [1.0 - w1, w1, 0.0, 0.0]
        r2 = (x * x + (y - length / 2) ** 2) / 0.5
        h = 0.3 * math.exp(-r2)
        bump += [0.0, 0.0, h]
        # The bump's slopes: the normal's change, (-dh/dx, -dh/dy, 0) to first order.
        bump_normals += [2 * x / 0.5 * h, 2 * (y - length / 2) / 0.5 * h, 0.0]
        ripple += [0.0, 0.0, 0.1 * math.sin(8 * x)]
count = side * side
indices = []
for j in range(side - 1):
    for i in range(side - 1):
        a = j * side + i
        indices += [a, a + 1, a + side, a + 1, a + side + 1, a + side]  # counter-clockwise seen from +Z
pos = add(struct.pack(f"<{3 * count}f", *positions), "VEC3", count, target=34962,
          minmax=([-0.5, 0.0, 0.0], [0.5, length, 0.0]))
nrm = add(struct.pack(f"<{3 * count}f", *normals), "VEC3", count, target=34962)
jnt = add(struct.pack(f"<{4 * count}B", *joint_ids), "VEC4", count, component=5121, target=34962)
wgt = add(struct.pack(f"<{4 * count}f", *weights), "VEC4", count, target=34962)
t0p = add(struct.pack(f"<{3 * count}f", *bump), "VEC3", count,
          minmax=([0.0, 0.0, min(bump[2::3])], [0.0, 0.0, max(bump[2::3])]))
t0n = add(struct.pack(f"<{3 * count}f", *bump_normals), "VEC3", count)
t1p = add(struct.pack(f"<{3 * count}f", *ripple), "VEC3", count,
          minmax=([0.0, 0.0, min(ripple[2::3])], [0.0, 0.0, max(ripple[2::3])]))
idx = add(struct.pack(f"<{len(indices)}I", *indices), "SCALAR", len(indices), component=5125, target=34963)

# Joint k at y = k * segment, each the previous one's child (k = 0 a root); inverse bind: translate(0, -k segment, 0).
nodes = [{"mesh": 0, "skin": 0}]
for k in range(joints):
    node = {"translation": [0.0, segment if k > 0 else 0.0, 0.0]}
    if k + 1 < joints:
        node["children"] = [k + 2]
    nodes.append(node)
ibm = []
for k in range(joints):
    ibm += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -k * segment, 0, 1]
ibm_accessor = add(struct.pack(f"<{16 * joints}f", *ibm), "MAT4", joints)

keys = 9
times = [2.0 * k / (keys - 1) for k in range(keys)]
time_accessor = add(struct.pack(f"<{keys}f", *times), "SCALAR", keys, minmax=([0.0], [2.0]))
channels, samplers = [], []
for k in range(1, joints):
    rotations = []
    for t in times:
        angle = 0.25 * math.sin(math.pi * t + 0.3 * k)  # the chain curls and uncurls over the 2 s clip
        rotations += [math.sin(angle / 2), 0.0, 0.0, math.cos(angle / 2)]
    samplers.append({"input": time_accessor, "output": add(struct.pack(f"<{4 * keys}f", *rotations), "VEC4", keys),
                     "interpolation": "LINEAR"})
    channels.append({"sampler": len(samplers) - 1, "target": {"node": k + 1, "path": "rotation"}})
morph = []
for t in times:
    morph += [0.5 + 0.5 * math.sin(math.pi * t), 0.5 + 0.5 * math.cos(math.pi * t)]
samplers.append({"input": time_accessor, "output": add(struct.pack(f"<{2 * keys}f", *morph), "SCALAR", 2 * keys),
                 "interpolation": "LINEAR"})
channels.append({"sampler": len(samplers) - 1, "target": {"node": 0, "path": "weights"}})

bin_name = os.path.splitext(os.path.basename(out))[0] + ".bin"
doc = {
    "asset": {"version": "2.0", "generator": "lightpass scripts/make_skinned_grid.py"},
    "buffers": [{"byteLength": len(blob), "uri": bin_name}],
    "bufferViews": views, "accessors": accessors,
    "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm, "JOINTS_0": jnt, "WEIGHTS_0": wgt},
                                "targets": [{"POSITION": t0p, "NORMAL": t0n}, {"POSITION": t1p}], "indices": idx}],
                "weights": [0.5, 0.5]}],
    "nodes": nodes, "skins": [{"joints": list(range(1, joints + 1)), "inverseBindMatrices": ibm_accessor, "skeleton": 1}],
    "scenes": [{"nodes": [0, 1]}], "scene": 0,
    "animations": [{"name": "curl_and_morph", "channels": channels, "samplers": samplers}],
}
with open(os.path.join(os.path.dirname(os.path.abspath(out)), bin_name), "wb") as f:
    f.write(blob)
with open(out, "w") as f:
    json.dump(doc, f)
print(f"{out}: {count} vertices skinned to {joints} joints, 2 morph targets, {len(indices) // 3} triangles")
