#!/usr/bin/env python3
"""Writes a large instanced scene for measuring how a frame scales with what is seen, not with what
is stored (docs/performance.md, "Big scenes").

    scripts/make_big_scene.py --triangles 100M --out big_100m.json [--visible-triangles 5M]
                              [--model dragon|bunny|buddha|sphere] [--still]

The scene is one mesh stored once and drawn many times (models[].instances):
  * copies in rows that fill the camera's view, about --visible-triangles in all;
  * the rest of the copies, up to --triangles, hidden: packed behind a wall that closes the view
    (occluded) and behind the camera (outside the frustum), so that two scenes of different
    --triangles with the same --visible-triangles show the same image;
  * unless --still: a sun that turns ("turn") and eight of the copies in view spinning ("spin"), so that neither the cascade cache nor any other cache can hold from one frame to the next.
The model comes from ../shared/assets (the Stanford scans) when it is there; "sphere" (4,096 triangles,
bundled) needs nothing. Paths in the scene are written relative to the output file. Deterministic.
"""
import argparse
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
ASSETS = os.path.normpath(os.path.join(ROOT, "..", "shared", "assets"))

# Each model: its file under ASSETS (None: a primitive), triangles, the scale that makes it about a
# metre wide, and the translation that stands it on y = 0 at the origin.
MODELS = {
    "dragon": ("stanford-dragon/dragon.obj", 100000, 0.1, [0.0, 0.0, 0.0]),
    "bunny": ("stanford-bunny/stanford-bunny.obj", 69451, 6.0, [0.0, -0.2, 0.0]),
    "buddha": ("stanford-happy-buddha/buddha.obj", 112876, 0.012, [0.0, 0.0, 0.0]),
    "sphere": (None, 4096, 1.0, [0.0, 0.5, 0.0]),
}


def count(text):
    """'100M', '5m', '250k', '12345' -> an integer."""
    t = text.strip().lower()
    scale = {"k": 1e3, "m": 1e6, "g": 1e9}.get(t[-1:], 1)
    value = float(t[:-1] if scale != 1 else t) * scale
    if not (value >= 1):
        raise argparse.ArgumentTypeError(f"{text}: expected a positive count such as 10M")
    return int(value)


def grid(n, spacing, origin, columns):
    """n placements on a grid of `columns` across (x) and as many rows as needed (-z), from origin."""
    out = []
    for i in range(n):
        r, c = divmod(i, columns)
        x = origin[0] + (c - (columns - 1) / 2.0) * spacing
        z = origin[2] - r * spacing
        out.append({"translate": [round(x, 3), origin[1], round(z, 3)], "rotate": [0, (i * 47) % 360, 0]})
    return out


def field(n, spacing, camera_z, nearest, half_angle):
    """n placements in rows that fill the view: row r lies nearest + r x spacing ahead of the camera
    (looking down -z) and holds as many copies as fit within half_angle of the view's axis."""
    out, r = [], 0
    while len(out) < n:
        ahead = nearest + r * spacing
        columns = max(1, int(2 * ahead * math.tan(half_angle) / spacing))
        for c in range(min(columns, n - len(out))):
            x = (c - (columns - 1) / 2.0) * spacing
            out.append({"translate": [round(x, 3), 0.0, round(camera_z - ahead, 3)], "rotate": [0, (len(out) * 47) % 360, 0]})
        r += 1
    return out, nearest + (r - 1) * spacing


def build(args):
    file, tris, scale, lift = MODELS[args.model]
    out_dir = os.path.dirname(os.path.abspath(args.out))
    model = {"scale": scale, "translate": lift,
             "material": {"diffuse": [0.7, 0.66, 0.6], "specular": [0.3, 0.3, 0.3], "shininess": 96}}
    if file is None:
        model["primitive"] = "sphere"
    else:
        path = os.path.join(ASSETS, file)
        if not os.path.exists(path):
            sys.exit(f"make_big_scene.py: {path}: not found (--model sphere needs no assets)")
        model["obj"] = os.path.relpath(path, out_dir)

    total = max(1, args.triangles // tris)
    visible = max(1, min(total, args.visible_triangles // tris))
    spinning = 0 if args.still else min(8, visible)
    hidden = total - visible
    spacing = 1.6
    camera_z, fov = 3.0, 50.0
    # The horizontal half-angle of a 16:9 view less a margin, so that every copy in view is whole.
    half_angle = 0.85 * math.atan(math.tan(math.radians(fov / 2)) * 16 / 9)
    places, farthest = field(visible, spacing, camera_z, 4.0, half_angle)
    # The first (nearest, central) places hold the spinning copies.
    spin_places, places = places[:spinning], places[spinning:]
    columns = max(4, int(2 * farthest * math.tan(half_angle) / spacing) + 1)
    # The wall stands past the farthest row, as wide as the view there and taller than the camera sees
    # over it; the hidden copies fill the ground behind it and behind the camera.
    wall_z = camera_z - farthest - 2.0
    wall_half = (camera_z - wall_z) * math.tan(half_angle / 0.85) + 2 * spacing
    depth = camera_z - wall_z
    models = [
        {"name": "ground", "primitive": "plane", "scale": [round(2 * wall_half, 3), 1, round(2 * depth + 8, 3)],
         "translate": [0, 0, round(camera_z - depth / 2, 3)],
         "material": {"diffuse": [0.5, 0.5, 0.48], "specular": [0.04, 0.04, 0.04], "shininess": 16}},
        {"name": "wall", "primitive": "cube", "scale": [round(2 * wall_half, 3), round(wall_half, 3), 1.0],
         "translate": [0, round(wall_half / 2, 3), round(wall_z, 3)],
         "material": {"diffuse": [0.6, 0.58, 0.55], "specular": [0.04, 0.04, 0.04], "shininess": 16}},
    ]
    if places:
        models.append(dict(model, name="visible", instances=places))
    if hidden > 0:
        behind_wall = (hidden + 1) // 2
        behind_camera = hidden - behind_wall
        hidden_columns = max(columns, int(math.ceil(math.sqrt(behind_wall))))
        # Rows widening with distance, within the angle the wall covers as the camera sees it.
        wall_angle = math.atan2(wall_half - spacing, camera_z - wall_z)
        behind, _ = field(behind_wall, spacing, camera_z, camera_z - wall_z + 2.0, wall_angle)
        models.append(dict(model, name="hidden_behind_wall", instances=behind))
        if behind_camera > 0:
            # Behind the camera, facing away: the grid runs toward +z from 3 m behind it.
            placements = grid(behind_camera, spacing, [0.0, 0.0, 0.0], hidden_columns)
            for p in placements:
                p["translate"][2] = round(camera_z + 3.0 - p["translate"][2], 3)
            models.append(dict(model, name="hidden_behind_camera", instances=placements))
    for k, place in enumerate(spin_places):
        x, _, z = place["translate"]
        models.append(dict(model, name=f"spinning_{k}", translate=[round(x + lift[0], 3), lift[1], round(z + lift[2], 3)],
                           spin={"axis": [0, 1, 0], "speed": round(0.6 + 0.1 * k, 2)}))
    sun = {"type": "directional", "direction": [-0.4, -1.0, -0.35], "color": [1.0, 0.96, 0.9], "intensity": 3.0,
           "shadows": True}
    if not args.still:
        sun["turn"] = {"axis": [0, 1, 0], "speed": 0.2}
    stored = tris
    drawn = total * tris
    description = (f"make_big_scene.py --triangles {args.triangles} --visible-triangles {args.visible_triangles} "
                   f"--model {args.model}{' --still' if args.still else ''}: one {args.model} ({tris} triangles) "
                   f"stored once and drawn {total} times ({drawn} triangles): {visible} in view ({spinning} "
                   f"of them spinning), {hidden} hidden behind a wall and behind the camera"
                   f"{'' if args.still else '; the sun turns'}.")
    return {
        "description": description,
        "camera": {"position": [0.0, 2.2, camera_z], "target": [0.0, 0.3, round(camera_z - farthest / 2 - 2.0, 3)],
                   "fov": fov, "near": 0.1, "far": round(depth + 5.0, 3)},
        "models": models,
        "lights": [sun],
        "environment": {"color": [0.35, 0.45, 0.6], "intensity": 1.0},
        "ambient": [0.05, 0.05, 0.06],
    }, {"stored_triangles": stored, "drawn_triangles": drawn, "instances": total}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--triangles", type=count, required=True, help="triangles drawn in all (10M, 100M, ...)")
    parser.add_argument("--visible-triangles", type=count, default=count("5M"),
                        help="triangles of the copies in view (default 5M)")
    parser.add_argument("--model", choices=sorted(MODELS), default="dragon")
    parser.add_argument("--still", action="store_true", help="no turning sun and no spinning copies")
    parser.add_argument("--out", required=True, help="the scene file to write")
    args = parser.parse_args()
    scene, counts = build(args)
    tmp = args.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")
    os.replace(tmp, args.out)
    print(f"wrote {args.out}: {counts['instances']} instances, {counts['drawn_triangles']} triangles drawn, "
          f"{counts['stored_triangles']} stored")


if __name__ == "__main__":
    main()
